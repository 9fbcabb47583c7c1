//! NumPy's `.npz`: a zip archive of `.npy` arrays (format version 1.0, NEP 1 "A simple file
//! format for NumPy arrays"), stored uncompressed, read by `numpy.load` without pickles. The
//! `.npy` header is a few lines written here; the archive is the `zip` crate's (zip-rs). The
//! crates that write `.npy` (`npyz`, `ndarray-npy`) bring a Python-literal parser for reading
//! headers or the `ndarray` crate, for what is one header line per array.

use std::io::{self, Seek, Write};

use super::Value;

/// The `.npy` bytes of an array with dtype `descr`, Fortran (column-major) order or not,
/// `shape`, and `data`.
fn npy_with(descr: &str, fortran: bool, shape: &[usize], data: &[u8]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let shape = match dims.len() {
        1 => format!("({},)", dims[0]),
        _ => format!("({})", dims.join(", ")),
    };
    let order = if fortran { "True" } else { "False" };
    let mut header =
        format!("{{'descr': '{descr}', 'fortran_order': {order}, 'shape': {shape}, }}");
    // Magic (6), version (2), length (2), header and a newline: a multiple of 64 bytes.
    let total = (10 + header.len() + 1).next_multiple_of(64);
    while 10 + header.len() + 1 < total {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

/// The `.npy` bytes of a column-major array.
fn npy(descr: &str, shape: &[usize], data: &[u8]) -> Vec<u8> {
    npy_with(descr, true, shape, data)
}

/// The `.npy` bytes of `value`.
fn array(value: &Value) -> Vec<u8> {
    match value {
        Value::Matrix { rows, cols, data } => {
            let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
            npy("<f8", &[*rows, *cols], &bytes)
        }
        Value::Complex(v) => {
            let bytes: Vec<u8> = v
                .iter()
                .flat_map(|z| [z.0.to_le_bytes(), z.1.to_le_bytes()].concat())
                .collect();
            npy("<c16", &[v.len()], &bytes)
        }
        Value::Strings(list) => {
            // Fixed-width UTF-32: NumPy's '<U' dtype.
            let width = list
                .iter()
                .map(|s| s.chars().count())
                .max()
                .unwrap_or(0)
                .max(1);
            let mut bytes = Vec::with_capacity(list.len() * width * 4);
            for s in list {
                let mut k = 0;
                for c in s.chars() {
                    bytes.extend_from_slice(&(c as u32).to_le_bytes());
                    k += 1;
                }
                bytes.resize(bytes.len() + 4 * (width - k), 0);
            }
            npy(&format!("<U{width}"), &[list.len()], &bytes)
        }
        Value::Ints(v) => {
            let bytes: Vec<u8> = v.iter().flat_map(|i| i.to_le_bytes()).collect();
            npy("<i8", &[v.len()], &bytes)
        }
        Value::Array { shape, data } => {
            let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
            npy_with("<f8", false, shape, &bytes)
        }
    }
}

/// Write an `.npz` archive holding `variables` (`NAME.npy` each; `numpy.load` gives them back
/// under `NAME`, which may contain `/`) to `out`.
pub fn write<W: Write + Seek, N: AsRef<str>>(out: W, variables: &[(N, Value)]) -> io::Result<W> {
    let mut zip = zip::ZipWriter::new(out);
    for (name, value) in variables {
        let npy = array(value);
        // Zip64 for entries past 4 GiB (a long run's node history can be).
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Stored)
            .large_file(npy.len() as u64 >= u64::from(u32::MAX));
        zip.start_file(format!("{}.npy", name.as_ref()), options)
            .map_err(io::Error::other)?;
        zip.write_all(&npy)?;
    }
    zip.finish().map_err(io::Error::other)
}

/// The bytes of an `.npz` archive holding `variables` (`NAME.npy` each).
pub fn bytes<N: AsRef<str>>(variables: &[(N, Value)]) -> io::Result<Vec<u8>> {
    Ok(write(io::Cursor::new(Vec::new()), variables)?.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_are_aligned_and_spell_the_shape() {
        let b = array(&Value::Matrix {
            rows: 2,
            cols: 3,
            data: vec![0.0; 6],
        });
        let len = u16::from_le_bytes([b[8], b[9]]) as usize;
        assert_eq!((10 + len) % 64, 0);
        let header = std::str::from_utf8(&b[10..10 + len]).unwrap();
        assert!(header.starts_with("{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }"));
        assert!(header.ends_with('\n'));
        assert_eq!(b.len(), 10 + len + 48);
        let s = array(&Value::Strings(vec!["ab".into(), "m/s²".into()]));
        let len = u16::from_le_bytes([s[8], s[9]]) as usize;
        assert!(std::str::from_utf8(&s[10..10 + len])
            .unwrap()
            .contains("'<U4'"));
        assert_eq!(s.len(), 10 + len + 2 * 4 * 4);
        let a = array(&Value::Array {
            shape: vec![2, 3, 4],
            data: vec![0.0; 24],
        });
        let len = u16::from_le_bytes([a[8], a[9]]) as usize;
        assert!(std::str::from_utf8(&a[10..10 + len])
            .unwrap()
            .starts_with("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3, 4), }"));
    }
}

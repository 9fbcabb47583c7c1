//! A MAT-file writer, level 5 (MATLAB 5 to R2006, read by every MATLAB since, Octave and
//! `scipy.io.loadmat`): uncompressed real and complex double matrices and cell columns of
//! strings, from "MATLAB MAT-File Format" (The MathWorks, R2013b), ch. 1. Written here rather
//! than taken from a crate: `matrw` (0.1, one author) pulls binrw, chrono and flate2 for a
//! format whose subset needed is a few tagged elements; `matio-rs` binds a C library.

use super::Value;

const MI_INT8: u32 = 1;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_DOUBLE: u32 = 9;
const MI_MATRIX: u32 = 14;
const MI_INT64: u32 = 12;
const MI_UTF8: u32 = 16;
const MX_CELL: u32 = 1;
const MX_CHAR: u32 = 4;
const MX_DOUBLE: u32 = 6;
const MX_INT64: u32 = 14;
const COMPLEX: u32 = 0x0800;

/// A data element: tag (type, byte count) and data, padded to 8 bytes.
fn element(out: &mut Vec<u8>, kind: u32, data: &[u8]) {
    out.extend_from_slice(&kind.to_le_bytes());
    out.extend_from_slice(&(data.len() as u32).to_le_bytes());
    out.extend_from_slice(data);
    out.resize(out.len().next_multiple_of(8), 0);
}

/// A miMATRIX element of class `class` (with `flags`), dimensions `dims`, name `name` and the
/// sub-elements `body` (already encoded).
fn matrix(out: &mut Vec<u8>, class: u32, flags: u32, dims: &[usize], name: &str, body: &[u8]) {
    let mut m = Vec::new();
    let mut f = Vec::new();
    f.extend_from_slice(&(class | flags).to_le_bytes());
    f.extend_from_slice(&0u32.to_le_bytes());
    element(&mut m, MI_UINT32, &f);
    let d: Vec<u8> = dims
        .iter()
        .flat_map(|&v| (v as i32).to_le_bytes())
        .collect();
    element(&mut m, MI_INT32, &d);
    element(&mut m, MI_INT8, name.as_bytes());
    m.extend_from_slice(body);
    element(out, MI_MATRIX, &m);
}

fn doubles(values: impl Iterator<Item = f64>) -> Vec<u8> {
    values.flat_map(f64::to_le_bytes).collect()
}

/// A 1 × n char array, its data in UTF-8 (`miUTF8`, as `scipy.io.savemat` writes them; MATLAB
/// reads it too): `n` characters, not bytes (`m/s²` is 4 characters in 5 bytes).
fn string(out: &mut Vec<u8>, name: &str, s: &str) {
    let mut body = Vec::new();
    element(&mut body, MI_UTF8, s.as_bytes());
    matrix(out, MX_CHAR, 0, &[1, s.chars().count()], name, &body);
}

/// The variable `name` = `value`.
fn variable(out: &mut Vec<u8>, name: &str, value: &Value) {
    match value {
        Value::Matrix { rows, cols, data } => {
            let mut body = Vec::new();
            element(&mut body, MI_DOUBLE, &doubles(data.iter().copied()));
            matrix(out, MX_DOUBLE, 0, &[*rows, *cols], name, &body);
        }
        Value::Complex(v) => {
            let mut body = Vec::new();
            element(&mut body, MI_DOUBLE, &doubles(v.iter().map(|z| z.0)));
            element(&mut body, MI_DOUBLE, &doubles(v.iter().map(|z| z.1)));
            matrix(out, MX_DOUBLE, COMPLEX, &[v.len(), 1], name, &body);
        }
        Value::Strings(list) => {
            let mut body = Vec::new();
            for s in list {
                string(&mut body, "", s);
            }
            matrix(out, MX_CELL, 0, &[list.len(), 1], name, &body);
        }
        Value::Ints(v) => {
            let mut body = Vec::new();
            let data: Vec<u8> = v.iter().flat_map(|i| i.to_le_bytes()).collect();
            element(&mut body, MI_INT64, &data);
            matrix(out, MX_INT64, 0, &[v.len(), 1], name, &body);
        }
        Value::Array { shape, .. } => {
            let mut body = Vec::new();
            element(
                &mut body,
                MI_DOUBLE,
                &doubles(value.column_major().into_iter()),
            );
            let dims: Vec<usize> = match shape.len() {
                0 => vec![1, 1],
                1 => vec![shape[0], 1],
                _ => shape.clone(),
            };
            matrix(out, MX_DOUBLE, 0, &dims, name, &body);
        }
    }
}

/// The bytes of a MAT-file holding `variables`, with the header text `description`.
pub fn bytes<N: AsRef<str>>(description: &str, variables: &[(N, Value)]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut text = format!("MATLAB 5.0 MAT-file, {description}");
    text.truncate(116);
    let mut header = text.into_bytes();
    header.resize(116, b' ');
    out.extend_from_slice(&header);
    out.extend_from_slice(&[0u8; 8]); // no subsystem data
    out.extend_from_slice(&0x0100u16.to_le_bytes());
    out.extend_from_slice(b"IM");
    for (name, value) in variables {
        variable(&mut out, name.as_ref(), value);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The layout of a 2 × 1 double named `a` as the specification lays it out (regression test
    /// of the byte layout; SciPy reading the files back is the independent check,
    /// crates/flexwing-py/tests/test_linearize.py).
    #[test]
    fn a_matrix_is_laid_out_as_the_specification() {
        let b = bytes("test", &[("a", Value::column(&[1.0, 2.0]))]);
        assert_eq!(b.len() % 8, 0);
        assert_eq!(&b[126..128], b"IM");
        let tag = |at: usize| {
            (
                u32::from_le_bytes(b[at..at + 4].try_into().unwrap()),
                u32::from_le_bytes(b[at + 4..at + 8].try_into().unwrap()),
            )
        };
        // miMATRIX of 16 (flags) + 16 (dims) + 16 (name, padded) + 8 + 16 (data) bytes.
        assert_eq!(tag(128), (MI_MATRIX, 72));
        assert_eq!(tag(136), (MI_UINT32, 8));
        assert_eq!(tag(152), (MI_INT32, 8));
        assert_eq!(tag(168), (MI_INT8, 1));
        assert_eq!(tag(184), (MI_DOUBLE, 16));
        let value = |at: usize| f64::from_le_bytes(b[at..at + 8].try_into().unwrap());
        assert_eq!((value(192), value(200)), (1.0, 2.0));
        assert_eq!(b.len(), 128 + 8 + 72);
    }
}

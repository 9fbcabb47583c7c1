//! Writing result files: atomically (`flexwing_io::atomic`: temporary file in the same directory,
//! then rename), so an interrupted run never leaves a half-written file that looks complete; CSV
//! without non-finite cells; the output folder.

use std::fs;
use std::path::Path;

use anyhow::{anyhow, Context, Result};

/// Write `path` through `write`, which must create the file it is given, atomically
/// (`flexwing_io::write_atomic`); the error names the file.
pub fn write_atomic(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    flexwing_io::write_atomic(path, write)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Write `bytes` to `path` atomically.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<()> {
    Ok(flexwing_io::write_bytes(path, bytes)?)
}

/// Serialize `rows` as CSV (header from the field names) and write it atomically to `path`.
/// A non-finite number (a state that blew up) is written as an empty cell: no `inf` or `NaN`
/// ever reaches a result file.
pub fn write_csv<R: serde::Serialize>(
    path: &Path,
    rows: impl IntoIterator<Item = R>,
) -> Result<()> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for row in rows {
        w.serialize(row)?;
    }
    let bytes = w.into_inner().map_err(|e| anyhow!("{}", e.error()))?;
    write_bytes(path, &finite_cells(bytes)?)
}

/// `csv`, with every cell that reads as a non-finite number emptied.
fn finite_cells(csv: Vec<u8>) -> Result<Vec<u8>> {
    // Every non-finite cell contains "inf" or "NaN": without either anywhere (the rule), the
    // text is returned as it is, in one pass over the bytes instead of a parse that keeps every
    // record (2 million of them, 124 MB, for examples/long_chain.toml's nodes).
    if !csv.windows(3).any(|w| w == b"inf" || w == b"NaN") {
        return Ok(csv);
    }
    let non_finite = |c: &[u8]| matches!(c, b"inf" | b"-inf" | b"NaN" | b"+inf" | b"-NaN");
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(csv.as_slice());
    let mut records = Vec::new();
    let mut any = false;
    for record in r.byte_records() {
        let record = record?;
        any |= record.iter().any(non_finite);
        records.push(record);
    }
    if !any {
        return Ok(csv);
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    for record in &records {
        let cells: Vec<&[u8]> = record
            .iter()
            .map(|c| if non_finite(c) { &b""[..] } else { c })
            .collect();
        w.write_record(cells)?;
    }
    w.into_inner().map_err(|e| anyhow!("{}", e.error()))
}

/// Make `dir` ready for a run, before anything is computed: create it (and its parents), check
/// that it is a writable directory, remove the result files of a previous run (`previous`, file
/// names in `dir`; a folder's contents belong to one run) and, with `status`, write
/// `status.txt: running`, which the run replaces with its status when it ends. A run that is
/// killed leaves `running` behind, never an older run's `complete` beside its own files.
pub fn prepare_dir(dir: &Path, previous: &[&str], status: bool) -> Result<()> {
    if dir.exists() && !dir.is_dir() {
        return Err(anyhow!(
            "the output directory {} is not a directory",
            dir.display()
        ));
    }
    create_dir(dir)?;
    for name in previous {
        match fs::remove_file(dir.join(name)) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(anyhow!(
                    "cannot remove the previous run's {} from the output directory {}: {e}",
                    name,
                    dir.display()
                ))
            }
            _ => {}
        }
    }
    if status {
        write_bytes(&dir.join("status.txt"), b"running\n")
    } else {
        // Probe: the directory must take files.
        let probe = dir.join(format!(".flexwing-probe.{}", std::process::id()));
        fs::write(&probe, b"")
            .and_then(|()| fs::remove_file(&probe))
            .with_context(|| format!("cannot write into the output directory {}", dir.display()))
    }
}

/// Create the output directory (and its parents).
pub fn create_dir(dir: &Path) -> Result<()> {
    fs::create_dir_all(dir)
        .with_context(|| format!("cannot create the output directory {}", dir.display()))
}

/// Numbers in messages and tables: the library's one formatting (`flexwing::text`).
pub use flexwing::text::{short, significant};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_numbers_become_empty_cells() {
        #[derive(serde::Serialize)]
        struct Row {
            name: &'static str,
            a: f64,
            b: f64,
        }
        let mut w = csv::Writer::from_writer(Vec::new());
        for (name, a, b) in [("x", 1.5, f64::INFINITY), ("inf", f64::NAN, -f64::INFINITY)] {
            w.serialize(Row { name, a, b }).unwrap();
        }
        let text = finite_cells(w.into_inner().unwrap()).unwrap();
        // The label "inf" is text, but nothing tells it from the number: it goes too; labels
        // are model names, never "inf".
        assert_eq!(String::from_utf8(text).unwrap(), "name,a,b\nx,1.5,\n,,\n");
    }
}

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

/// Serialize `rows` as CSV (header from the field names) and write it atomically to `path`,
/// non-finite numbers as empty cells (`flexwing_io::csv`).
pub fn write_csv<R: serde::Serialize>(
    path: &Path,
    rows: impl IntoIterator<Item = R>,
) -> Result<()> {
    write_bytes(path, &flexwing_io::csv::bytes(rows)?)
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

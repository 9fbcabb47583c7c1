//! Writing result files atomically: into a temporary file in the same directory, made durable,
//! then renamed over the target, so that an interrupted run never leaves a half-written file
//! that looks complete (POSIX `rename(2)` replaces the target in one step; the temporary's name
//! starts with a dot and ends in `.tmp.EXT`, so nothing takes it for a result).

use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The temporary file beside `path` that [`write_atomic`] writes first: same directory (so the
/// rename is atomic), same extension (some encoders pick the format from it).
pub fn temporary(path: &Path) -> io::Result<PathBuf> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let stem = path
        .file_stem()
        .ok_or_else(|| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("{}: not a file name", path.display()),
            )
        })?
        .to_string_lossy();
    let mut tmp_name = format!(".{stem}.{}.tmp", std::process::id());
    if let Some(ext) = path.extension() {
        tmp_name.push('.');
        tmp_name.push_str(&ext.to_string_lossy());
    }
    Ok(dir.join(tmp_name))
}

/// Write `path` through `write`, which must create the file it is given (the temporary); then
/// make it durable and rename it to `path`. On failure the temporary file is removed and `path`
/// is left as it was.
pub fn write_atomic<E: From<io::Error>>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), E> {
    let tmp = temporary(path)?;
    let result = write(&tmp).and_then(|()| {
        // Make the content durable before the rename makes it visible.
        File::open(&tmp)
            .and_then(|f| f.sync_all())
            .and_then(|()| fs::rename(&tmp, path))
            .map_err(E::from)
    });
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Write `bytes` to `path` atomically; the error names the file.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomic(path, |tmp| {
        let mut f = File::create(tmp)?;
        f.write_all(bytes)
    })
    .map_err(|e: io::Error| {
        io::Error::new(e.kind(), format!("cannot write {}: {e}", path.display()))
    })
}

/// Write `path` atomically through a buffered file (for writers that stream, such as
/// [`crate::npz::write`]); the error names the file.
pub fn write_with(
    path: &Path,
    write: impl FnOnce(io::BufWriter<File>) -> io::Result<io::BufWriter<File>>,
) -> io::Result<()> {
    write_atomic(path, |tmp| {
        let f = write(io::BufWriter::new(File::create(tmp)?))?;
        f.into_inner().map_err(|e| e.into_error())?;
        Ok(())
    })
    .map_err(|e: io::Error| {
        io::Error::new(e.kind(), format!("cannot write {}: {e}", path.display()))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_and_leaves_no_temporary() {
        let dir = std::env::temp_dir().join(format!("flexwing-io-atomic-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.csv");
        write_bytes(&path, b"old").unwrap();
        write_bytes(&path, b"new").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        let failed = write_atomic(&path, |tmp| {
            fs::write(tmp, b"half")?;
            Err(io::Error::other("interrupted"))
        });
        assert!(failed.is_err());
        assert_eq!(fs::read(&path).unwrap(), b"new");
        let names: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
        fs::remove_dir_all(&dir).unwrap();
    }
}

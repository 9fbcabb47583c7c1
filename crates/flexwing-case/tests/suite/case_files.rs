//! Case files that are not files: regression tests of issue 9 ("reading /dev/zero as a case file
//! eats memory without bound; a FIFO blocks").

use flexwing_case::{Case, MAX_CASE_FILE_BYTES};
use std::path::Path;

#[test]
fn devices_directories_and_huge_files_are_refused_at_once() {
    for path in ["/dev/zero", "/dev/null", "/"] {
        if !Path::new(path).exists() {
            continue;
        }
        let e = Case::load(Path::new(path)).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{path}: {e}");
        assert_eq!(e.lines().count(), 1, "{e}");
    }
    let dir = std::env::temp_dir().join(format!("flexwing-case-files-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let big = dir.join("big.toml");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len(MAX_CASE_FILE_BYTES + 1).unwrap();
    let e = Case::load(&big).unwrap_err().to_string();
    assert!(e.contains("at most 16777216 are read"), "{e}");
    // A FIFO with no writer would block a plain read; it is refused before it is opened.
    let fifo = dir.join("fifo.toml");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success());
    if made {
        let e = Case::load(&fifo).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

//! ARCHITECTURE.md's module map is true: it lists every module of every crate's `src/` and of
//! the Python package (test-only modules aside), one line each, and nothing that does not exist.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The workspace root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The source files under `dir`, relative to the workspace root, test-only modules aside.
fn files(dir: &Path, out: &mut BTreeSet<String>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if name != "__pycache__" {
                files(&path, out);
            }
            continue;
        }
        let source = [".rs", ".py", ".pyi"].iter().any(|e| name.ends_with(e));
        let test_only = name == "tests.rs" || name.ends_with("_tests.rs");
        if source && !test_only {
            let relative = path.strip_prefix(root()).unwrap();
            out.insert(relative.to_string_lossy().replace("//", "/"));
        }
    }
}

/// The paths the module map lists: under each `### DIR/` heading, the first word of each line
/// of its code block.
fn listed(text: &str) -> BTreeSet<String> {
    let map = text
        .split("\n## Module map")
        .nth(1)
        .expect("ARCHITECTURE.md has a `## Module map` section");
    let map = map.split("\n## ").next().unwrap_or(map);
    let (mut dir, mut inside, mut out) = (String::new(), false, BTreeSet::new());
    for line in map.lines() {
        if let Some(h) = line.strip_prefix("### ") {
            dir = h.trim().to_string();
        } else if line.starts_with("```") {
            inside = !inside;
        } else if inside {
            if let Some(word) = line.split_whitespace().next() {
                out.insert(format!("{dir}{word}"));
            }
        }
    }
    out
}

#[test]
fn the_module_map_lists_every_module_once() {
    let root = root();
    let text = std::fs::read_to_string(root.join("ARCHITECTURE.md")).unwrap();
    let mut actual = BTreeSet::new();
    for krate in std::fs::read_dir(root.join("crates")).unwrap().flatten() {
        files(&krate.path().join("src"), &mut actual);
    }
    files(
        &root.join("crates/flexwing-py/python/flexwing"),
        &mut actual,
    );
    let listed = listed(&text);
    let missing: Vec<_> = actual.difference(&listed).collect();
    let extra: Vec<_> = listed.difference(&actual).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "ARCHITECTURE.md's module map is out of date: add a line `PATH  what it is` under the \
         crate's heading for {missing:?}; remove {extra:?}"
    );
    // A line per module, each with what it is.
    let map = text.split("\n## Module map").nth(1).unwrap();
    let mut inside = false;
    for line in map.split("\n## ").next().unwrap().lines() {
        if line.starts_with("```") {
            inside = !inside;
        } else if inside {
            assert!(
                line.split_whitespace().count() >= 2,
                "a module line without a description: {line:?}"
            );
        }
    }
}

//! Helpers shared by the integration tests: run the binary, make scratch directories.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Run `flexwing` with `args` in the working directory `cwd`.
pub fn flexwing_in(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexwing"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("the flexwing binary runs")
}

/// Run `flexwing COMMAND CASE --out DIR/OUT EXTRA…` in `dir`.
pub fn run_case(dir: &TempDir, command: &str, case: &Path, out: &str, extra: &[&str]) -> Output {
    let out = dir.path().join(out);
    let mut args = vec![
        command,
        case.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    flexwing_in(dir.path(), &args)
}

/// [`run_case`] with `--json`, asserted successful: its document.
pub fn run_json_case(dir: &TempDir, command: &str, case: &Path, out: &str) -> serde_json::Value {
    let o = run_case(dir, command, case, out, &["--json"]);
    assert_success(&o);
    serde_json::from_str(&stdout(&o)).expect("one JSON document")
}

/// Path of a case file in the workspace's `examples/`.
pub fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// A scratch directory under the system temporary directory, removed on drop.
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn new(label: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!(
            "flexwing-cli-test-{}-{label}-{n}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).expect("create scratch directory");
        Self(path)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }

    /// Write a file into the directory and return its path.
    pub fn write(&self, name: &str, content: &str) -> PathBuf {
        let p = self.0.join(name);
        std::fs::write(&p, content).expect("write scratch file");
        p
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Assert that the run succeeded, showing stderr otherwise.
pub fn assert_success(o: &Output) {
    assert!(
        o.status.success(),
        "flexwing failed with {:?}: {}",
        o.status.code(),
        stderr(o)
    );
}

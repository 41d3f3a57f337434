//! What the CLI tests share: running `lpm` in the workspace root, its
//! output as text, a fresh temporary folder.

#![allow(dead_code)] // each test file uses its own part

use std::path::PathBuf;
use std::process::{Command, Output};

/// The workspace root, where the tests run `lpm` (specs/ is there).
pub const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// Runs `lpm` with `args` in the workspace root.
pub fn lpm<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lpm"))
        .args(args)
        .current_dir(ROOT)
        .output()
        .expect("lpm runs")
}

/// What it printed on stdout.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// What it printed on stderr.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A new folder under the system's temporary folder, named for the test
/// and the process.
pub fn temporary(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lpm-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

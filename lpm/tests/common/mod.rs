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

/// The folder for test `name`'s files: under the build's own temporary
/// folder (`target/tmp`, which `cargo clean` removes), not the system's,
/// and named for the test alone, so that the next run replaces it instead
/// of leaving another beside it. Its path, not yet made.
pub fn scratch(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("lpm-test-{name}"))
}

/// A new, empty folder for test `name` (see [`scratch`]).
pub fn temporary(name: &str) -> PathBuf {
    let dir = scratch(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

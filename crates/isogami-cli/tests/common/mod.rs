//! Helpers shared by the CLI's end-to-end tests: run the built binary, make a scratch folder.
#![allow(dead_code)] // each test binary uses its own subset

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs the `isogami` binary built for these tests with `args`.
pub fn isogami(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_isogami"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// A fresh, empty folder for this test process and `name` (one per test: names are unique
/// within a test binary, and the process id separates binaries).
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("isogami-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

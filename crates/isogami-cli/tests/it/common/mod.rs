//! Helpers shared by the CLI's end-to-end tests: run the built binary, make a scratch folder.
#![allow(dead_code)] // each test binary uses its own subset

use std::process::{Command, Output};
use tempfile::TempDir;

/// Runs the `isogami` binary built for these tests with `args`.
pub fn isogami(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_isogami"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// Runs `isogami` with `args`, which must succeed, and parses what it prints as JSON.
pub fn json(args: &[&str]) -> serde_json::Value {
    let out = isogami(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

/// A fresh, empty folder for one test, named after it, removed with everything in it when the
/// returned guard drops, so a run leaves nothing behind.
pub fn scratch(name: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("isogami-cli-{name}-"))
        .tempdir()
        .expect("temp dir")
}

/// The names of the files in `dir`, sorted.
pub fn entries(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("folder reads")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

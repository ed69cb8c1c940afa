//! Every malformed invocation fails the same way: exactly one line on stderr (`error: …`),
//! nothing on stdout, exit code 2. `--help` and `--version` still print and exit 0.

use crate::common;
use common::{isogami, scratch};

/// Asserts the one-line failure and returns the line.
fn fails_in_one_line(args: &[&str]) -> String {
    let out = isogami(args);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(
        out.stdout.is_empty(),
        "{args:?} printed to stdout: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr:?}");
    assert!(stderr.ends_with('\n'), "{args:?}: {stderr:?}");
    assert!(stderr.starts_with("error: "), "{args:?}: {stderr:?}");
    stderr.trim_end().to_string()
}

const RS: &str = "rotating-squares";

#[test]
fn malformed_invocations_fail_in_one_line_with_exit_2() {
    let cases: &[&[&str]] = &[
        // The command itself.
        &[],
        &["--frobnicate"],
        &["deplyo"],
        &["help", "nope"],
        &["families", "--bogus"],
        &["families", "extra"],
        // cell
        &["cell"],
        &["cell", "--family"],
        &["cell", "--family", "IH999"],
        &["cell", "--family", "IH28", "--params", "x,1"],
        &["cell", "--family", "IH28", "--params", "nan,0.5"],
        &["cell", "--family", "IH28", "--params", "0.1"],
        &["cell", "--family", "IH28", "--cell", "5x1"],
        &["cell", "--family", "IH28", "--cell", "2by1"],
        // analyze
        &["analyze"],
        &["analyze", "--design", RS, "--tol", "abc"],
        &["analyze", "--design", RS, "--tol", "-1"],
        &["analyze", "--design", RS, "--tol", "nan"],
        &["analyze", "--design", "IH28:0.1:1x1:ab"],
        &["analyze", "--design", "{\"family\": \"IH28\""],
        // deploy
        &["deploy"],
        &["deploy", "--design", RS, "--method", "magic"],
        &["deploy", "--design", RS, "--kerf"],
        &["deploy", "--design", RS, "--kerf", "1,5"],
        &["deploy", "--design", RS, "--kerf", "0.5"],
        &["deploy", "--design", RS, "--kerf", "-inf"],
        &["deploy", "--design", RS, "--frame-count", "1"],
        &["deploy", "--design", RS, "--frame-count", "-3"],
        &["deploy", "--design", RS, "--frame-count", "1e3"],
        &[
            "deploy",
            "--design",
            RS,
            "--frame-count",
            "99999999999999999999999",
        ],
        &["deploy", "--design", RS, "--polar-t", "0.5,2"],
        &["deploy", "--design", RS, "--polar-t", ""],
        &["deploy", "--design", RS, "--json", "--json"],
        &["deploy", "--design", "IH28::1x1:ab"],
        // compare, linkages
        &["compare", "--kerf", "inf"],
        &["compare", "--design", "nonsense"],
        &["linkages"],
        &["linkages", "--design", "IH28::1x1:zz"],
        // databases
        &["merge"],
        &["merge", "--into"],
        &["db"],
        &["db", "frobnicate"],
        &["db", "stats", "--bogus"],
    ];
    assert!(cases.len() >= 30);
    for args in cases {
        fails_in_one_line(args);
    }
}

#[test]
fn explore_refuses_bad_flags_before_touching_the_database() {
    let dir_guard = scratch("explore");
    let dir = dir_guard.path();
    let db = dir.join("never.db");
    let db = db.to_str().expect("utf-8 path");
    let base = [
        "explore",
        "--families",
        "IH76",
        "--cells",
        "1x1",
        "--db",
        db,
    ];
    for extra in [
        &["--threshold", "abc"][..],
        &["--threshold", "nan"],
        &["--threshold", "-1"],
        &["--samples", "0"],
        &["--samples", "-1"],
        &["--jobs", "0"],
        &["--jobs", "x"],
        &["--shard", "3/2"],
        &["--shard", "1/0"],
        &["--shard", "half"],
        &["--cells", "9x9"],
        &["--families", "IH0"],
    ] {
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        fails_in_one_line(&args);
        assert!(
            std::fs::read_dir(dir).expect("dir").next().is_none(),
            "{args:?} left a file behind"
        );
    }
}

#[test]
fn usage_errors_name_the_help_to_read() {
    let line = fails_in_one_line(&["deploy", "--design", RS, "--method", "magic"]);
    assert!(
        line.contains("'magic'") && line.contains("--method"),
        "{line}"
    );
    assert!(line.contains("rigid-modes, ncm, springs"), "{line}");
    assert!(line.ends_with("see 'isogami deploy --help'"), "{line}");
    let line = fails_in_one_line(&["db", "stats", "--bogus"]);
    assert!(line.ends_with("see 'isogami db stats --help'"), "{line}");
    let line = fails_in_one_line(&["deplyo"]);
    assert!(
        line.contains("'deplyo'") && line.contains("'deploy'"),
        "{line}"
    );
    assert!(line.ends_with("see 'isogami --help'"), "{line}");
    let line = fails_in_one_line(&[]);
    assert!(
        line.contains("deploy") && line.contains("explore"),
        "{line}"
    );
    let line = fails_in_one_line(&["merge"]);
    assert!(line.contains("--into <INTO>, <SHARDS>..."), "{line}");
}

#[test]
fn help_and_version_print_normally() {
    for args in [
        &["--help"][..],
        &["-h"],
        &["help"],
        &["help", "deploy"],
        &["deploy", "--help"],
        &["db", "stats", "--help"],
        &["db", "help"],
    ] {
        let out = isogami(args);
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("Usage:"), "{args:?}: {text}");
        assert!(text.lines().count() > 3, "{args:?}");
    }
    for flag in ["--version", "-V"] {
        let out = isogami(&[flag]);
        assert_eq!(out.status.code(), Some(0));
        let text = String::from_utf8_lossy(&out.stdout);
        assert_eq!(
            text.trim(),
            format!("isogami {}", env!("CARGO_PKG_VERSION"))
        );
    }
}

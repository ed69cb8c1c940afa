//! The output boundary: no command prints or writes NaN, an infinity, or `null` in place of
//! a number. Runs that diverge (issue 8 §3: springs on IH10 and IH93) must either report
//! finite numbers or refuse with one line naming the offending field, and write no file.

use serde_json::Value;
use std::process::Output;

mod common;
use common::{isogami, scratch};

/// Every number finite (serde_json holds nothing else) and no `null` outside `behaviour`.
fn assert_finite_report(v: &Value, path: &str) {
    match v {
        Value::Null => assert!(path.ends_with(".behaviour"), "null at {path}"),
        Value::Array(items) => {
            for (i, x) in items.iter().enumerate() {
                assert_finite_report(x, &format!("{path}[{i}]"));
            }
        }
        Value::Object(map) => {
            for (k, x) in map {
                assert_finite_report(x, &format!("{path}.{k}"));
            }
        }
        _ => {}
    }
}

/// Either a finite report, or exit 2 with one line that names a non-finite number.
fn finite_or_refused(out: &Output, args: &[&str]) -> Option<Value> {
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        let v: Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
        assert_finite_report(&v, "");
        return Some(v);
    }
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(out.stdout.is_empty(), "{args:?}");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    assert!(stderr.contains("non-finite number"), "{args:?}: {stderr}");
    None
}

#[test]
fn diverging_runs_never_print_nan_or_null() {
    for design in ["IH10::1x1:a--", "IH93::1x1:---"] {
        let args = [
            "deploy", "--design", design, "--method", "springs", "--json",
        ];
        if finite_or_refused(&isogami(&args), &args).is_none() {
            let line = String::from_utf8_lossy(&isogami(&args).stderr).to_string();
            // The message names where the number sits, e.g. `frames[1].measures.area_ratio`.
            assert!(
                line.contains(" is NaN") || line.contains(" is inf"),
                "{line}"
            );
        }
        // The text summary is held to the same rule.
        let text = ["deploy", "--design", design, "--method", "springs"];
        let out = isogami(&text);
        let stdout = String::from_utf8_lossy(&out.stdout);
        if out.status.success() {
            for word in stdout.split_whitespace() {
                let w = word.trim_start_matches(['+', '-']);
                assert!(w != "NaN" && w != "inf", "{text:?}: {stdout}");
            }
        } else {
            assert_eq!(out.status.code(), Some(2));
            assert!(stdout.is_empty());
            assert_eq!(String::from_utf8_lossy(&out.stderr).lines().count(), 1);
        }
    }
}

#[test]
fn report_files_are_checked_like_printed_reports() {
    let dir_guard = scratch("out");
    let dir = dir_guard.path();
    for (design, method) in [
        ("IH93::1x1:---", "springs"),
        ("rotating-squares", "rigid-modes"),
    ] {
        let file = dir.join(format!("{method}.json"));
        let path = file.to_str().expect("utf-8");
        let args = [
            "deploy", "--design", design, "--method", method, "--out", path,
        ];
        let out = isogami(&args);
        if out.status.success() {
            let text = std::fs::read_to_string(&file).expect("report written");
            let v: Value = serde_json::from_str(&text).expect("valid JSON");
            assert_finite_report(&v, "");
            // The file holds what --json prints.
            let printed = isogami(&["deploy", "--design", design, "--method", method, "--json"]);
            assert_eq!(
                serde_json::from_slice::<Value>(&printed.stdout).expect("valid JSON"),
                v
            );
        } else {
            assert_eq!(out.status.code(), Some(2), "{args:?}");
            assert_eq!(String::from_utf8_lossy(&out.stderr).lines().count(), 1);
            assert!(
                !file.exists(),
                "{args:?} wrote a report with non-finite numbers"
            );
        }
    }
    // Rotating squares deploys cleanly, so at least that file exists.
    assert!(dir.join("rigid-modes.json").exists());
}

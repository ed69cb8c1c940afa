//! The output boundary: no command prints or writes NaN, an infinity, or `null` in place of
//! a number. Runs that diverge (issue 8 §3: springs on IH10 and IH93) must either report
//! finite numbers or refuse with one line naming the offending field, and write no file.

use serde_json::Value;
use std::process::Output;

use crate::common;
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

/// What a refused command must look like: exit 2, one line on stderr, no panic.
fn refused(out: &Output, what: &str) -> String {
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{what}: {err}");
    assert_eq!(err.trim().lines().count(), 1, "{what}: {err}");
    assert!(!err.contains("panicked"), "{what}: {err}");
    err
}

/// `path`'s kind as `stat` would name it, without following a link.
fn kind(path: &std::path::Path) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let t = std::fs::symlink_metadata(path).unwrap().file_type();
    if t.is_symlink() {
        "symlink"
    } else if t.is_char_device() {
        "char device"
    } else if t.is_fifo() {
        "fifo"
    } else if t.is_dir() {
        "folder"
    } else {
        "file"
    }
}

const EXPORT: [&str; 7] = [
    "export",
    "--design",
    "rotating-squares",
    "--format",
    "tiles-csv",
    "--patch",
    "1x1",
];

fn export_to(out: &std::path::Path) -> Output {
    let mut args: Vec<&str> = EXPORT.to_vec();
    args.extend(["--out", out.to_str().unwrap()]);
    isogami(&args)
}

#[test]
fn outputs_write_through_devices_and_fifos_and_follow_links() {
    let dir = scratch("out-kinds");
    let d = dir.path();
    // A character device of our own where we may make one (root, as CI runs), and always
    // /dev/null through a link: written through, never replaced by a regular file.
    let node = d.join("dev1");
    let made = std::process::Command::new("mknod")
        .args([node.to_str().unwrap(), "c", "1", "3"])
        .status()
        .is_ok_and(|s| s.success());
    if made {
        assert!(export_to(&node).status.success());
        assert_eq!(kind(&node), "char device");
    }
    let null = d.join("null-link");
    std::os::unix::fs::symlink("/dev/null", &null).unwrap();
    let out = export_to(&null);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(kind(&null), "symlink");
    assert_eq!(kind(std::path::Path::new("/dev/null")), "char device");

    // A FIFO: its reader gets the file whole; it stays a FIFO.
    let fifo = d.join("pipe");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    assert!(export_to(&fifo).status.success());
    let got = reader.join().unwrap();
    let plain = d.join("plain.csv");
    assert!(export_to(&plain).status.success());
    assert_eq!(got, std::fs::read(&plain).unwrap());
    assert_eq!(kind(&fifo), "fifo");

    // A link to a file: the file is written, the link stays a link.
    let target = d.join("target.csv");
    std::fs::write(&target, "old").unwrap();
    let link = d.join("link.csv");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    assert!(export_to(&link).status.success());
    assert_eq!(kind(&link), "symlink");
    assert_eq!(
        std::fs::read(&target).unwrap(),
        std::fs::read(&plain).unwrap()
    );

    // A link to nothing, a folder: refused in one line, nothing made.
    let dangling = d.join("dangling");
    std::os::unix::fs::symlink(d.join("missing"), &dangling).unwrap();
    refused(&export_to(&dangling), "dangling link");
    assert!(!d.join("missing").exists());
    refused(&export_to(d), "a folder");
    let names: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert!(
        names.iter().all(|n| !n.starts_with('.')),
        "temporary files left: {names:?}"
    );
}

#[test]
fn a_command_with_several_outputs_writes_all_or_none() {
    let dir = scratch("out-all-or-none");
    let d = dir.path();
    std::fs::write(d.join("afile"), "mine").unwrap();
    let p = |name: &str| d.join(name).to_str().unwrap().to_string();
    let (frames, gif, out) = (p("fr"), p("fr.gif"), p("afile/x.json"));
    let run = isogami(&[
        "deploy",
        "--design",
        "rotating-squares",
        "--frame-count",
        "3",
        "--frames",
        &frames,
        "--gif",
        &gif,
        "--out",
        &out,
    ]);
    refused(&run, "deploy into afile/");
    let mut names: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["afile"], "nothing but what was there");
    assert_eq!(std::fs::read(d.join("afile")).unwrap(), b"mine");

    // A folder format whose folder holds a folder where a file goes: none of its files.
    let ks = d.join("ks");
    std::fs::create_dir_all(ks.join("hull_tiles.txt")).unwrap();
    let run = isogami(&[
        "export",
        "--design",
        "rotating-squares",
        "--format",
        "kirigami-sim",
        "--patch",
        "2x2",
        "--out",
        ks.to_str().unwrap(),
    ]);
    refused(&run, "kirigami-sim over a folder");
    let inside: Vec<_> = std::fs::read_dir(&ks)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(inside, ["hull_tiles.txt"]);

    // The same with good destinations writes every one of them.
    let run = isogami(&[
        "deploy",
        "--design",
        "rotating-squares",
        "--frame-count",
        "3",
        "--frames",
        &frames,
        "--gif",
        &gif,
        "--out",
        &p("x.json"),
    ]);
    assert!(run.status.success());
    assert_eq!(std::fs::read_dir(d.join("fr")).unwrap().count(), 3);
    assert!(d.join("fr.gif").is_file() && d.join("x.json").is_file());
}

#[test]
fn a_full_stdout_ends_in_one_line_and_exit_2() {
    let dir = scratch("out-full");
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap()
    };
    let out_csv = dir.path().join("a.csv");
    let commands: Vec<Vec<&str>> = vec![
        [EXPORT.as_slice(), &["--out", out_csv.to_str().unwrap()]].concat(),
        vec!["deploy", "--design", "rotating-squares"],
        vec!["analyze", "--design", "rotating-squares"],
        vec!["families"],
    ];
    for args in commands {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_isogami"))
            .args(&args)
            .stdout(full())
            .output()
            .unwrap();
        let err = refused(&out, &args.join(" "));
        assert!(err.contains("stdout"), "{args:?}: {err}");
    }
}

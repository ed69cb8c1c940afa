//! Inputs that used to cost the command line its memory, its stack, minutes of work or its
//! words (issue 42): each is refused at once in one line with exit code 2, and nothing is
//! written.

use crate::common;

use common::{entries as listing, isogami, scratch};
use std::path::Path;
use std::time::{Duration, Instant};

/// `args` fails with exit code 2 and one line on stderr that says `needle`, within `within`
/// (generous: the point is "before the work", which took minutes).
fn refused(args: &[&str], needle: &str, within: Duration) -> String {
    let started = Instant::now();
    let out = isogami(args);
    let took = started.elapsed();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    assert!(
        err.contains(needle),
        "{args:?}: {err:?} does not say {needle:?}"
    );
    assert!(took < within, "{args:?} took {took:?}");
    err
}

/// `--target @/dev/zero` and `export --sheet /dev/zero` read until memory ran out; a FIFO
/// with no writer blocked forever; 25,000 nested groups aborted the process (exit 134).
#[test]
fn devices_fifos_and_deep_svgs_are_refused_unread() {
    let dir = scratch("hostile-reads");
    let fifo = dir.path().join("outline.svg");
    assert!(std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let deep = dir.path().join("deep.svg");
    let n = 25_000;
    std::fs::write(
        &deep,
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg">{}<circle r="3"/>{}</svg>"#,
            "<g>".repeat(n),
            "</g>".repeat(n)
        ),
    )
    .unwrap();
    let out = dir.path().join("sheet.json");
    let at = |p: &Path| format!("@{}", p.display());
    let minute = Duration::from_secs(60);
    for (target, needle) in [
        (
            "@/dev/zero".to_string(),
            "character device, not a regular file",
        ),
        (at(&fifo), "FIFO, not a regular file"),
        (at(&deep), "deeper than 256 levels"),
    ] {
        refused(
            &[
                "graded",
                "--design",
                "rotating-squares",
                "--region",
                "2x2",
                "--target",
                &target,
                "--out",
                out.to_str().unwrap(),
            ],
            needle,
            minute,
        );
    }
    let svg_out = dir.path().join("x.svg");
    for sheet in ["/dev/zero", fifo.to_str().unwrap()] {
        refused(
            &[
                "export",
                "--sheet",
                sheet,
                "--format",
                "svg",
                "--out",
                svg_out.to_str().unwrap(),
            ],
            "not a regular file",
            minute,
        );
    }
    assert_eq!(listing(dir.path()), ["deep.svg", "outline.svg"]);
}

/// `graded --out EXISTING_DIR` and `export --out DIR` refused only after the whole
/// computation (minutes for a 13×13 sheet). Now before it: a 13×13 sheet at 2,000
/// iterations is refused in well under the time it takes.
#[test]
fn a_bad_destination_is_refused_before_the_work() {
    let dir = scratch("hostile-out");
    let folder = dir.path().to_str().unwrap();
    let minute = Duration::from_secs(60);
    refused(
        &[
            "graded",
            "--design",
            "rotating-squares",
            "--region",
            "13x13",
            "--iterations",
            "2000",
            "--out",
            folder,
        ],
        "is a folder",
        minute,
    );
    refused(
        &[
            "export",
            "--design",
            "rotating-squares",
            "--patch",
            "30x30",
            "--format",
            "svg",
            "--out",
            folder,
        ],
        "is a folder, expected a file",
        minute,
    );
    let missing = dir.path().join("no/such/folder/sheet.json");
    refused(
        &[
            "graded",
            "--design",
            "rotating-squares",
            "--region",
            "13x13",
            "--out",
            missing.to_str().unwrap(),
        ],
        "does not exist",
        minute,
    );
    assert!(listing(dir.path()).is_empty());
}

/// A run killed between writing its temporary file and renaming it (SIGKILL) left
/// `.NAME.tmpPID-0` beside the destination forever. The next write of that destination
/// removes the temporary files of processes that are gone, and leaves alone those of a
/// running process and every other file.
#[test]
fn temporary_files_of_killed_runs_are_removed_by_the_next_write() {
    let dir = scratch("stale-temps");
    let out = dir.path().join("cell.svg");
    // A process id that is not running: one past the largest the kernel hands out is never
    // one; fall back to a large number.
    let max = std::fs::read_to_string("/proc/sys/kernel/pid_max")
        .ok()
        .and_then(|t| t.trim().parse::<u64>().ok())
        .unwrap_or(4_194_304);
    let dead = max + 1;
    let alive = std::process::id();
    let names = [
        format!(".cell.svg.tmp{dead}-0"),
        format!(".cell.svg.tmp{dead}-3"),
        format!(".cell.svg.tmp{alive}-0"),
        ".cell.svg.tmpnotapid-0".to_string(),
        format!(".other.svg.tmp{dead}-0"),
        "cell.svg.bak".to_string(),
    ];
    for name in &names {
        std::fs::write(dir.path().join(name), b"partial").unwrap();
    }
    let ok = isogami(&["cell", "--family", "IH28", "--svg", out.to_str().unwrap()]);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let mut kept: Vec<String> = names[2..].to_vec();
    kept.push("cell.svg".into());
    kept.sort();
    assert_eq!(listing(dir.path()), kept);
}

/// One-line errors echoed whole inputs (a 100,000-digit number, a 5,000-character path); they are
/// cut to their first characters and their length.
#[test]
fn long_inputs_are_cut_in_messages() {
    // The kernel takes one argument of at most 128 KiB.
    let number = "1".repeat(100_000) + "x";
    let err = refused(
        &["deploy", "--design", "rotating-squares", "--kerf", &number],
        "characters)",
        Duration::from_secs(60),
    );
    assert!(err.len() < 400, "{} bytes: {}", err.len(), &err[..400]);
    let dir = scratch("long-path");
    let long = dir.path().join("d/".repeat(2_500)).join("sheet.json");
    let err = refused(
        &[
            "graded",
            "--design",
            "rotating-squares",
            "--out",
            long.to_str().unwrap(),
        ],
        "characters)",
        Duration::from_secs(60),
    );
    assert!(err.len() < 400, "{} bytes: {err}", err.len());
}

/// Numbers at the edge of the floating point: a polygon of 1e308 mm was "49 tiles", a disc of
/// 1e308 mm "holds no tile", an ellipse of axes 1 and 1e-300 was refused as JSON it was not
/// asked to write. Each is refused for what it is.
#[test]
fn huge_and_tiny_numbers_are_refused_for_what_they_are() {
    let minute = Duration::from_secs(60);
    let sheet = |region: &str| {
        vec![
            "sheet".to_string(),
            "--design".into(),
            "rotating-squares".into(),
            "--region".into(),
            region.into(),
        ]
    };
    for (region, needle) in [
        ("polygon:0,0;1e308,0;0,1e308", "overflows"),
        ("disc:1e308", "cells; at most 160 fit"),
        ("rect:1e300,1e300", "cells; at most 160 fit"),
    ] {
        let args = sheet(region);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let err = refused(&args, needle, minute);
        assert!(err.len() < 200, "{err}");
    }
    for (target, needle) in [
        ("ellipse:1,1e-300", "longer than wide"),
        ("ellipse:1e300,1", "longer than wide"),
        ("polygon:0,0;1e308,0;0,1e308", "overflows"),
    ] {
        refused(
            &[
                "graded",
                "--design",
                "rotating-squares",
                "--region",
                "2x2",
                "--target",
                target,
            ],
            needle,
            minute,
        );
    }
}

/// `graded --region 50x50` said "1..=40" while `65x1` said "at most 64 each way": every
/// region too large, or empty, is refused with the same words and the same limit as a
/// finite sheet's.
#[test]
fn region_limits_speak_with_one_voice() {
    let minute = Duration::from_secs(60);
    let mut said = Vec::new();
    for region in ["50x50", "65x1", "1x41", "0x3"] {
        for command in ["graded", "sheet"] {
            let err = refused(
                &[command, "--design", "rotating-squares", "--region", region],
                "rows and columns must be 1..=40",
                minute,
            );
            said.push(err);
        }
    }
    assert_eq!(said.len(), 8);
}

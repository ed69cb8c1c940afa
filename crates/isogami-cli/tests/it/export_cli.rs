//! `isogami export` end to end: every format writes its file(s) and they parse; bad values
//! fail in one line with exit code 2 and leave no file (nor a temporary one) behind.

use std::path::Path;

use crate::common;
use common::{entries, isogami, scratch};

const IH22: &str = "IH22:0.1312,0.2611,0.4191:1x1:aa-a-";

#[test]
fn every_format_writes_a_file_that_parses() {
    let dir_guard = scratch("formats");
    let dir = dir_guard.path();
    let out = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let run = |format: &str, file: &str, extra: &[&str]| {
        let target = out(file);
        // The rectangle as it is (--raw): the counts below are whole cells.
        let mut args = vec![
            "export", "--design", IH22, "--format", format, "--out", &target, "--raw",
        ];
        args.extend_from_slice(extra);
        let o = isogami(&args);
        assert!(
            o.status.success(),
            "{format}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(String::from_utf8_lossy(&o.stdout).starts_with("wrote "));
    };
    run(
        "fold",
        "a.fold",
        &["--patch", "2x3", "--t", "open", "--frames", "5"],
    );
    let fold: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("a.fold")).unwrap()).unwrap();
    assert_eq!(fold["frame_unit"], "mm");
    assert_eq!(fold["file_frames"].as_array().unwrap().len(), 5);
    let faces = fold["faces_vertices"].as_array().unwrap().len();
    assert!(
        faces > 0 && faces.is_multiple_of(6),
        "2x3 cells of whole cells"
    );

    run("obj", "a.obj", &["--patch", "2x3", "--width-mm", "120"]);
    let obj = std::fs::read_to_string(dir.join("a.obj")).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("o ")).count(), faces);

    run("tiles-csv", "a.csv", &["--patch", "2x3", "--edge-mm", "10"]);
    let csv = std::fs::read_to_string(dir.join("a.csv")).unwrap();
    assert_eq!(csv.lines().count(), faces + 1);
    assert!(csv.starts_with("id,cell_i,cell_j,tile,"));

    run("tiles-json", "a.json", &["--patch", "2x3", "--t", "0.5"]);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("a.json")).unwrap()).unwrap();
    assert_eq!(json["tiles"].as_array().unwrap().len(), faces);
    assert_eq!(json["unit"], "mm");

    run("kirigami-sim", "sim", &["--patch", "2x3"]);
    assert_eq!(
        entries(&dir.join("sim")),
        [
            "constraints.txt",
            "hull_tiles.txt",
            "hull_vertices.txt",
            "vertices.txt"
        ]
    );
    let vertices = std::fs::read_to_string(dir.join("sim/vertices.txt")).unwrap();
    assert_eq!(vertices.lines().count(), faces);
    assert_eq!(
        entries(dir),
        ["a.csv", "a.fold", "a.json", "a.obj", "sim"],
        "no temporary files left"
    );
}

const IH44: &str = "IH44:0.5,0.027564102564:1x2:-aaabbaa";

/// The tiles of a tiles-json file as (cell, tile).
fn tile_keys(path: &Path) -> Vec<(i64, i64, i64)> {
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    keys_of(&json)
}

/// The `tiles` of a tiles-json file or of a finite sheet's JSON as (cell, tile).
fn keys_of(json: &serde_json::Value) -> Vec<(i64, i64, i64)> {
    json["tiles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| {
            let cell = &t["cell"];
            (
                cell[0].as_i64().unwrap(),
                cell[1].as_i64().unwrap(),
                t["tile"].as_i64().unwrap(),
            )
        })
        .collect()
}

#[test]
fn export_writes_the_completed_sheet_unless_raw() {
    let dir_guard = scratch("complete");
    let dir = dir_guard.path();
    let path = |name: &str| dir.join(name).to_string_lossy().into_owned();
    let (done, raw) = (path("done.json"), path("raw.json"));
    let common = ["export", "--design", IH44, "--format", "tiles-json"];
    let o = isogami(&[&common[..], &["--patch", "4x4", "--out", &done]].concat());
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("one-DOF completion"), "{stdout}");
    assert!(o.stderr.is_empty(), "a one-DOF sheet has no warning");
    let o = isogami(&[&common[..], &["--patch", "4x4", "--out", &raw, "--raw"]].concat());
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(stdout.contains("raw rectangle"), "{stdout}");
    assert!(stderr.contains("degrees of freedom"), "{stderr}");
    // The raw file is the 4x4 rectangle; the completed one differs from it (IH44 4x4 flops
    // at its boundary) and holds ring tiles outside the rectangle's cells.
    let (done, raw) = (tile_keys(Path::new(&done)), tile_keys(Path::new(&raw)));
    assert!(raw
        .iter()
        .all(|&(i, j, _)| (0..4).contains(&i) && (0..4).contains(&j)));
    assert_ne!(done, raw);
    assert!(done
        .iter()
        .any(|&(i, j, _)| !(0..4).contains(&i) || !(0..4).contains(&j)));
    // No one-DOF sheet: refused in one line naming --raw; --raw writes the rectangle.
    let iso = [
        "export",
        "--design",
        "IH10::2x2:--a--aa-a-bb",
        "--format",
        "obj",
    ];
    let o = isogami(&[&iso[..], &["--out", &path("iso.obj")]].concat());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("no one-DOF sheet") && stderr.contains("--raw"),
        "{stderr}"
    );
    assert!(!dir.join("iso.obj").exists());
    let o = isogami(&[&iso[..], &["--out", &path("iso.obj"), "--raw"]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // --complete (the default, kept for old scripts) and --raw contradict each other.
    let o = isogami(&[&iso[..], &["--out", &path("x.obj"), "--raw", "--complete"]].concat());
    assert_eq!(o.status.code(), Some(2));
}

/// `--region` reads every region `sheet --region` reads, and writes the sheet `sheet`
/// completes (the same tiles), or the same raw region with --raw; where `sheet` refuses the
/// completion, the export refuses it too and writes nothing.
#[test]
fn a_region_exports_the_sheet_that_sheet_makes() {
    let dir_guard = scratch("region");
    let dir = dir_guard.path();
    let out = dir.join("r.json");
    let out_arg = out.to_string_lossy().into_owned();
    let keys = |v: &serde_json::Value| {
        let mut k = keys_of(v);
        k.sort();
        k
    };
    let (mut written, mut refused) = (0, 0);
    for region in ["3x5", "disc:70", "rect:90,60", "polygon:0,0;100,0;0,80"] {
        for raw in [false, true] {
            let flag: &[&str] = if raw { &["--raw"] } else { &[] };
            let sheet = isogami(
                &[
                    &["sheet", "--design", IH44, "--region", region, "--json"][..],
                    flag,
                ]
                .concat(),
            );
            let o = isogami(
                &[
                    &["export", "--design", IH44, "--format", "tiles-json"][..],
                    &["--region", region, "--out", &out_arg],
                    flag,
                ]
                .concat(),
            );
            let stderr = String::from_utf8_lossy(&o.stderr);
            if !sheet.status.success() {
                assert_eq!(o.status.code(), Some(2), "{region}: {stderr}");
                assert!(stderr.contains("no one-DOF sheet"), "{region}: {stderr}");
                assert!(!out.exists(), "{region}: a refused export wrote a file");
                refused += 1;
                continue;
            }
            assert!(o.status.success(), "{region} raw={raw}: {stderr}");
            let v: serde_json::Value = serde_json::from_slice(&sheet.stdout).unwrap();
            let sheet = if raw {
                &v["raw"]
            } else {
                &v["completion"]["sheet"]
            };
            let file: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
            assert_eq!(keys(&file), keys(sheet), "{region} raw={raw}");
            std::fs::remove_file(&out).unwrap();
            written += 1;
        }
    }
    assert!(written >= 6, "{written} regions written, {refused} refused");
}

#[test]
fn bad_values_fail_in_one_line_and_write_nothing() {
    let dir_guard = scratch("errors");
    let dir = dir_guard.path();
    let target = dir.join("out.fold").to_string_lossy().into_owned();
    let cases: &[&[&str]] = &[
        &["--patch", "0x3"],
        &["--patch", "41x2"],
        &["--patch", "6by6"],
        &["--patch", "x"],
        &["--edge-mm", "0"],
        &["--edge-mm", "-5"],
        &["--edge-mm", "nan"],
        &["--width-mm", "-1"],
        &["--width-mm", "inf"],
        &["--edge-mm", "10", "--width-mm", "100"],
        &["--region", "disc:40", "--width-mm", "100"],
        &["--region", "disc:-1"],
        &["--region", "0x3"],
        &["--region", "polygon:0,0;1,1"],
        &["--region", "4x4", "--patch", "4x4"],
        &["--t", "1.5"],
        &["--t", "-0.1"],
        &["--t", "nan"],
        &["--t", "half"],
        &["--kerf", "0"],
        &["--kerf", "0.9"],
        &["--frames", "1"],
        &["--frames", "101"],
        &["--format", "pdf"],
        &["--design", "IH999::1x1:a"],
    ];
    for extra in cases {
        let mut args = vec!["export", "--out", &target];
        if !extra.contains(&"--format") {
            args.extend_from_slice(&["--format", "fold"]);
        }
        if !extra.contains(&"--design") {
            args.extend_from_slice(&["--design", "rotating-squares"]);
        }
        args.extend_from_slice(extra);
        let o = isogami(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {stderr}");
        assert!(o.stdout.is_empty(), "{extra:?}");
        assert_eq!(stderr.lines().count(), 1, "{extra:?}: {stderr}");
        assert!(stderr.starts_with("error: "), "{extra:?}: {stderr}");
        assert!(entries(dir).is_empty(), "{extra:?} left {:?}", entries(dir));
    }
}

#[test]
fn out_of_the_wrong_kind_is_refused() {
    let dir_guard = scratch("kinds");
    let dir = dir_guard.path();
    let folder = dir.to_string_lossy().into_owned();
    let o = isogami(&[
        "export",
        "--design",
        "rotating-squares",
        "--format",
        "obj",
        "--out",
        &folder,
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is a folder"));
    let file = dir.join("f.txt");
    std::fs::write(&file, "keep").unwrap();
    let file_arg = file.to_string_lossy().into_owned();
    let o = isogami(&[
        "export",
        "--design",
        "rotating-squares",
        "--format",
        "kirigami-sim",
        "--out",
        &file_arg,
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep");
    assert_eq!(entries(dir), ["f.txt"]);
}

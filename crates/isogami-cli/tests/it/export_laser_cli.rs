//! `isogami export --format svg|dxf` end to end: files written with the asked settings in
//! their metadata, a material preset overridden by a flag, bad values refused in one line
//! (exit 2) with no file left behind.

use crate::common;
use common::{isogami, scratch};

#[test]
fn svg_and_dxf_carry_the_preset_and_the_overrides() {
    let dir_guard = scratch("ok");
    let dir = dir_guard.path();
    let svg = dir.join("s.svg").to_string_lossy().into_owned();
    let base = ["export", "--design", "rotating-squares", "--patch", "2x2"];
    let out = isogami(
        &[
            &base[..],
            &[
                "--format",
                "svg",
                "--out",
                &svg,
                "--material",
                "card",
                "--hinge-mm",
                "1.2",
                "--labels",
            ],
        ]
        .concat(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    for needle in [
        "hinge_mm: 1.2",
        "kerf_mm: 0.1",
        "thickness_mm: 0.3",
        "material: card",
        "width=\"",
        "mm\"",
        "<text",
    ] {
        assert!(text.contains(needle), "svg lacks {needle}");
    }
    let dxf = dir.join("s.dxf").to_string_lossy().into_owned();
    let out = isogami(
        &[
            &base[..],
            &["--format", "dxf", "--out", &dxf, "--cut-colour", "#ff0000"],
        ]
        .concat(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let drawing = dxf::Drawing::load_file(&dxf).unwrap();
    let cut = drawing.layers().find(|l| l.name == "CUT").unwrap();
    assert_eq!(cut.color.index(), Some(1), "red cut layer");
    assert!(drawing.entities().count() > 8);
}

#[test]
fn bad_laser_values_leave_no_file() {
    let dir_guard = scratch("bad");
    let dir = dir_guard.path();
    let target = dir.join("x.svg").to_string_lossy().into_owned();
    for extra in [
        &["--hinge-mm", "25"][..],
        &["--hinge-mm", "0"],
        &["--kerf-mm", "-0.2"],
        &["--kerf-mm", "nan"],
        &["--material", "oak"],
        &["--cut-colour", "black"],
    ] {
        let args = [
            &[
                "export",
                "--design",
                "rotating-squares",
                "--patch",
                "2x2",
                "--format",
                "svg",
                "--out",
                &target,
            ][..],
            extra,
        ]
        .concat();
        let out = isogami(&args);
        assert_eq!(out.status.code(), Some(2), "{extra:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{extra:?}: {err}");
        assert_eq!(
            std::fs::read_dir(dir).unwrap().count(),
            0,
            "{extra:?} left a file"
        );
    }
}

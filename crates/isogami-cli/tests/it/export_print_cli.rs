//! `isogami export --format stl|3mf` end to end: the files carry the asked print settings
//! (3MF metadata, STL size and header); the shared --hinge-mm and --thickness-mm reach the
//! print settings; bad values fail in one line (exit 2) and leave no file behind.

use crate::common;
use common::{isogami, scratch};
use std::io::Read;

fn export(args: &[&str]) -> std::process::Output {
    let base = ["export", "--design", "rotating-squares", "--patch", "2x2"];
    isogami(&[&base[..], args].concat())
}

#[test]
fn stl_and_3mf_carry_the_asked_settings() {
    let dir_guard = scratch("print-ok");
    let dir = dir_guard.path();
    let mf = dir.join("s.3mf").to_string_lossy().into_owned();
    let out = export(&[
        "--format",
        "3mf",
        "--out",
        &mf,
        "--hinge-mm",
        "1.1",
        "--thickness-mm",
        "3",
        "--gap-mm",
        "0.3",
        "--lamella-mm",
        "0.5",
        "--nozzle-mm",
        "0.25",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut zip = zip::ZipArchive::new(std::fs::File::open(&mf).unwrap()).unwrap();
    let mut model = String::new();
    zip.by_name("3D/3dmodel.model")
        .unwrap()
        .read_to_string(&mut model)
        .unwrap();
    for needle in [
        "unit=\"millimeter\"",
        "hinge_mm: 1.1",
        "thickness_mm: 3",
        "gap_mm: 0.3",
        "lamella_mm: 0.5",
        "nozzle_mm: 0.25",
        "IH76",
    ] {
        assert!(model.contains(needle), "3mf lacks {needle}");
    }
    // The laser defaults do not leak into the print: without flags the print defaults hold.
    let stl = dir.join("s.stl").to_string_lossy().into_owned();
    let out = export(&["--format", "stl", "--out", &stl, "--material", "felt"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&stl).unwrap();
    assert!(bytes.starts_with(b"isogami binary STL, units mm: IH76"));
    let n = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert!(n > 0 && bytes.len() == 84 + 50 * n);
    let z_max = (0..n)
        .flat_map(|t| (0..3).map(move |k| 84 + 50 * t + 12 + 12 * k + 8))
        .map(|at| f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()))
        .fold(f32::MIN, f32::max);
    assert_eq!(z_max, 2.0, "default print thickness");
}

#[test]
fn bad_print_values_leave_no_file() {
    let dir_guard = scratch("print-bad");
    let dir = dir_guard.path();
    for format in ["stl", "3mf"] {
        let target = dir
            .join(format!("x.{format}"))
            .to_string_lossy()
            .into_owned();
        for (extra, needle) in [
            (&["--hinge-mm", "0.3"][..], "nozzle"),
            (&["--hinge-mm", "21"], "does not fit"),
            // Fits on its 20 mm edge, but reaches another joint's hinge.
            (&["--hinge-mm", "19"], "comes within the gap"),
            (&["--gap-mm", "0"], "gap_mm"),
            (&["--lamella-mm", "-0.4"], "lamella_mm"),
            (&["--thickness-mm", "inf"], "thickness_mm"),
            (&["--lamella-mm", "2.5"], "thinner"),
            (&["--gap-mm", "25"], "too wide"),
        ] {
            let out = export(&[&["--format", format, "--out", &target][..], extra].concat());
            assert_eq!(out.status.code(), Some(2), "{extra:?}");
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(err.trim().lines().count(), 1, "{extra:?}: {err}");
            assert!(err.contains(needle), "{extra:?}: {err}");
            assert_eq!(
                std::fs::read_dir(dir).unwrap().count(),
                0,
                "{extra:?} left a file"
            );
        }
    }
}

//! `isogami graded --target @FILE.svg`: an outline drawn in an SVG file grades a sheet as
//! the same outline typed in does; a bad or missing file is refused in one line with exit
//! code 2 and nothing written.

use crate::common;

use common::{isogami, json, scratch};

/// The run's JSON for a 2×2-cell rotating-squares sheet towards `target`, 60 iterations.
fn graded(target: &str) -> serde_json::Value {
    json(&[
        "graded",
        "--design",
        "rotating-squares",
        "--region",
        "2x2",
        "--target",
        target,
        "--iterations",
        "60",
        "--allow-failed",
        "--json",
    ])
}

/// A rhombus drawn in SVG — tall and narrow in a y-down file, turned a quarter turn by its
/// group, offset and scaled — is the rhombus `polygon:0,-1;1.3,0;0,1;-1.3,0`: the run's
/// target outline has its four corners, wide along x, and the fit is the typed outline's.
#[test]
fn an_svg_outline_grades_like_the_same_outline_typed_in() {
    let dir = scratch("graded-svg");
    let file = dir.path().join("rhombus.svg");
    std::fs::write(
        &file,
        r#"<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="120mm" height="120mm" viewBox="0 0 120 120">
  <title>target</title>
  <g transform="translate(60 60) rotate(90) scale(20)">
    <path id="outline" d="M 0 -1.3 l 1 1.3 L 0 1.3 l -1 -1.3 z"/>
  </g>
</svg>
"#,
    )
    .unwrap();
    let from_svg = graded(&format!("@{}", file.display()));
    let typed = graded("polygon:0,-1;1.3,0;0,1;-1.3,0");
    assert_eq!(from_svg["sheet"]["tiles"].as_array().unwrap().len(), 16);
    let corners = |v: &serde_json::Value| -> Vec<(f64, f64)> {
        v["report"]["target"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
            .collect()
    };
    let (svg, text) = (corners(&from_svg), corners(&typed));
    assert_eq!(svg.len(), 4, "{svg:?}");
    let width = |c: &[(f64, f64)]| c.iter().map(|p| p.0.abs()).fold(0.0, f64::max);
    let height = |c: &[(f64, f64)]| c.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    assert!(
        (width(&svg) / height(&svg) - 1.3).abs() < 1e-9,
        "wide along x: {svg:?}"
    );
    // The same corners as the typed rhombus (in some order), so the same fit.
    for p in &text {
        let nearest = svg
            .iter()
            .map(|q| (q.0 - p.0).hypot(q.1 - p.1))
            .fold(f64::MAX, f64::min);
        assert!(nearest < 1e-9 * width(&text), "{p:?} not in {svg:?}");
    }
    for key in ["max_outline_error", "median_outline_error", "joint_gap"] {
        let (a, b) = (
            from_svg["report"][key].as_f64().unwrap(),
            typed["report"][key].as_f64().unwrap(),
        );
        assert!(
            (a - b).abs() <= 1e-6 * b.abs().max(1e-9),
            "{key}: {a} from the SVG, {b} typed"
        );
    }
}

/// A bad SVG, a missing file: one line naming the problem and the file, exit code 2, no
/// file written.
#[test]
fn bad_svg_targets_are_refused_in_one_line() {
    let dir = scratch("graded-svg-bad");
    let out = dir.path().join("sheet.json");
    let write = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        format!("@{}", path.display())
    };
    let two = write(
        "two.svg",
        r#"<svg xmlns="http://www.w3.org/2000/svg"><rect id="frame" width="90" height="90"/><circle cx="45" cy="45" r="30"/></svg>"#,
    );
    let open = write(
        "open.svg",
        r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 10 0 L 10 10"/></svg>"#,
    );
    let html = write("page.svg", "<html><body>not a drawing</body></html>");
    let missing = format!("@{}", dir.path().join("missing.svg").display());
    for (target, needles) in [
        (&two, vec!["two.svg", "2 shapes", "<rect id=\"frame\">"]),
        (&open, vec!["open.svg", "is open"]),
        (&html, vec!["page.svg", "not an SVG document"]),
        (&missing, vec!["cannot read it", "missing.svg"]),
    ] {
        let args = [
            "graded",
            "--design",
            "rotating-squares",
            "--region",
            "2x2",
            "--iterations",
            "60",
            "--target",
            target,
            "--out",
            out.to_str().unwrap(),
        ];
        let run = isogami(&args);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{target}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{target}: {err}");
        for needle in needles {
            assert!(
                err.contains(needle),
                "{target}: {err:?} does not say {needle:?}"
            );
        }
        assert!(!out.exists(), "{target} wrote a file");
    }
}

//! `isogami graded`: a graded sheet written as JSON whose numbers meet its report, the
//! refusals in one line with exit code 2, and no file left by a refused run.

use crate::common;

use common::{isogami, scratch};

/// A 2×2-cell rotating-squares sheet towards a rhombus: the file holds the sheet, the
/// report and the path check, and the sheet's own geometry agrees with the report (its
/// opened outline corners lie on the rhombus within the reported error; its pins close).
#[test]
fn a_graded_sheet_is_written_and_its_numbers_hold() {
    let dir = scratch("graded");
    let out = dir.path().join("sheet.json");
    let run = isogami(&[
        "graded",
        "--design",
        "rotating-squares",
        "--region",
        "2x2",
        "--target",
        "polygon:0,-1;1.3,0;0,1;-1.3,0",
        // 2×2 cells draw the rhombus coarsely: beyond the default tolerance.
        "--allow-failed",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(text.contains("opens along one motion"), "{text}");
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let sheet = &v["sheet"];
    let tiles = sheet["tiles"].as_array().unwrap();
    assert_eq!(tiles.len(), 16);
    assert_eq!(sheet["opened"].as_array().unwrap().len(), 16);
    assert_eq!(v["path"]["reached"], true);
    let gap = v["report"]["joint_gap"].as_f64().unwrap();
    assert!(gap < 1e-6, "{gap}");
    // Recompute every pin's gap from the file's nodes and poses.
    let nodes = sheet["nodes"].as_array().unwrap();
    let node = |n: usize| {
        let p = nodes[n].as_array().unwrap();
        (p[0].as_f64().unwrap(), p[1].as_f64().unwrap())
    };
    let corner = |t: usize, n: usize| {
        let pose = &sheet["opened"][t];
        let (x, y, th) = (
            pose["x"].as_f64().unwrap(),
            pose["y"].as_f64().unwrap(),
            pose["theta"].as_f64().unwrap(),
        );
        let first = node(tiles[t]["nodes"][0].as_u64().unwrap() as usize);
        let p = node(n);
        let (dx, dy) = (p.0 - first.0, p.1 - first.1);
        (
            x + th.cos() * dx - th.sin() * dy,
            y + th.sin() * dx + th.cos() * dy,
        )
    };
    let mut worst: f64 = 0.0;
    for j in sheet["joints"].as_array().unwrap() {
        let (a, b, n) = (
            j["a"].as_u64().unwrap() as usize,
            j["b"].as_u64().unwrap() as usize,
            j["node"].as_u64().unwrap() as usize,
        );
        let (pa, pb) = (corner(a, n), corner(b, n));
        worst = worst.max(((pa.0 - pb.0).powi(2) + (pa.1 - pb.1).powi(2)).sqrt());
    }
    assert!(
        (worst - gap).abs() <= 1e-12 + 1e-9 * gap,
        "{worst} vs {gap}"
    );
}

#[test]
fn bad_requests_are_refused_in_one_line_and_write_nothing() {
    let dir = scratch("graded-bad");
    let out = dir.path().join("sheet.json");
    let out = out.to_str().unwrap();
    for (args, needle) in [
        (vec!["--target", "blob"], "target"),
        (vec!["--target", "ellipse:1,0"], "semi-axes"),
        (vec!["--region", "0x2"], "region"),
        (vec!["--states", "0"], "states"),
        (vec!["--t", "1.5"], "t = 1.5"),
        (vec!["--design", "IH99::1x1:a"], "IH99"),
        (vec!["--target", "ellipse:100,1"], "unreachable target"),
        (vec!["--tolerance", "0"], "tolerance"),
        (vec!["--edge-mm", "0"], "--edge-mm"),
    ] {
        let mut all = vec!["graded", "--region", "2x2"];
        if args[0] != "--design" {
            all.extend(["--design", "rotating-squares"]);
        }
        all.extend(args.iter().copied());
        all.extend(["--out", out]);
        let run = isogami(&all);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{all:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{all:?}: {err}");
        assert!(err.contains(needle), "{all:?}: {err}");
        assert!(!std::path::Path::new(out).exists(), "{all:?} wrote a file");
    }
}

/// A field target (issue 25: a linear ramp of area ratio met within 0.05 per cell; its
/// example, 1.2× at one end and 1.8× at the other, missed by 0.22 before the fit's damping
/// floor): rotating squares, 4×4 cells, 1.2× at the left to 1.8× at the right. The report's
/// error agrees with the sheet: every measured cell's opened area ratio, recomputed here from
/// the written nodes and poses (the quadrilateral of four neighbouring cells' tile-0 first
/// corners), is within 0.05 of the ramp; and the graded sheet opens along one motion. The
/// ramp is read along the cells' place in the lattice, as the library reads it at the start's
/// closed centres (the rotating squares' lattice is square and axis-aligned): the grading
/// itself moves a cell's closed centre by up to a fifth of a cell.
#[test]
fn a_field_target_is_met_cell_by_cell() {
    let (from, to) = (1.2, 1.8);
    let run = isogami(&[
        "graded",
        "--design",
        "rotating-squares",
        "--region",
        "4x4",
        "--target",
        &format!("field:{from},{to}"),
        "--json",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let report = &v["report"];
    assert_eq!(report["field_cells"], 9);
    let error = report["max_field_error"].as_f64().unwrap();
    assert!(error < 0.05, "{error}");
    assert_eq!(v["path"]["reached"], true, "{}", v["path"]);
    // Recompute every cell's ratio from the sheet.
    let sheet = &v["sheet"];
    let node = |n: usize| {
        let p = &sheet["nodes"][n];
        [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()]
    };
    let tiles = sheet["tiles"].as_array().unwrap();
    let opened = |i: usize, n: usize| {
        let first = tiles[i]["nodes"][0].as_u64().unwrap() as usize;
        let pose = &sheet["opened"][i];
        let (x, y, th) = (
            pose["x"].as_f64().unwrap(),
            pose["y"].as_f64().unwrap(),
            pose["theta"].as_f64().unwrap(),
        );
        let (p, f) = (node(n), node(first));
        let d = [p[0] - f[0], p[1] - f[1]];
        [
            x + th.cos() * d[0] - th.sin() * d[1],
            y + th.sin() * d[0] + th.cos() * d[1],
        ]
    };
    let area = |q: &[[f64; 2]]| {
        (0..q.len())
            .map(|k| {
                let (a, b) = (q[k], q[(k + 1) % q.len()]);
                a[0] * b[1] - a[1] * b[0]
            })
            .sum::<f64>()
            / 2.0
    };
    let reference = |c: [i64; 2]| {
        tiles.iter().position(|t| {
            t["tile"] == 0
                && t["cell"][0].as_i64() == Some(c[0])
                && t["cell"][1].as_i64() == Some(c[1])
        })
    };
    let mut ratios = Vec::new();
    for i in -2..6 {
        for j in -2..6 {
            let quad: Option<Vec<usize>> = [[0, 0], [1, 0], [1, 1], [0, 1]]
                .iter()
                .map(|d| reference([i + d[0], j + d[1]]))
                .collect();
            let Some(quad) = quad else { continue };
            let first = |t: usize| tiles[t]["nodes"][0].as_u64().unwrap() as usize;
            let closed: Vec<[f64; 2]> = quad.iter().map(|&t| node(first(t))).collect();
            let open: Vec<[f64; 2]> = quad.iter().map(|&t| opened(t, first(t))).collect();
            ratios.push((i as f64, area(&open) / area(&closed)));
        }
    }
    assert_eq!(ratios.len(), 9);
    let (lo, hi) = ratios
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), r| (l.min(r.0), h.max(r.0)));
    for &(x, ratio) in &ratios {
        let want = from + (to - from) * (x - lo) / (hi - lo);
        assert!(
            (ratio - want).abs() < 0.05,
            "cell in column {x}: {ratio} vs {want}"
        );
    }
}

/// A sheet that misses its target (2×2 cells of rotating squares are too coarse for a disc
/// within 5 %, the default tolerance) is an error in one line with exit code 2, after the
/// summary that says by how much, and its file is not written; with `--allow-failed` the
/// same run writes it, and a looser `--tolerance` lets it pass. The verdict in the file
/// matches what the summary printed.
#[test]
fn a_sheet_that_misses_its_target_is_an_error_unless_allowed() {
    let dir = scratch("graded-verdict");
    let out = dir.path().join("sheet.json");
    let base = [
        "graded",
        "--design",
        "rotating-squares",
        "--region",
        "2x2",
        "--out",
        out.to_str().unwrap(),
    ];
    let run = isogami(&base);
    let err = String::from_utf8_lossy(&run.stderr);
    let text = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("misses its target"), "{err}");
    assert!(
        text.contains("verdict     opens along one motion; MISSES the target"),
        "{text}"
    );
    assert!(!out.exists(), "a failed sheet was written");
    let allowed = isogami(&[&base[..], &["--allow-failed"]].concat());
    assert!(allowed.status.success());
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let verdict = &v["verdict"];
    assert_eq!(verdict["opens"], true);
    assert_eq!(verdict["meets_target"], false);
    let error = verdict["error"].as_f64().unwrap();
    assert!(
        error > 0.05 && error == v["fit"]["hausdorff"].as_f64().unwrap(),
        "{v}"
    );
    let loose = format!("{}", error * 1.01);
    std::fs::remove_file(&out).unwrap();
    let passed = isogami(&[&base[..], &["--tolerance", &loose]].concat());
    assert!(
        passed.status.success(),
        "{}",
        String::from_utf8_lossy(&passed.stderr)
    );
    assert!(out.exists());
}

//! The `isogami` binary end to end: outputs, JSON contracts and exit codes.

use crate::common;
use common::{isogami, json};

#[test]
fn families_lists_all_81() {
    let v = json(&["families", "--json"]);
    let list = v.as_array().unwrap();
    assert_eq!(list.len(), 81);
    let ih28 = list.iter().find(|f| f["name"] == "IH28").unwrap();
    assert_eq!(ih28["param_count"], 2);
    assert_eq!(ih28["vertex_count"], 5);
    assert_eq!(ih28["aspect_count"], 4);
    assert_eq!(ih28["edges"].as_array().unwrap().len(), 5);
    let table = isogami(&["families"]);
    assert!(String::from_utf8_lossy(&table.stdout).lines().count() >= 82);
}

#[test]
fn cell_json_and_svg() {
    let dir_guard = tempfile::Builder::new()
        .prefix("isogami-cli-")
        .tempdir()
        .unwrap();
    let dir = dir_guard.path();
    let svg = dir.join("cell.svg");
    let v = json(&[
        "cell",
        "--family",
        "IH28",
        "--params",
        "0.4,0.5",
        "--cell",
        "2x1",
        "--json",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(v["tiles"].as_array().unwrap().len(), 8);
    assert_eq!(v["edges"].as_array().unwrap().len(), 20);
    let poly = v["tiles"][0]["polygon"].as_array().unwrap();
    assert_eq!(poly.len(), 5);
    assert_eq!(poly[0].as_array().unwrap().len(), 2);
    assert_eq!(v["u"].as_array().unwrap().len(), 2);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.starts_with("<?xml") && text.contains("<svg") && text.trim_end().ends_with("</svg>")
    );
    // 3×3 cells of 8 tiles plus the cell outline and arrow heads.
    assert!(text.matches("<polygon").count() >= 72);
}

#[test]
fn analyze_rotating_squares() {
    let v = json(&["analyze", "--design", "rotating-squares", "--json"]);
    assert_eq!(v["dof"], 1);
    let eig: Vec<f64> = v["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(eig.windows(2).all(|w| w[0] <= w[1]));
    assert!(eig[0].abs() < 1e-12 && eig[1] > 0.1);
    assert_eq!(v["motion"]["tiles"].as_array().unwrap().len(), 4);
    assert!(v["motion"]["u"].is_array() && v["motion"]["w"].is_array());
    let text = isogami(&["analyze", "--design", "rotating-squares"]);
    assert!(String::from_utf8_lossy(&text.stdout).contains("dof         1"));
}

#[test]
fn spec_and_json_designs_agree() {
    let spec = json(&["analyze", "--design", "rotating-squares", "--json"])["design"]
        .as_str()
        .unwrap()
        .to_string();
    let a = json(&["analyze", "--design", &spec, "--json"]);
    assert_eq!(a["dof"], 1);
}

/// Every malformed input: one line on stderr starting with "error", exit code 2, no panic.
#[test]
fn malformed_inputs_exit_2_with_one_line() {
    let cases: &[&[&str]] = &[
        &["cell", "--family", "IH19"],
        &["cell", "--family", "banana"],
        &["cell", "--family", "IH28", "--params", "0.1"],
        &["cell", "--family", "IH28", "--params", "0.1,nan"],
        &["cell", "--family", "IH28", "--params", "0.1,inf"],
        &["cell", "--family", "IH28", "--params", "0.1,x"],
        &["cell", "--family", "IH28", "--cell", "0x1"],
        &["cell", "--family", "IH28", "--cell", "5x5"],
        &["cell", "--family", "IH28", "--cell", "2by1"],
        &["cell", "--family", "IH41", "--params", "-5,0.5"],
        &[
            "cell",
            "--family",
            "IH28",
            "--svg",
            "/nonexistent-dir/x.svg",
        ],
        &["analyze", "--design", "no-such-design"],
        &["analyze", "--design", "IH76::2x2:ab"],
        &["analyze", "--design", "IH76::2x2:abab?aba"],
        &["analyze", "--design", "IH76:1:2x2:abababab"],
        &[
            "analyze",
            "--design",
            r#"{"family":"IH76","cell":[2,2],"joints":[{"edge":99,"at":"a"}]}"#,
        ],
        &["analyze", "--design", "{not json"],
        &["analyze", "--design", "rotating-squares", "--tol", "-1"],
        &["analyze"],
        &["frobnicate"],
    ];
    for args in cases {
        let out = isogami(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(err.starts_with("error"), "{args:?}: {err}");
        // Our own errors are one line; clap's usage errors add a usage hint.
        if args.len() > 1 && args[0] != "frobnicate" {
            assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        }
    }
}

#[test]
fn refused_parameter_is_named() {
    let out = isogami(&["cell", "--family", "IH41", "--params", "-5,0.5"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("v0"), "{err}");
}

#[test]
fn deploy_json_and_outputs() {
    let dir_guard = tempfile::Builder::new()
        .prefix("isogami-deploy-")
        .tempdir()
        .unwrap();
    let dir = dir_guard.path();
    let (gif, plot, out, frames) = (
        dir.join("d.gif"),
        dir.join("p.svg"),
        dir.join("t.json"),
        dir.join("frames"),
    );
    let v = json(&[
        "deploy",
        "--design",
        "rotating-squares",
        "--json",
        "--frame-count",
        "12",
        "--gif",
        gif.to_str().unwrap(),
        "--plot",
        plot.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--frames",
        frames.to_str().unwrap(),
    ]);
    assert_eq!(v["end_reason"]["kind"], "contact_limit");
    assert_eq!(v["behaviour"], "isotropic_auxetic");
    assert!(v["max_joint_residual"].as_f64().unwrap() <= 1e-8);
    assert!(v["min_clearance"].as_f64().unwrap() > 0.0);
    let fr = v["frames"].as_array().unwrap();
    assert!(fr.len() >= 10 && fr.len() <= 13, "{}", fr.len());
    assert_eq!(fr[0]["t"], 0.0);
    assert_eq!(fr.last().unwrap()["t"], 1.0);
    let f = fr[5]["F"].as_array().unwrap();
    assert_eq!(f.len(), 2);
    assert_eq!(f[0].as_array().unwrap().len(), 2);
    let tiles = fr[5]["tiles"].as_array().unwrap();
    assert_eq!(tiles.len(), 4);
    for key in ["x", "y", "theta"] {
        assert!(tiles[1][key].is_f64(), "{key}");
    }
    assert!(std::fs::read(&gif).unwrap().starts_with(b"GIF89a"));
    assert!(std::fs::read_to_string(&plot).unwrap().contains("<svg"));
    assert!(std::fs::read_to_string(dir.join("p-polar.svg"))
        .unwrap()
        .contains("<svg"));
    let saved: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(saved["frames"].as_array().unwrap().len(), fr.len());
    assert_eq!(std::fs::read_dir(&frames).unwrap().count(), fr.len());
}

#[test]
fn deploy_refuses_rigid_and_bad_settings() {
    for args in [
        &["deploy", "--design", "IH76::2x2:xxxxxxxx"][..],
        &["deploy", "--design", "rotating-squares", "--kerf", "0"],
        &["deploy", "--design", "rotating-squares", "--kerf", "-1"],
        &["deploy", "--design", "rotating-squares", "--kerf", "nan"],
        &[
            "deploy",
            "--design",
            "rotating-squares",
            "--frame-count",
            "1",
        ],
        &[
            "deploy",
            "--design",
            "rotating-squares",
            "--gif",
            "/nonexistent-dir/x.gif",
        ],
    ] {
        let out = isogami(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.starts_with("error") && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
    let err =
        String::from_utf8_lossy(&isogami(&["deploy", "--design", "IH76::2x2:xxxxxxxx"]).stderr)
            .to_string();
    assert!(err.contains("rigid"), "{err}");
}

#[test]
fn compare_prints_final_t_per_method() {
    let v = json(&["compare", "--design", "rotating-squares", "--json"]);
    let results = v[0]["results"].as_array().unwrap();
    assert_eq!(results.len(), 3);
    let t = |m: &str| {
        results.iter().find(|r| r["method"] == m).unwrap()["final_t"]
            .as_f64()
            .unwrap()
    };
    assert_eq!(t("rigid-modes"), 1.0);
    assert!(t("ncm") < 1.0 && t("springs") < t("ncm"));
}

#[test]
fn deploy_all_steps_and_polar_t() {
    let v = json(&[
        "deploy",
        "--design",
        "rotating-squares",
        "--json",
        "--all-steps",
    ]);
    assert_eq!(
        v["frames"].as_array().unwrap().len(),
        v["steps"].as_u64().unwrap() as usize
    );
    for bad in ["2", "x", "", "0.1,,0.2"] {
        let out = isogami(&["deploy", "--design", "rotating-squares", "--polar-t", bad]);
        assert_eq!(out.status.code(), Some(2), "--polar-t {bad}");
    }
}

#[test]
fn linkages_json_and_svg() {
    let dir_guard = tempfile::Builder::new()
        .prefix("isogami-linkages-")
        .tempdir()
        .unwrap();
    let dir = dir_guard.path();
    let svg = dir.join("l.svg");
    let v = json(&[
        "linkages",
        "--design",
        "rotating-squares",
        "--json",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(v["signature"], "4×4-bar");
    assert_eq!(v["linkages"].as_array().unwrap().len(), 4);
    assert_eq!(v["degree_histogram"]["4"], 4);
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    let out = isogami(&["linkages", "--design", "IH76::2x2:ab"]);
    assert_eq!(out.status.code(), Some(2));
}

/// `deploy` checks the periodic path for singular states: IH85 and IH86 designs of the quick
/// exploration pass one (a singular value of the cell vanishing between two accepted states)
/// and say where; rotating squares passes none and says so, pointing at `sheet --deploy` for
/// the branches only a finite sheet has.
#[test]
fn deploy_reports_the_singular_states_of_the_periodic_path() {
    for (spec, t) in [
        ("IH85:0.5,0.196416770201:1x1:aaabbb", 0.4994),
        ("IH86:0.271416770201:1x1:aaabbb", 0.5874),
    ] {
        let out = isogami(&["deploy", "--design", spec]);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{spec}");
        let line = text
            .lines()
            .find(|l| l.starts_with("warning: the periodic path is singular at t = "))
            .unwrap_or_else(|| panic!("{spec}: {text}"));
        let at: f64 = line["warning: the periodic path is singular at t = ".len()..]
            .split_whitespace()
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!((at - t).abs() < 0.002, "{spec}: {line}");
    }
    let out = isogami(&["deploy", "--design", "rotating-squares"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("singular     no state of the periodic path") && !text.contains("warning"),
        "{text}"
    );
}

//! `isogami compare` end to end: the JSON fields per method, the table, and one-line errors
//! with exit code 2.

use crate::common;
use common::isogami;

const FIELDS: [&str; 9] = [
    "final_t",
    "path_distance",
    "max_area_ratio",
    "max_area_t",
    "final_area_ratio",
    "max_expansion",
    "min_expansion",
    "max_tile_rotation",
    "millis",
];

#[test]
fn json_has_every_measure_per_method() {
    let out = isogami(&["compare", "--design", "rotating-squares", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    let row = &v.as_array().expect("one row per design")[0];
    assert_eq!(row["design"], "IH76::2x2:bbbbaaaa");
    assert_eq!(row["dof"], 1);
    let results = row["results"].as_array().unwrap();
    let methods: Vec<&str> = results
        .iter()
        .map(|r| r["method"].as_str().unwrap())
        .collect();
    assert_eq!(methods, ["rigid-modes", "ncm", "springs"]);
    for r in results {
        for field in FIELDS {
            assert!(
                r[field].as_f64().is_some_and(f64::is_finite),
                "{}: {field} = {}",
                r["method"],
                r[field]
            );
        }
        let t = r["final_t"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&t));
        assert!(r["reached_peak_area"].is_boolean());
        assert!(r["end_reason"]["kind"].is_string());
        assert!(r["steps"].as_u64().unwrap() >= 1);
    }
    // Rotating squares: the area ratio peaks at 2 (squares turned by 45°) half-way along the
    // rigid-modes path and closes again; the springs stop at that peak.
    let rigid = &results[0];
    assert_eq!(rigid["final_t"].as_f64(), Some(1.0));
    assert!((rigid["max_area_ratio"].as_f64().unwrap() - 2.0).abs() < 1e-3);
    let springs = &results[2];
    assert!((springs["final_t"].as_f64().unwrap() - 0.5).abs() < 0.02);
    assert_eq!(springs["reached_peak_area"], true);
}

#[test]
fn table_has_a_row_per_method() {
    let out = isogami(&["compare", "--design", "rotating-squares"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for method in ["rigid-modes", "ncm", "springs"] {
        assert_eq!(
            text.lines()
                .filter(|l| l.trim_start().starts_with(method))
                .count(),
            1,
            "{method}: {text}"
        );
    }
    assert!(text.contains("IH76::2x2:bbbbaaaa"), "{text}");
}

#[test]
fn bad_input_is_one_line_and_exit_2() {
    for args in [
        &["compare", "--design", "IH999::1x1:a"][..],
        &["compare", "--design", "rotating-squares", "--kerf", "-1"],
        &["compare", "--design", "rotating-squares", "--kerf", "NaN"],
        &["compare", "--design", "IH76::2x2:xxxxxxxx"],
    ] {
        let out = isogami(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

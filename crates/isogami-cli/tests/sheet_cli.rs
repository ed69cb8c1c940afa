//! `isogami sheet`: the finite sheet's counts and completion, the finite deployment, and
//! one-line refusals with exit code 2.

mod common;

use common::isogami;
use serde_json::Value;

const IH44: &str = "IH44:0.5,0.027564102564:1x2:-aaabbaa";

fn json(args: &[&str]) -> Value {
    let out = isogami(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

#[test]
fn the_completed_sheet_has_one_dof_and_deploys_with_the_periodic_motion() {
    let v = json(&["sheet", "--design", IH44, "--region", "4x4", "--json"]);
    assert!(v["raw_mobility"]["dof"].as_u64().unwrap() > 1);
    assert_eq!(v["completion"]["mobility"]["dof"], 1);
    let d = json(&[
        "sheet", "--design", IH44, "--region", "4x4", "--deploy", "--frames", "7", "--json",
    ]);
    // The analysis inside the deployment is the one `sheet` prints, to the last digit (the
    // sparse kernel sums in a fixed order).
    assert!(
        d["analysis"] == v,
        "the deployment's sheet differs from `sheet --json`'s"
    );
    assert_eq!(d["frames"].as_array().unwrap().len(), 7);
    assert_eq!(d["one_dof_throughout"], true);
    let a = &d["agreement"];
    assert!(a["max_position_deviation"].as_f64().unwrap() <= 1e-6);
    assert!(a["compared_steps"].as_u64().unwrap() >= 2);
    let tiles = v["completion"]["sheet"]["tiles"].as_array().unwrap().len();
    for f in d["frames"].as_array().unwrap() {
        assert_eq!(f["poses"].as_array().unwrap().len(), tiles);
    }
    // The text report says what happened.
    let out = isogami(&["sheet", "--design", IH44, "--region", "4x4", "--deploy"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    for needle in ["deployed", "periodic", "same poses as the periodic sheet"] {
        assert!(text.contains(needle), "{needle} in {text}");
    }
}

#[test]
fn a_sheet_repeats_byte_for_byte() {
    let args = ["sheet", "--design", IH44, "--region", "6x6", "--json"];
    let (a, b) = (isogami(&args), isogami(&args));
    assert!(a.status.success() && !a.stdout.is_empty());
    assert!(a.stdout == b.stdout, "two runs of {args:?} differ");
}

#[test]
fn bad_requests_are_one_line_and_exit_2() {
    for (args, needle) in [
        (vec!["--region", "0x3"], "region"),
        (vec!["--region", "4x4", "--t", "0"], "t = 0"),
        (vec!["--region", "4x4", "--deploy", "--t", "NaN"], "t = NaN"),
        (
            vec!["--region", "4x4", "--deploy", "--min-cover", "200"],
            "covered",
        ),
        (
            vec!["--region", "4x4", "--raw", "--deploy"],
            "degrees of freedom",
        ),
        (
            vec!["--region", "4x4", "--deploy", "--frames", "1"],
            "frames",
        ),
        (vec!["--region", "4x4", "--frames", "5"], "--deploy"),
    ] {
        let mut all = vec!["sheet", "--design", IH44];
        all.extend(&args);
        let out = isogami(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
        if !args.contains(&"--frames") || args.contains(&"--deploy") {
            assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        }
    }
}

//! `isogami sheet`: the finite sheet's counts and completion, the finite deployment, the
//! pull, and one-line refusals with exit code 2.

use crate::common;

use common::{isogami, json};

const IH44: &str = "IH44:0.5,0.027564102564:1x2:-aaabbaa";

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
            vec!["--region", "4x4", "--deploy", "--frames", "1"],
            "frames",
        ),
        (vec!["--region", "4x4", "--frames", "5"], "--deploy"),
        (
            vec!["--region", "2x2", "--raw", "--pull", "--grips", "0,0"],
            "grips",
        ),
        (
            vec!["--region", "2x2", "--raw", "--pull", "--grips", "0,9999"],
            "grips",
        ),
        (
            vec!["--region", "2x2", "--raw", "--pull", "--grips", "a,b"],
            "grips",
        ),
        (vec!["--region", "2x2", "--grips", "0,1"], "--pull"),
        (vec!["--region", "2x2", "--pull", "--deploy"], "--deploy"),
    ] {
        let mut all = vec!["sheet", "--design", IH44];
        all.extend(&args);
        let out = isogami(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
        // clap's own refusals of a flag without the one it needs add a usage line.
        let clap_refusal = (args.contains(&"--frames") && !args.contains(&"--deploy"))
            || (args.contains(&"--grips") && !args.contains(&"--pull"))
            || (args.contains(&"--pull") && args.contains(&"--deploy"));
        if !clap_refusal {
            assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        }
    }
}

/// A completion refused — by counting alone for an isostatic cell, by pruning for a design
/// whose boundary keeps flopping — and a raw region too floppy to deploy still answer --json
/// with the raw region (and the refusal's reason), then the reason in one line on stderr and
/// exit code 2; the text report is the one line alone.
#[test]
fn a_refusal_still_prints_the_raw_region() {
    const ISOSTATIC: &str = "IH10::2x2:--a--aa-a-bb";
    // Its 6×6 completion keeps 79 % of the region.
    const FLOPPY: &str = "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-";
    let cases: [(&str, &[&str], &str); 4] = [
        (ISOSTATIC, &["--region", "4x4"], "counting"),
        (ISOSTATIC, &["--region", "4x4", "--deploy"], "counting"),
        (FLOPPY, &["--region", "6x6", "--min-cover", "100"], "100 %"),
        (
            IH44,
            &["--region", "4x4", "--raw", "--deploy"],
            "degrees of freedom",
        ),
    ];
    for (design, args, needle) in cases {
        let base = [&["sheet", "--design", design][..], args].concat();
        for json in [true, false] {
            let all = [&base[..], if json { &["--json"][..] } else { &[][..] }].concat();
            let out = isogami(&all);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{all:?}: {err}");
            assert_eq!(err.trim().lines().count(), 1, "{all:?}: {err}");
            assert!(err.contains(needle), "{all:?}: {err}");
            let reason = err.trim().trim_start_matches("error: ");
            if json {
                let v: serde_json::Value = serde_json::from_slice(&out.stdout)
                    .unwrap_or_else(|e| panic!("{all:?}: stdout is no JSON ({e})"));
                assert!(v["raw_mobility"]["dof"].as_u64().unwrap() > 1, "{all:?}");
                assert!(!v["raw"]["tiles"].as_array().unwrap().is_empty());
                assert!(v["completion"].is_null(), "{all:?}");
                if !args.contains(&"--raw") {
                    assert_eq!(v["refusal"].as_str(), Some(reason), "{all:?}");
                }
            } else {
                assert!(out.stdout.is_empty(), "{all:?}");
            }
        }
    }
}

#[test]
fn a_pulled_raw_sheet_leaves_the_motion_and_says_why() {
    const IH9: &str = "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-";
    let args = [
        "sheet", "--design", IH9, "--region", "2x2", "--raw", "--pull",
    ];
    let v = json(&[&args[..], &["--frames", "6", "--json"]].concat());
    assert!(v["dof"].as_u64().unwrap() > 1);
    assert_eq!(v["frames"].as_array().unwrap().len(), 6);
    assert!(v["max_deviation"].as_f64().unwrap() > 0.01);
    assert!(!v["leaving"].as_array().unwrap().is_empty());
    assert!(v["leaves"]["dof"].as_u64().unwrap() > 1);
    let tiles = v["analysis"]["raw"]["tiles"].as_array().unwrap().len();
    assert!(v["frames"][0]["poses"].as_array().unwrap().len() == tiles);
    let text = String::from_utf8(isogami(&args).stdout).unwrap();
    for needle in ["pulled", "leave the periodic motion", "extra modes"] {
        assert!(text.contains(needle), "{needle} in {text}");
    }
    // A one-DOF sheet follows the motion; named grips are used.
    let squares = [
        "sheet",
        "--design",
        "rotating-squares",
        "--region",
        "2x2",
        "--pull",
        "--grips",
        "0,15",
    ];
    let out = isogami(&squares);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        text.contains("every tile follows the periodic motion"),
        "{text}"
    );
    assert!(
        text.contains("held tile 0") && text.contains("pulled tile 15"),
        "{text}"
    );
}

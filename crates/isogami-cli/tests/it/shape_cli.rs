//! `isogami shape` end to end: a special design's class and constraints, following a
//! parameter (checked by `isogami analyze`), the rank-drop search, a database table, and bad
//! input as one line with exit 2.

use crate::common;

use common::isogami;

const IH2: &str = "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:aa-aa-";

fn ok(args: &[&str]) -> String {
    let out = isogami(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&ok(args)).unwrap()
}

#[test]
fn a_special_design_is_classified_followed_and_found_back() {
    let m = json(&["shape", "--design", IH2, "--json"]);
    assert_eq!(m["class"], "special");
    assert_eq!(m["constraints"].as_array().unwrap().len(), 1);
    let text = ok(&["shape", "--design", IH2]);
    assert!(
        text.contains("special") && text.contains("constraint 0"),
        "{text}"
    );

    let f = json(&["shape", "--design", IH2, "--set", "2=0.25", "--json"]);
    let spec = f["spec"].as_str().unwrap();
    let a = json(&["analyze", "--design", spec, "--json"]);
    assert_eq!(a["dof"], 1, "{spec}");

    // Off the special set the design is rigid; the search finds a moving shape again.
    let off = "IH2:0.12239750492,0.5,0.225335752741,0.24:1x1:aa-aa-";
    assert_eq!(json(&["analyze", "--design", off, "--json"])["dof"], 0);
    let r = json(&["shape", "--design", off, "--rank-drop", "--json"]);
    let found = r["spec"].as_str().unwrap();
    assert_eq!(
        json(&["analyze", "--design", found, "--json"])["dof"],
        1,
        "{found}"
    );
}

#[test]
fn bad_input_is_one_line_and_exit_2() {
    for (args, want) in [
        (
            vec!["shape", "--design", IH2, "--set", "9=0.1"],
            "parameter 9 does not exist",
        ),
        (
            vec!["shape", "--design", IH2, "--set", "x"],
            "expected I=VALUE",
        ),
        (
            vec!["shape", "--design", IH2, "--set", "0=nan"],
            "not a finite number",
        ),
        (
            vec![
                "shape",
                "--design",
                "IH2:0.12239750492,0.5,0.225335752741,0.24:1x1:aa-aa-",
            ],
            "0 degrees of freedom",
        ),
        (
            vec![
                "shape",
                "--design",
                "IH16:0.216506350946:1x1:-a-a-aaaa",
                "--set",
                "0=0.22",
            ],
            "fixed by the shape constraints",
        ),
        (vec!["shape", "--db", "/no/such.db"], "/no/such.db"),
    ] {
        let out = isogami(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

//! `explore --max-edges`: requested cells are never dropped silently (a cell over the cap is
//! an error naming the option), a raised cap runs cells above 16 edges (IH77's minimal cell,
//! 18 edges), and runs with different caps do not mix in one database.

use isogami_store::{Check, Store};

fn dir(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("isogami-cap-{name}-"))
        .tempdir()
        .unwrap()
}

fn run(args: &[&str]) -> (Option<i32>, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_isogami"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Exit 2 with one line on stderr that contains every `needle`, and no database made.
fn refused(args: &[&str], db: &std::path::Path, needles: &[&str]) {
    let (code, _, err) = run(args);
    assert_eq!(code, Some(2), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {err} lacks {n}");
    }
    assert!(!db.exists(), "{args:?} made {}", db.display());
}

#[test]
fn requested_cells_over_the_cap_are_errors_naming_max_edges() {
    let d_guard = dir("over");
    let d = d_guard.path();
    let db = d.join("a.db");
    let p = db.to_str().unwrap();
    // Issue 13: this printed "0 work units run" and exited 0.
    refused(
        &["explore", "--families", "IH76", "--cells", "3x3", "--db", p],
        &db,
        &[
            "IH76/3x3",
            "18 unique edges",
            "--max-edges 16",
            "--max-edges 18",
        ],
    );
    // Several families: the first offender, how many more, the cap that takes them all.
    refused(
        &[
            "explore",
            "--families",
            "IH76,IH41",
            "--cells",
            "3x3",
            "--max-edges",
            "17",
            "--db",
            p,
        ],
        &db,
        &["--max-edges 17", "more requested cell"],
    );
    // A named family without any cell under the cap.
    refused(
        &["explore", "--quick", "--families", "IH77", "--db", p],
        &db,
        &[
            "IH77",
            "18 unique edges",
            "--max-edges 12",
            "--max-edges 18",
        ],
    );
    // A cell the quick exploration never takes, and caps outside the enumerator's range.
    refused(
        &[
            "explore",
            "--quick",
            "--families",
            "IH90",
            "--cells",
            "2x1",
            "--db",
            p,
        ],
        &db,
        &["2x1", "--quick"],
    );
    for bad in ["0", "25"] {
        refused(
            &["explore", "--max-edges", bad, "--db", p],
            &db,
            &["--max-edges", "1..=24"],
        );
    }
}

#[test]
fn a_raised_cap_runs_ih77_and_caps_do_not_mix() {
    let d_guard = dir("ih77");
    let d = d_guard.path();
    let db = d.join("a.db");
    let p = db.to_str().unwrap();
    let (code, out, err) = run(&[
        "explore",
        "--quick",
        "--families",
        "IH77",
        "--max-edges",
        "18",
        "--db",
        p,
        "--json",
    ]);
    assert_eq!(code, Some(0), "{err}");
    assert!(out.contains("IH77"), "{out}");
    let store = Store::open_read(&db, Check::Full).unwrap();
    let units = store.work_units().unwrap();
    let ids: Vec<&str> = units.iter().map(|(u, _)| u.id.as_str()).collect();
    assert_eq!(ids, ["IH77/1x1"]);
    // Every one of the 2^18 masks went through the reduced checks.
    let degree = units[0].1.iter().find(|s| s.stage == "degree").unwrap();
    assert_eq!(degree.count_in, 1 << 18);
    drop(store);
    // The same file with another cap: refused, naming the setting; the file is unchanged.
    let before = std::fs::read(&db).unwrap();
    let (code, _, err) = run(&[
        "explore",
        "--quick",
        "--families",
        "IH77",
        "--max-edges",
        "20",
        "--db",
        p,
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("max_edges 18 in the file, 20 in this run"),
        "{err}"
    );
    assert_eq!(std::fs::read(&db).unwrap(), before);
}

#[test]
fn plan_lists_what_a_run_runs_longest_first_and_touches_nothing() {
    let d_guard = dir("plan");
    let d = d_guard.path();
    let db = d.join("p.db");
    let db_arg = db.to_str().unwrap();
    let common = ["explore", "--quick", "--families", "IH83,IH84,IH90,IH28"];
    let (code, json, err) = run(&[&common[..], &["--db", db_arg, "--plan", "--json"]].concat());
    assert_eq!(code, Some(0), "{err}");
    assert!(!db.exists(), "--plan made {}", db.display());
    let planned: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    let costs: Vec<f64> = planned
        .iter()
        .map(|p| p["expected_cost"].as_f64().unwrap())
        .collect();
    assert!(costs.windows(2).all(|w| w[0] >= w[1]), "{costs:?}");
    for p in &planned {
        let (edges, group) = (
            p["edges"].as_u64().unwrap(),
            p["symmetry_group"].as_u64().unwrap(),
        );
        let cost = 3f64.powi(edges as i32) / group as f64;
        assert!(
            (p["expected_cost"].as_f64().unwrap() - cost).abs() <= 1e-9 * cost,
            "{p}"
        );
    }
    let mut ids: Vec<String> = planned
        .iter()
        .map(|p| p["unit"].as_str().unwrap().to_string())
        .collect();
    ids.sort();
    // The run itself does exactly those units.
    let (code, _, err) = run(&[&common[..], &["--db", db_arg]].concat());
    assert_eq!(code, Some(0), "{err}");
    let mut done: Vec<String> = Store::open_read(&db, Check::Full)
        .unwrap()
        .done_units()
        .unwrap()
        .into_iter()
        .collect();
    done.sort();
    assert_eq!(ids, done);
    // A bad cap is refused as for a run.
    let none = d.join("none.db");
    refused(
        &[
            &common[..],
            &[
                "--max-edges",
                "30",
                "--plan",
                "--db",
                none.to_str().unwrap(),
            ],
        ]
        .concat(),
        &none,
        &["--max-edges"],
    );
}

//! `explore --unit-parts P`: every unit's masks split into P parts. A run that holds every part
//! joins each unit exactly as if it ran whole; shards that each hold some parts merge into the
//! same database, also one shard at a time; reruns skip what is stored; mixing part counts is
//! refused with one line.

use crate::common;

use common::{isogami as run, scratch as dir};
use isogami_store::{Check, Store};
use std::path::{Path, PathBuf};
use std::process::Output;

const FAMILIES: &str = "IH28,IH6,IH90,IH41";

fn ok(out: Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn explore(db: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "explore",
        "--quick",
        "--families",
        FAMILIES,
        "--db",
        db.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    run(&args)
}

/// Unit ids, (spec, report) per design, stage counts per unit, motion classes.
type Content = (
    Vec<String>,
    Vec<(String, String)>,
    Vec<Vec<(String, u64, u64)>>,
    String,
);

fn content(db: &Path) -> Content {
    let s = Store::open_read(db, Check::Full).unwrap();
    let units = s.work_units().unwrap();
    let designs = units
        .iter()
        .flat_map(|(u, _)| s.designs_of_unit(&u.id).unwrap())
        .map(|d| (d.summary().spec.clone(), d.report_json().to_string()))
        .collect();
    let stages = units
        .iter()
        .map(|(_, st)| {
            st.iter()
                .map(|x| (x.stage.clone(), x.count_in, x.count_out))
                .collect()
        })
        .collect();
    let classes = format!("{:?}", s.motion_classes().unwrap());
    (
        units.iter().map(|(u, _)| u.id.clone()).collect(),
        designs,
        stages,
        classes,
    )
}

fn stats(db: &Path) -> serde_json::Value {
    let text = ok(run(&[
        "db",
        "stats",
        "--db",
        db.to_str().unwrap(),
        "--json",
    ]));
    serde_json::from_str(&text).unwrap()
}

fn merge(into: &Path, inputs: &[&Path], extra: &[&str]) -> Output {
    let mut args = vec!["merge", "--into", into.to_str().unwrap()];
    args.extend_from_slice(extra);
    args.extend(inputs.iter().map(|p| p.to_str().unwrap()));
    run(&args)
}

#[test]
fn parts_in_one_run_or_over_shards_equal_whole_units() {
    let d_guard = dir("equal");
    let d = d_guard.path();
    let whole = d.join("whole.db");
    ok(explore(&whole, &["--jobs", "2"]));
    let want = content(&whole);
    assert!(want.1.len() > 5, "{} designs", want.1.len());

    // Every part in one run: each unit is joined when its last part is stored.
    let split = d.join("split.db");
    let text = ok(explore(&split, &["--jobs", "2", "--unit-parts", "3"]));
    assert!(text.contains("unit parts run"), "{text}");
    assert_eq!(content(&split), want);
    assert!(stats(&split).get("waiting_parts").is_none());

    // Two shards of 3 parts per unit: no shard holds a whole unit; each waits.
    let shards: Vec<PathBuf> = (0..2).map(|i| d.join(format!("s{i}.db"))).collect();
    for (i, s) in shards.iter().enumerate() {
        ok(explore(
            s,
            &[
                "--unit-parts",
                "3",
                "--shard",
                &format!("{i}/2"),
                "--jobs",
                "1",
            ],
        ));
        let st = stats(s);
        // Only units with a single mask to expand run whole (never split into empty parts).
        let whole_units = st["shard"]["record"]["units"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|u| !u.as_str().unwrap().contains(" part "))
            .count();
        assert!(whole_units < 4, "{st}");
        assert_eq!(st["work_units"], whole_units, "{st}");
        assert!(st["waiting_parts"].as_u64().unwrap() > 0, "{st}");
        assert_eq!(st["shard"]["missing"].as_array().unwrap().len(), 0, "{st}");
        // A rerun skips every stored part.
        let again = ok(explore(
            s,
            &["--unit-parts", "3", "--shard", &format!("{i}/2")],
        ));
        assert!(again.starts_with("0 unit parts run"), "{again}");
        ok(run(&[
            "db",
            "check-shard",
            "--db",
            s.to_str().unwrap(),
            "--shard",
            &format!("{i}/2"),
        ]));
    }
    let merged = d.join("merged.db");
    let out = ok(merge(&merged, &[&shards[0], &shards[1]], &[]));
    assert!(out.contains("units joined"), "{out}");
    assert_eq!(content(&merged), want);
    assert!(stats(&merged).get("waiting_parts").is_none());

    // One shard at a time: parts wait in the target until the other shard's arrive.
    let stepwise = d.join("stepwise.db");
    ok(merge(&stepwise, &[&shards[1]], &["--allow-incomplete"]));
    let st = stats(&stepwise);
    let whole_in_1 = stats(&shards[1])["shard"]["record"]["units"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|u| !u.as_str().unwrap().contains(" part "))
        .count();
    assert_eq!(st["work_units"], whole_in_1, "{st}");
    assert!(st["waiting_parts"].as_u64().unwrap() > 0);
    ok(merge(&stepwise, &[&shards[0]], &["--allow-incomplete"]));
    assert_eq!(content(&stepwise), want);
}

#[test]
fn bad_part_counts_are_refused_in_one_line() {
    let d_guard = dir("bad");
    let d = d_guard.path();
    let db = d.join("a.db");
    for bad in ["0", "4097", "x"] {
        let out = explore(&db, &["--unit-parts", bad]);
        assert_eq!(out.status.code(), Some(2), "--unit-parts {bad}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains("unit-parts"), "{err}");
        assert!(!db.exists());
    }
    // Parts of 3 waiting in a plain database (one shard merged alone), then a run that
    // splits the same units in 2: each of its parts is refused, naming the option.
    let shard = d.join("s0.db");
    ok(explore(&shard, &["--unit-parts", "3", "--shard", "0/2"]));
    let target = d.join("t.db");
    ok(merge(&target, &[&shard], &["--allow-incomplete"]));
    let out = explore(&target, &["--unit-parts", "2"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("use the same --unit-parts"), "{err}");
    // Only single-mask units (whole under any part count) are complete; no split unit is.
    let plan: Vec<serde_json::Value> = serde_json::from_str(&ok(explore(
        &d.join("plan.db"),
        &["--unit-parts", "2", "--plan", "--json"],
    )))
    .unwrap();
    let whole_units = plan.iter().filter(|p| p["parts"] == 1).count();
    assert!(whole_units < plan.len());
    assert_eq!(stats(&target)["work_units"], whole_units);
    // Whole units then replace the waiting parts: nothing is left waiting, and the file
    // equals a whole run.
    ok(explore(&target, &[]));
    assert!(stats(&target).get("waiting_parts").is_none());
    let whole = d.join("whole.db");
    ok(explore(&whole, &[]));
    assert_eq!(content(&target), content(&whole));
}

/// Issue 23: `--unit-parts` larger than a unit's work never makes empty parts (on main,
/// `--unit-parts 4096` committed 4096 parts of every unit, most with nothing to do), the
/// joined units still equal the whole run, and `--plan` prints one entry per unit with its
/// part count instead of one per part.
#[test]
fn parts_never_outnumber_a_units_masks_and_the_plan_lists_units() {
    let d_guard = dir("parts-cap");
    let d = d_guard.path();
    let (whole, split) = (d.join("whole.db"), d.join("split.db"));
    let plan_args = |db: &Path, parts: &str| {
        run(&[
            "explore",
            "--quick",
            "--families",
            FAMILIES,
            "--unit-parts",
            parts,
            "--plan",
            "--json",
            "--db",
            db.to_str().unwrap(),
        ])
    };
    let units: Vec<serde_json::Value> = serde_json::from_str(&ok(plan_args(&split, "1"))).unwrap();
    let planned: Vec<serde_json::Value> =
        serde_json::from_str(&ok(plan_args(&split, "4096"))).unwrap();
    assert!(!split.exists(), "--plan made a database");
    let ids = |v: &[serde_json::Value]| -> Vec<String> {
        let mut ids: Vec<String> = v
            .iter()
            .map(|p| p["unit"].as_str().unwrap().into())
            .collect();
        ids.sort();
        ids
    };
    assert_eq!(ids(&planned), ids(&units), "one entry per unit");
    let parts: Vec<u64> = planned
        .iter()
        .map(|p| p["parts"].as_u64().unwrap())
        .collect();
    assert!(parts.iter().all(|&p| (1..4096).contains(&p)), "{parts:?}");
    assert!(parts.iter().any(|&p| p > 1), "{parts:?}");
    for p in &planned {
        assert_eq!(p["parts"], p["parts_here"], "{p}");
    }
    let total: u64 = parts.iter().sum();
    // The text plan: one line per unit, the header counting the items.
    let text = ok(run(&[
        "explore",
        "--quick",
        "--families",
        FAMILIES,
        "--unit-parts",
        "4096",
        "--plan",
        "--db",
        split.to_str().unwrap(),
    ]));
    assert_eq!(text.lines().count(), 3 + units.len(), "{text}");
    assert!(
        text.starts_with(&format!("{} work units ({total} work items)", units.len())),
        "{text}"
    );
    // The run commits exactly those parts, and joins them into the whole run's units.
    let out = ok(explore(&split, &["--unit-parts", "4096"]));
    assert!(out.starts_with(&format!("{total} unit parts run")), "{out}");
    ok(explore(&whole, &[]));
    assert_eq!(content(&split), content(&whole));
}

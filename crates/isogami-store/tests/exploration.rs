//! The exploration driver `explore_into`: events, commits, resumption, cancellation.

mod common;

use common::{quick_settings, temp};
use isogami::explore::{ExplorePlan, WorkUnit};
use isogami::tiling::Family;
use isogami_store::{
    explore_into, Check, ExploreEvent, ExploreRequest, Store, StoreError, UnitRecords,
};
use std::sync::atomic::AtomicBool;

/// Two cheap families of the quick exploration.
fn request(jobs: usize) -> ExploreRequest {
    ExploreRequest {
        settings: quick_settings(),
        families: vec![
            Family::from_number(83).unwrap(),
            Family::from_number(90).unwrap(),
        ],
        cells: None,
        shard: None,
        jobs,
    }
}

/// Events as plain tuples: ("started", planned, skipped, to_run) or ("unit", finished, to_run,
/// ok as 0/1) with the unit's id.
type Log = Vec<(&'static str, usize, usize, usize, String)>;

fn run(
    db: &std::path::Path,
    req: &ExploreRequest,
    cancel: bool,
) -> (isogami_store::ExploreOutcome, Log) {
    let mut log = Log::new();
    let flag = AtomicBool::new(cancel);
    let outcome = explore_into(
        db,
        req,
        &mut |e| match *e {
            ExploreEvent::Started {
                planned,
                skipped,
                to_run,
            } => log.push(("started", planned, skipped, to_run, String::new())),
            ExploreEvent::UnitFinished {
                unit,
                ok,
                finished,
                to_run,
            } => log.push(("unit", finished, to_run, usize::from(ok), unit.id())),
        },
        &flag,
    )
    .unwrap();
    (outcome, log)
}

#[test]
fn runs_every_planned_unit_once_and_resumes() {
    let d = temp("explore-run");
    let db = d.join("a.db");
    let req = request(2);
    let planned: Vec<WorkUnit> = req.plan().unwrap().units();
    assert_eq!(
        planned.len(),
        2,
        "one minimal cell per family in the quick plan"
    );
    let (outcome, log) = run(&db, &req, false);
    assert_eq!(log[0], ("started", 2, 0, 2, String::new()));
    assert_eq!(log.len(), 3);
    let mut ids: Vec<String> = log[1..].iter().map(|e| e.4.clone()).collect();
    ids.sort();
    assert_eq!(ids, ["IH83/1x1", "IH90/1x1"]);
    assert_eq!(
        log[1..].iter().map(|e| (e.1, e.2, e.3)).collect::<Vec<_>>(),
        [(1, 2, 1), (2, 2, 1)]
    );
    assert_eq!(
        (outcome.committed, outcome.skipped, outcome.not_run),
        (2, 0, 0)
    );
    assert!(outcome.failures.is_empty() && !outcome.cancelled);
    assert_eq!(outcome.stats.work_units, 2);

    // What was committed is exactly what the library computes for each unit.
    let store = Store::open_read(&db, Check::Full).unwrap();
    for unit in &planned {
        let expected = UnitRecords::from_outcome(
            &isogami::catalog::run_unit(unit.family, unit.dims, &req.settings).unwrap(),
            0.0,
        )
        .unwrap();
        let stored = store.designs_of_unit(&unit.id()).unwrap();
        let mut want = expected.designs.clone();
        want.sort_by(|a, b| a.summary().spec.cmp(&b.summary().spec));
        assert!(!want.is_empty(), "{unit} keeps designs");
        assert_eq!(stored, want, "{unit}");
    }
    assert_eq!(outcome.stats.designs, store.design_count().unwrap());
    drop(store);

    // A rerun skips both units and changes nothing.
    let before = std::fs::read(&db).unwrap();
    let (again, log) = run(&db, &req, false);
    assert_eq!(log, [("started", 2, 2, 0, String::new())]);
    assert_eq!((again.committed, again.skipped), (0, 2));
    assert_eq!(std::fs::read(&db).unwrap(), before);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn cancelled_run_starts_nothing_and_a_rerun_finishes() {
    let d = temp("explore-cancel");
    let db = d.join("a.db");
    let req = request(1);
    let (outcome, log) = run(&db, &req, true);
    assert_eq!(log, [("started", 2, 0, 2, String::new())]);
    assert!(outcome.cancelled);
    assert_eq!((outcome.committed, outcome.not_run), (0, 2));
    assert_eq!(outcome.stats.work_units, 0);
    let (outcome, _) = run(&db, &req, false);
    assert_eq!((outcome.committed, outcome.skipped), (2, 0));
    assert!(!outcome.cancelled);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bad_requests_are_refused_before_the_file_is_made() {
    let d = temp("explore-bad");
    let db = d.join("a.db");
    let flag = AtomicBool::new(false);
    for (req, what) in [
        (
            ExploreRequest {
                jobs: 0,
                ..request(1)
            },
            "jobs",
        ),
        (
            ExploreRequest {
                settings: isogami::catalog::CatalogSettings {
                    samples: 0,
                    ..quick_settings()
                },
                ..request(1)
            },
            "samples",
        ),
    ] {
        let e = explore_into(&db, &req, &mut |_| {}, &flag).unwrap_err();
        assert!(
            matches!(&e, StoreError::InvalidSettings(s) if s.name == what),
            "{e}"
        );
        assert!(!db.exists());
    }
    // The plan of a request is the library's plan.
    let req = request(1);
    assert_eq!(
        req.plan().unwrap(),
        ExplorePlan::new(&req.families, None, &req.settings.topology, None).unwrap()
    );
    std::fs::remove_dir_all(&d).unwrap();
}

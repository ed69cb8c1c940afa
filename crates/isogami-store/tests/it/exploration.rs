//! The exploration driver `explore_into`: events, commits, resumption, cancellation.

use crate::common;

use common::{quick_settings, temp};
use isogami::explore::{ExplorePlan, WorkUnit};
use isogami::tiling::Family;
use isogami_store::{
    explore_into, Check, ExploreEvent, ExploreRequest, Store, StoreError, UnitRecords,
};
use std::sync::atomic::AtomicBool;

/// Two cheap families of the quick exploration.
fn request(jobs: usize) -> ExploreRequest {
    common::two_family_request(jobs)
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
    let d_guard = temp("explore-run");
    let d = d_guard.path();
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
}

#[test]
fn cancelled_run_starts_nothing_and_a_rerun_finishes() {
    let d_guard = temp("explore-cancel");
    let d = d_guard.path();
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
}

#[test]
fn bad_requests_are_refused_before_the_file_is_made() {
    let d_guard = temp("explore-bad");
    let d = d_guard.path();
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
}

/// Everything stored about a unit but its timings: the design records (spec, summary, full
/// deployment report and linkage analysis) and the stage counts.
fn unit_content(
    store: &Store,
    id: &str,
) -> (Vec<isogami_store::DesignRecord>, Vec<(String, u64, u64)>) {
    let stages = store
        .work_units()
        .unwrap()
        .into_iter()
        .find(|(u, _)| u.id == id)
        .map(|(_, st)| {
            st.iter()
                .map(|x| (x.stage.clone(), x.count_in, x.count_out))
                .collect()
        })
        .unwrap_or_default();
    (store.designs_of_unit(id).unwrap(), stages)
}

#[test]
fn one_and_two_jobs_store_the_same_designs() {
    let d_guard = temp("explore-jobs");
    let d = d_guard.path();
    // Quick settings on cells up to 2x2 of at most 10 edges: a low-symmetry hexagon cell
    // (IH28, hundreds of unique topologies deployed in parallel), rotating squares on 2x2,
    // triangle cells.
    let mut settings = quick_settings();
    settings.topology.max_dims = 2;
    settings.topology.max_edges = 10;
    settings.samples = 3;
    let req = |jobs: usize| ExploreRequest {
        settings,
        families: [28, 76, 83, 90]
            .iter()
            .map(|&n| Family::from_number(n).unwrap())
            .collect(),
        cells: None,
        shard: None,
        jobs,
        parts: 1,
    };
    let plan = req(1).plan().unwrap();
    assert!(plan.all.len() >= 6, "{} units", plan.all.len());
    let (a, b) = (d.join("one.db"), d.join("two.db"));
    let (one, _) = run(&a, &req(1), false);
    let (two, _) = run(&b, &req(2), false);
    assert_eq!(
        (one.committed, two.committed),
        (plan.all.len(), plan.all.len())
    );
    let (sa, sb) = (
        Store::open_read(&a, Check::Full).unwrap(),
        Store::open_read(&b, Check::Full).unwrap(),
    );
    let mut designs = 0;
    for unit in &plan.all {
        let (ca, cb) = (unit_content(&sa, &unit.id()), unit_content(&sb, &unit.id()));
        assert!(!ca.1.is_empty(), "{unit} stored");
        designs += ca.0.len();
        assert_eq!(ca, cb, "{unit}");
    }
    assert!(designs > 10, "{designs} designs");
    assert_eq!(sa.stats().unwrap().designs, sb.stats().unwrap().designs);
}

#[test]
fn runs_with_other_edge_caps_do_not_mix() {
    let d_guard = temp("explore-caps");
    let d = d_guard.path();
    let db = d.join("a.db");
    let mut req = request(1);
    run(&db, &req, false);
    let before = std::fs::read(&db).unwrap();
    req.settings.topology.max_edges = 11;
    let e = explore_into(&db, &req, &mut |_| {}, &AtomicBool::new(false)).unwrap_err();
    let text = e.to_string();
    assert!(matches!(e, StoreError::SettingsMismatch(_)), "{text}");
    assert!(
        text.contains("max_edges 12 in the file, 11 in this run"),
        "{text}"
    );
    assert_eq!(std::fs::read(&db).unwrap(), before, "the file is unchanged");
    // A database of the other cap cannot be merged into it either.
    let other = d.join("b.db");
    run(&other, &req, false);
    let mut w = isogami_store::StoreWriter::open(&db, None, Check::Full).unwrap();
    let e = w
        .merge_from(&Store::open_read(&other, Check::Full).unwrap())
        .unwrap_err();
    assert!(
        e.to_string()
            .contains("max_edges 12 in the target, 11 in the input"),
        "{e}"
    );
    drop(w);
}

#[test]
fn a_requested_cell_over_the_cap_is_refused_before_the_file_is_made() {
    let d_guard = temp("explore-over-cap");
    let d = d_guard.path();
    let db = d.join("a.db");
    let mut req = request(1);
    req.families = vec![Family::from_number(76).unwrap()];
    req.cells = Some(vec![isogami::cell::CellDims::new(2, 2).unwrap()]);
    req.settings.topology.max_dims = 2;
    req.settings.topology.max_edges = 6;
    let e = explore_into(&db, &req, &mut |_| {}, &AtomicBool::new(false)).unwrap_err();
    assert!(
        matches!(
            e,
            StoreError::Plan(isogami::explore::ExploreError::CellsOverCap {
                edges: 8,
                max_edges: 6,
                ..
            })
        ),
        "{e}"
    );
    assert!(!db.exists());
}

#[test]
fn a_negative_zero_time_is_stored_as_zero_and_reads_back_intact() {
    let d_guard = temp("explore-negative-zero");
    let d = d_guard.path();
    let db = d.join("a.db");
    let mut outcome = isogami::catalog::run_unit(
        Family::from_number(90).unwrap(),
        isogami::cell::CellDims::MINIMAL,
        &quick_settings(),
    )
    .unwrap();
    for s in &mut outcome.stages {
        s.seconds = -0.0;
    }
    let records = UnitRecords::from_outcome(&outcome, -0.0).unwrap();
    let run = isogami_store::RunInfo {
        tool_version: "0.1.0",
        settings: "{}",
    };
    let mut w = isogami_store::StoreWriter::open(&db, Some(run), Check::Full).unwrap();
    w.commit_unit(&records).unwrap();
    drop(w);
    let store = Store::open_read(&db, Check::Full).unwrap();
    let units = store.work_units().unwrap();
    assert_eq!(units.len(), 1);
    assert!(units[0].1.iter().all(|s| s.seconds.to_bits() == 0));
}

/// Issue 21: a fresh deploy of every stored design equals its stored summary (every summary
/// is taken over all accepted states, so the stored frame count does not matter).
#[test]
fn a_fresh_deploy_of_every_stored_design_equals_its_row() {
    let dir_guard = temp("fresh-deploy");
    let dir = dir_guard.path();
    let db = dir.join("x.db");
    let req = request(2);
    explore_into(&db, &req, &mut |_| {}, &AtomicBool::new(false)).unwrap();
    let store = Store::open_read(&db, Check::Full).unwrap();
    let specs: Vec<String> = store
        .summaries()
        .unwrap()
        .into_iter()
        .map(|s| s.spec)
        .collect();
    assert!(specs.len() >= 2, "{specs:?}");
    let mut deploy = req.settings.deploy_request();
    for frames in [7, 60] {
        deploy.frames = isogami::api::FrameSelection::Evenly(frames);
        for spec in &specs {
            let stored = store.design(spec).unwrap().unwrap();
            let design: isogami::topology::Design = spec.parse().unwrap();
            assert_eq!(&design.to_string(), spec, "stored specs are canonical");
            let fresh = isogami::api::deploy(&design, &deploy, &mut |_| true)
                .unwrap()
                .report;
            let (a, b) = (&stored.report, &fresh);
            for (name, x, y) in [
                ("max_expansion", a.max_expansion, b.max_expansion),
                ("min_expansion", a.min_expansion, b.min_expansion),
                ("max_area_ratio", a.max_area_ratio, b.max_area_ratio),
                (
                    "max_tile_rotation",
                    a.max_tile_rotation,
                    b.max_tile_rotation,
                ),
                ("min_clearance", a.min_clearance, b.min_clearance),
            ] {
                assert!(
                    (x - y).abs() <= 1e-12 * x.abs().max(1.0),
                    "{spec} {name}: {x} vs {y}"
                );
            }
            assert_eq!(a.poisson_range(), b.poisson_range(), "{spec}");
            assert_eq!(a.behaviour, b.behaviour, "{spec}");
        }
    }
}

//! What is written reads back exactly: typed reports and linkages, work units, user designs,
//! atomic units, resumption, merging.

use crate::common;

use common::{entry, outcomes, real_db, run, temp};
use isogami_store::{
    Check, DesignRecord, Origin, Store, StoreError, StoreWriter, UnitRecords, SCHEMA_VERSION,
};

#[test]
fn reports_and_linkages_read_back_as_the_library_types() {
    let path_guard = temp("typed");
    let path = path_guard.path().join("db");
    real_db(&path);
    let store = Store::open_read(&path, Check::Full).unwrap();
    let mut n = 0;
    for unit in outcomes() {
        for written in &unit.designs {
            let spec = &written.summary().spec;
            let read = store.design(spec).unwrap().expect("stored design");
            assert_eq!(&read.summary, written.summary());
            // The library value that went in: re-serialising what came out gives identical JSON
            // (every field, every bit of every number).
            assert_eq!(
                serde_json::to_string(&read.report).unwrap(),
                written.report_json()
            );
            let linkages = read.linkages.expect("linkages stored");
            assert_eq!(
                serde_json::to_string(&linkages).unwrap(),
                written.linkages_json().unwrap()
            );
            n += 1;
        }
    }
    assert!(n >= 3, "{n} designs");
    // And equal to the entry computed by the library, field by field where types allow.
    let e = entry();
    let read = store.design(&e.design.to_string()).unwrap().unwrap();
    assert_eq!(read.linkages.as_ref(), Some(&e.linkages));
    assert_eq!(read.report.end_reason, e.report.end_reason);
    assert_eq!(read.report.frames.len(), e.report.frames.len());
    for (a, b) in read.report.frames.iter().zip(&e.report.frames) {
        assert_eq!(a.measures, b.measures);
        assert_eq!(a.f, b.f);
        assert_eq!(a.t.to_bits(), b.t.to_bits());
    }
    assert_eq!(
        serde_json::to_value(&read.report).unwrap(),
        serde_json::to_value(&e.report).unwrap()
    );
    // The summary agrees with the report.
    let s = &read.summary;
    assert_eq!(s.max_expansion, e.report.max_expansion);
    assert_eq!(s.steps, e.report.steps as u64);
    assert_eq!(s.behaviour, e.report.behaviour);
    assert_eq!(s.end_reason, "contact_limit");
    assert_eq!(
        s.linkage_signature.as_deref(),
        Some(e.linkages.signature.as_str())
    );
    assert_eq!(s.origin, Origin::Explored);
    assert_eq!((s.dof, e.report.dof), (1, 1));
    assert!(store.design("IH1::1x1:---").unwrap().is_none());
}

#[test]
fn poisson_ratio_range_is_the_reports_over_every_state() {
    let e = entry();
    let r = DesignRecord::from_entry(e).unwrap();
    let (lo, hi) = (
        r.summary().poisson_min.unwrap(),
        r.summary().poisson_max.unwrap(),
    );
    assert_eq!(Some((lo, hi)), e.report.poisson_range());
    // The report's range is over every accepted state, so it holds every opened frame's
    // ratio (the frames are some of those states).
    let open = isogami_store::POISSON_OPEN_FRACTION * e.report.max_expansion;
    let ratios: Vec<f64> = e
        .report
        .frames
        .iter()
        .filter(|f| f.measures.max_expansion >= open)
        .map(|f| -f.measures.min_expansion / f.measures.max_expansion)
        .collect();
    assert!(!ratios.is_empty());
    for x in ratios {
        assert!(lo <= x && x <= hi, "{lo} <= {x} <= {hi}");
    }
}

#[test]
fn records_with_non_finite_numbers_are_refused() {
    let e = entry();
    let mut report = e.report.clone();
    report.max_tile_rotation = f64::NAN;
    match DesignRecord::from_parts(&e.design, &e.topology, Origin::User, &report, None) {
        Err(StoreError::InvalidRecord { problem, .. }) => {
            assert!(problem.contains("max_tile_rotation"), "{problem}")
        }
        other => panic!("expected a refusal, got {other:?}"),
    }
    // A NaN deep inside a frame would be written as null and never read back.
    let mut report = e.report.clone();
    report.frames[3].measures.lattice_rotation = f64::INFINITY;
    assert!(matches!(
        DesignRecord::from_parts(&e.design, &e.topology, Origin::User, &report, None),
        Err(StoreError::InvalidRecord { .. })
    ));
}

#[test]
fn units_round_trip_and_resume_skips_them() {
    let path_guard = temp("units");
    let path = path_guard.path().join("db");
    real_db(&path);
    let w = StoreWriter::open(&path, Some(run()), Check::Full).unwrap();
    let done = w.done_units().unwrap();
    for u in outcomes() {
        assert!(done.contains(&u.unit.id));
    }
    let units = w.work_units().unwrap();
    assert_eq!(units.len(), 2);
    for (u, (read, stages)) in outcomes().iter().zip(&units) {
        assert_eq!(&u.unit, read);
        assert_eq!(&u.stages, stages);
        assert_eq!(w.designs_of_unit(&u.unit.id).unwrap(), {
            let mut d = u.designs.clone();
            d.sort_by(|a, b| a.summary().spec.cmp(&b.summary().spec));
            d
        });
    }
    let st = w.stats().unwrap();
    let designs: usize = outcomes().iter().map(|u| u.designs.len()).sum();
    assert_eq!((st.work_units, st.designs as usize), (2, designs));
    assert_eq!(st.schema_version, SCHEMA_VERSION);
}

#[test]
fn a_failed_unit_leaves_nothing_behind() {
    let path_guard = temp("atomic");
    let path = path_guard.path().join("db");
    let mut w = StoreWriter::open(&path, Some(run()), Check::Full).unwrap();
    // The unit repeats a design: the second insert fails and the whole unit rolls back.
    let mut unit = outcomes()[0].clone();
    unit.designs.push(unit.designs[0].clone());
    assert!(matches!(
        w.commit_unit(&unit),
        Err(StoreError::DuplicateSpec(_))
    ));
    assert!(w.done_units().unwrap().is_empty());
    assert_eq!(w.design_count().unwrap(), 0);
    assert!(w.work_units().unwrap().is_empty());
    // The same unit without the repeat commits.
    w.commit_unit(&outcomes()[0]).unwrap();
    assert_eq!(w.done_units().unwrap().len(), 1);
}

#[test]
fn user_designs_are_saved_marked_and_unique() {
    let path_guard = temp("user");
    let path = path_guard.path().join("db");
    real_db(&path);
    let e = entry();
    let mut params = e.design.params.clone();
    params[0] *= 1.01;
    let design = e.design.at_params(&params);
    let rec = DesignRecord::from_parts(&design, &design.to_string(), Origin::User, &e.report, None)
        .unwrap();
    let mut w = StoreWriter::open(&path, None, Check::Quick).unwrap();
    w.save_user_design(&rec).unwrap();
    assert!(matches!(
        w.save_user_design(&rec),
        Err(StoreError::DuplicateSpec(_))
    ));
    // An explored record is not a user design, and a unit's designs must be explored ones.
    let explored = DesignRecord::from_entry(e).unwrap();
    assert!(matches!(
        w.save_user_design(&explored),
        Err(StoreError::InvalidRecord { .. })
    ));
    let mut unit: UnitRecords = outcomes()[0].clone();
    unit.unit.id = "IH1/1x1".into();
    unit.designs = vec![rec.clone()];
    assert!(matches!(
        w.commit_unit(&unit),
        Err(StoreError::InvalidRecord { .. })
    ));
    drop(w);
    let r = Store::open_read(&path, Check::Full).unwrap();
    let read = r.design(&design.to_string()).unwrap().unwrap();
    assert_eq!(read.summary.origin, Origin::User);
    assert!(read.linkages.is_none());
    assert_eq!(r.user_designs().unwrap(), vec![rec]);
    assert_eq!(r.stats().unwrap().user_designs, 1);
}

#[test]
fn other_settings_are_refused() {
    let path_guard = temp("settings");
    let path = path_guard.path().join("db");
    real_db(&path);
    let other = isogami_store::RunInfo {
        tool_version: "0.1.0",
        settings: "{\"threshold\":0.5}",
    };
    assert!(matches!(
        StoreWriter::open(&path, Some(other), Check::Quick),
        Err(StoreError::SettingsMismatch(_))
    ));
}

#[test]
fn shards_merge_into_the_unsharded_result() {
    let dir_guard = temp("merge");
    let dir = dir_guard.path();
    let whole = dir.join("whole.db");
    real_db(&whole);
    let shards: Vec<_> = (0..2).map(|i| dir.join(format!("shard{i}.db"))).collect();
    for (u, s) in outcomes().iter().zip(&shards) {
        let mut w = StoreWriter::open(s, Some(run()), Check::Quick).unwrap();
        w.commit_unit(u).unwrap();
    }
    // A user design in one shard comes along.
    let e = entry();
    let mut params = e.design.params.clone();
    params[0] *= 0.99;
    let design = e.design.at_params(&params);
    let user = DesignRecord::from_parts(&design, "user", Origin::User, &e.report, None).unwrap();
    StoreWriter::open(&shards[1], None, Check::Quick)
        .unwrap()
        .save_user_design(&user)
        .unwrap();
    let merged = dir.join("merged.db");
    let mut m = StoreWriter::open(&merged, None, Check::Full).unwrap();
    let mut added = 0;
    for s in &shards {
        let r = m
            .merge_from(&Store::open_read(s, Check::Full).unwrap())
            .unwrap();
        assert_eq!(r.units_added, 1);
        added += r.designs_added;
    }
    let again = m
        .merge_from(&Store::open_read(&shards[1], Check::Full).unwrap())
        .unwrap();
    assert_eq!(
        (again.units_added, again.units_skipped, again.designs_added),
        (0, 1, 0)
    );
    assert_eq!(
        (again.user_designs_added, again.user_designs_skipped),
        (0, 1)
    );
    let w = Store::open_read(&whole, Check::Full).unwrap();
    assert_eq!(added, w.design_count().unwrap());
    assert_eq!(m.work_units().unwrap(), w.work_units().unwrap());
    for u in outcomes() {
        assert_eq!(
            m.designs_of_unit(&u.unit.id).unwrap(),
            w.designs_of_unit(&u.unit.id).unwrap()
        );
    }
    assert_eq!(m.user_designs().unwrap(), vec![user]);
    assert_eq!(m.settings().unwrap(), w.settings().unwrap());
    // A shard made with other settings is refused.
    let odd = dir.join("odd.db");
    StoreWriter::open(
        &odd,
        Some(isogami_store::RunInfo {
            tool_version: "0.1.0",
            settings: "{}",
        }),
        Check::Quick,
    )
    .unwrap();
    assert!(matches!(
        m.merge_from(&Store::open_read(&odd, Check::Full).unwrap()),
        Err(StoreError::SettingsMismatch(_))
    ));
}

#[test]
fn finite_sheet_figures_read_back_and_user_designs_have_none() {
    let path_guard = temp("finite");
    let path = path_guard.path().join("db");
    real_db(&path);
    let r = Store::open_read(&path, Check::Full).unwrap();
    let all = r.summaries().unwrap();
    assert!(!all.is_empty());
    for unit in outcomes() {
        for d in &unit.designs {
            let read = r.design(&d.summary().spec).unwrap().unwrap().summary;
            assert_eq!(&read, d.summary());
            assert!(read.finite_raw_dof.is_some(), "{}", read.spec);
        }
    }
    let e = entry();
    let f = e.finite.unwrap();
    let rec = DesignRecord::from_entry(e).unwrap();
    assert_eq!(rec.summary().finite_raw_dof, Some(f.raw_dof as u32));
    assert_eq!(rec.summary().finite_covered, f.covered);
    let user = DesignRecord::from_parts(&e.design, "user", Origin::User, &e.report, None).unwrap();
    assert_eq!(
        (user.summary().finite_raw_dof, user.summary().finite_covered),
        (None, None)
    );
    // A covered fraction that is not a share is refused.
    let bad = isogami::catalog::FiniteFigures {
        raw_dof: 1,
        covered: Some(f64::NAN),
    };
    assert!(matches!(
        user.with_finite(Some(&bad)),
        Err(StoreError::InvalidRecord { .. })
    ));
    let stats = r.stats().unwrap();
    assert_eq!(stats.finite.measured, all.len() as u64);
    assert_eq!(
        stats.finite.completed,
        all.iter().filter(|s| s.finite_covered.is_some()).count() as u64
    );
}

//! The design database: round trips, atomic work units, versioning, merging.

use isogami_store::{DesignRecord, StageCount, Store, StoreError, WorkUnitRecord, SCHEMA_VERSION};
use std::path::PathBuf;

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("isogami-store-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("db.sqlite")
}

fn unit(id: &str) -> WorkUnitRecord {
    WorkUnitRecord {
        id: id.into(),
        family: id.split('/').next().unwrap().into(),
        cell: "1x1".into(),
        kind: "topology+shapes".into(),
        seconds: 0.5,
    }
}

fn stages(n: u64) -> Vec<StageCount> {
    vec![
        StageCount {
            stage: "masks".into(),
            count_in: n,
            count_out: n / 2,
            seconds: 0.1,
        },
        StageCount {
            stage: "mobility".into(),
            count_in: n / 2,
            count_out: 3,
            seconds: 0.2,
        },
    ]
}

fn design(spec: &str) -> DesignRecord {
    DesignRecord {
        spec: spec.into(),
        family: spec.split(':').next().unwrap().into(),
        params: "[]".into(),
        cell: "1x1".into(),
        joints: "ab".into(),
        topology: spec.into(),
        behaviour: Some("isotropic_auxetic".into()),
        end_reason: "contact_limit".into(),
        max_expansion: 0.4142,
        min_expansion: 0.0,
        max_area_ratio: 2.0,
        max_tile_rotation: 1.57,
        steps: 100,
        linkage_signature: Some("2×4-bar".into()),
        report: "{\"frames\":[]}".into(),
        linkages: None,
    }
}

#[test]
fn units_round_trip_and_resume_skips_them() {
    let path = temp("roundtrip");
    {
        let mut s = Store::open(&path, "0.1.0", "{\"threshold\":0.1}").unwrap();
        s.commit_unit(
            &unit("IH1/1x1"),
            &stages(64),
            &[design("IH1::1x1:ab"), design("IH1::1x1:ba")],
        )
        .unwrap();
    }
    let s = Store::open(&path, "0.1.0", "{\"threshold\":0.1}").unwrap();
    assert!(s.done_units().unwrap().contains("IH1/1x1"));
    let designs = s.designs().unwrap();
    assert_eq!(designs.len(), 2);
    assert_eq!(designs[0], design("IH1::1x1:ab"));
    let units = s.work_units().unwrap();
    assert_eq!(units[0].1, stages(64));
    let st = s.stats().unwrap();
    assert_eq!((st.work_units, st.designs), (1, 2));
    assert_eq!(st.by_behaviour["isotropic_auxetic"], 2);
    assert_eq!(st.stages[0].count_in, 64);
}

#[test]
fn a_failed_unit_leaves_nothing_behind() {
    let path = temp("atomic");
    let mut s = Store::open(&path, "0.1.0", "{}").unwrap();
    // The second design repeats the first's key: the whole unit must roll back.
    let err = s.commit_unit(
        &unit("IH2/1x1"),
        &stages(8),
        &[design("IH2::1x1:ab"), design("IH2::1x1:ab")],
    );
    assert!(err.is_err());
    assert!(s.done_units().unwrap().is_empty());
    assert!(s.designs().unwrap().is_empty());
    assert!(s.work_units().unwrap().is_empty());
}

#[test]
fn other_settings_and_schema_versions_are_refused() {
    let path = temp("versions");
    drop(Store::open(&path, "0.1.0", "{\"a\":1}").unwrap());
    assert!(matches!(
        Store::open(&path, "0.1.0", "{\"a\":2}"),
        Err(StoreError::SettingsMismatch(_))
    ));
    bump_schema_version(&path);
    match Store::open_any(&path) {
        Err(StoreError::SchemaVersion { found, expected }) => {
            assert_eq!((found, expected), (SCHEMA_VERSION + 1, SCHEMA_VERSION));
        }
        other => panic!("expected a schema version error, got {other:?}"),
    }
}

/// Pretends the file was written by a future schema version.
fn bump_schema_version(path: &std::path::Path) {
    let s = Store::open_any(path).unwrap();
    s.set_meta_for_tests("schema_version", &(SCHEMA_VERSION + 1).to_string())
        .unwrap();
}

#[test]
fn shards_merge_into_the_unsharded_result() {
    let all = ["IH1/1x1", "IH2/1x1", "IH3/1x1", "IH4/1x1"];
    let whole = temp("whole");
    {
        let mut s = Store::open(&whole, "0.1.0", "{}").unwrap();
        for id in all {
            let fam = id.split('/').next().unwrap();
            s.commit_unit(&unit(id), &stages(16), &[design(&format!("{fam}::1x1:ab"))])
                .unwrap();
        }
    }
    let shards: Vec<PathBuf> = (0..2).map(|i| temp(&format!("shard{i}"))).collect();
    for (k, id) in all.iter().enumerate() {
        let mut s = Store::open(&shards[k % 2], "0.1.0", "{}").unwrap();
        let fam = id.split('/').next().unwrap();
        s.commit_unit(&unit(id), &stages(16), &[design(&format!("{fam}::1x1:ab"))])
            .unwrap();
    }
    let merged = temp("merged");
    let mut m = Store::open_any(&merged).unwrap();
    let r0 = m.merge_from(&shards[0]).unwrap();
    let r1 = m.merge_from(&shards[1]).unwrap();
    assert_eq!((r0.units_added, r1.units_added), (2, 2));
    // Merging again adds nothing.
    let again = m.merge_from(&shards[1]).unwrap();
    assert_eq!(
        (again.units_added, again.units_skipped, again.designs_added),
        (0, 2, 0)
    );
    let w = Store::open_any(&whole).unwrap();
    assert_eq!(m.designs().unwrap(), w.designs().unwrap());
    let strip = |v: Vec<(WorkUnitRecord, Vec<StageCount>)>| v;
    assert_eq!(
        strip(m.work_units().unwrap()),
        strip(w.work_units().unwrap())
    );
    assert_eq!(m.settings().unwrap(), w.settings().unwrap());
}

//! Shard databases: the shard record an `explore --shard` run leaves, resuming without
//! duplicates, refusing another plan, and proving a set of shards complete before a merge.

use crate::common;

use common::{quick_settings, temp};
use isogami::explore::Shard;
use isogami::tiling::Family;
use isogami_store::{
    check_shard_set, explore_into, Check, ExploreOutcome, ExploreRequest, ShardRecord,
    ShardSetError, Store, StoreError,
};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// Four cheap families of the quick exploration: four units, one minimal cell each.
fn request(families: &[u32], shard: Option<(usize, usize)>) -> ExploreRequest {
    ExploreRequest {
        settings: quick_settings(),
        families: families
            .iter()
            .map(|&n| Family::from_number(n).unwrap())
            .collect(),
        cells: None,
        shard: shard.map(|(i, n)| Shard::new(i, n).unwrap()),
        jobs: 1,
        parts: 1,
    }
}

const FAMILIES: [u32; 4] = [83, 84, 90, 91];

fn explore(db: &Path, req: &ExploreRequest, cancel: bool) -> Result<ExploreOutcome, StoreError> {
    explore_into(db, req, &mut |_| {}, &AtomicBool::new(cancel))
}

fn open(db: &Path) -> Store {
    Store::open_read(db, Check::Full).unwrap()
}

fn check(paths: &[&PathBuf]) -> Result<(), ShardSetError> {
    let stores: Vec<Store> = paths.iter().map(|p| open(p)).collect();
    let inputs: Vec<(&Path, &Store)> = paths.iter().map(|p| p.as_path()).zip(&stores).collect();
    check_shard_set(&inputs).unwrap()
}

#[test]
fn a_shard_records_its_plan_and_reruns_add_nothing() {
    let d_guard = temp("shard-record");
    let d = d_guard.path();
    let db = d.join("s1.db");
    let req = request(&FAMILIES, Some((1, 2)));
    let first = explore(&db, &req, false).unwrap();
    assert_eq!((first.planned, first.committed), (2, 2));
    let store = open(&db);
    let record = store
        .shard()
        .unwrap()
        .expect("a shard database has a record");
    assert_eq!(record, ShardRecord::of_plan(&req.plan().unwrap()).unwrap());
    assert_eq!((record.index, record.count, record.plan_units), (1, 2, 4));
    let ids: Vec<String> = req.plan().unwrap().units().iter().map(|u| u.id()).collect();
    assert_eq!(record.units, ids);
    // Positions 1 and 3 of the plan IH83, IH84, IH90, IH91.
    assert_eq!(ids, ["IH84/1x1", "IH91/1x1"]);
    let status = store.shard_status().unwrap().unwrap();
    assert!(status.complete(), "{status:?}");
    assert_eq!(status.done, 2);
    assert_eq!(store.stats().unwrap().shard, Some(status));
    let designs = store.design_count().unwrap();
    drop(store);

    // Rerunning the shard commits nothing and leaves the file byte for byte as it was.
    let before = std::fs::read(&db).unwrap();
    let again = explore(&db, &req, false).unwrap();
    assert_eq!((again.committed, again.skipped), (0, 2));
    assert_eq!(std::fs::read(&db).unwrap(), before);
    assert_eq!(open(&db).design_count().unwrap(), designs);

    // Whole runs have no record.
    let whole = d.join("whole.db");
    explore(&whole, &request(&[83], None), false).unwrap();
    assert_eq!(open(&whole).shard().unwrap(), None);
    assert_eq!(open(&whole).stats().unwrap().shard, None);
}

#[test]
fn another_plan_into_a_shard_database_is_refused_unchanged() {
    let d_guard = temp("shard-other");
    let d = d_guard.path();
    let db = d.join("s0.db");
    explore(&db, &request(&FAMILIES, Some((0, 2))), false).unwrap();
    let before = std::fs::read(&db).unwrap();
    for req in [
        request(&FAMILIES, Some((1, 2))),
        request(&FAMILIES, Some((0, 3))),
        request(&[83, 84, 90], Some((0, 2))),
        request(&FAMILIES, None),
    ] {
        let e = explore(&db, &req, false).unwrap_err();
        assert!(matches!(e, StoreError::OtherShard { .. }), "{e}");
        assert!(
            e.to_string().contains("shard 0/2 (2 of a 4-unit run)"),
            "{e}"
        );
        assert_eq!(std::fs::read(&db).unwrap(), before);
    }
    // A database without a record takes the shard's when its units belong to the shard (a
    // shard begun before records existed), and is refused when they do not.
    let old = d.join("old.db");
    explore(&old, &request(&[83], None), false).unwrap();
    let e = explore(&old, &request(&FAMILIES, Some((1, 2))), false).unwrap_err();
    assert!(e.to_string().contains("work unit IH83/1x1"), "{e}");
    let resumed = explore(&old, &request(&FAMILIES, Some((0, 2))), false).unwrap();
    assert_eq!((resumed.skipped, resumed.committed), (1, 1));
    assert_eq!(open(&old).shard().unwrap().map(|r| r.index), Some(0));
}

#[test]
fn a_set_of_shards_is_proved_complete_or_the_problem_named() {
    let d_guard = temp("shard-set");
    let d = d_guard.path();
    let n = 3;
    let paths: Vec<PathBuf> = (0..n).map(|i| d.join(format!("s{i}.db"))).collect();
    for (i, p) in paths.iter().enumerate() {
        explore(p, &request(&FAMILIES, Some((i, n))), false).unwrap();
    }
    let all: Vec<&PathBuf> = paths.iter().collect();
    assert_eq!(check(&all), Ok(()));
    assert_eq!(
        check(&[&paths[2], &paths[0], &paths[1]]),
        Ok(()),
        "any order"
    );

    // A missing shard.
    assert_eq!(
        check(&[&paths[0], &paths[2]]),
        Err(ShardSetError::Missing { index: 1, count: 3 })
    );
    // A shard held twice.
    let copy = d.join("copy.db");
    std::fs::copy(&paths[1], &copy).unwrap();
    assert!(matches!(
        check(&[&paths[0], &paths[1], &copy, &paths[2]]),
        Err(ShardSetError::Duplicate { index: 1, .. })
    ));
    // An incomplete shard: its run was cancelled before any unit started.
    let empty = d.join("empty1.db");
    let cancelled = explore(&empty, &request(&FAMILIES, Some((1, n))), true).unwrap();
    assert_eq!(cancelled.committed, 0);
    let e = check(&[&paths[0], &empty, &paths[2]]).unwrap_err();
    assert_eq!(
        e,
        ShardSetError::Incomplete {
            path: empty.display().to_string(),
            index: 1,
            count: 3,
            progress: "0 of 1 work units; IH84/1x1 missing".into(),
        }
    );
    assert!(e.to_string().contains("shard 1/3 is incomplete"), "{e}");
    // A shard of another run (other families), and a database that is no shard at all.
    let other = d.join("other.db");
    explore(&other, &request(&[83, 84, 90], Some((1, n))), false).unwrap();
    assert!(matches!(
        check(&[&paths[0], &other, &paths[2]]),
        Err(ShardSetError::OtherRun { .. })
    ));
    let whole = d.join("whole.db");
    explore(&whole, &request(&[83], None), false).unwrap();
    assert!(matches!(
        check(&[&paths[0], &paths[1], &paths[2], &whole]),
        Err(ShardSetError::NotAShard { .. })
    ));
    // Databases without records are merged as they are.
    assert_eq!(check(&[&whole]), Ok(()));
}

//! Databases of schema version 2 (joint strings in the shape-dependent edge labels of isogami
//! before issue 21) are refused by every open, naming the command that migrates them, and
//! `migrate` carries them into a new file: the catalogue explored again with the old plan and
//! settings, user designs translated to the same physical joints and deployed again.

use crate::common;

use common::temp;
use isogami::api::{deploy, linkages, DeployRequest};
use isogami::topology::Design;
use isogami_store::{
    explore_into, migrate, Check, DesignRecord, Origin, Store, StoreError, StoreWriter,
};
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// A spec that old isogami wrote at IH9 p1 = 0.500000001, where its labels differed from
/// today's (tile 1 sat one lattice step away).
const OLD_SPEC: &str = "IH9:0.12239750492,0.500000001,0.225335752741:2x1:---abb--a-bb";

/// A version-2 file as old isogami left it: the quick exploration of IH83 and IH90 and one
/// user design saved under `OLD_SPEC`.
fn old_database(path: &Path) {
    let request = common::two_family_request(1);
    explore_into(path, &request, &mut |_| {}, &AtomicBool::new(false)).unwrap();
    // Old isogami's row: the joint string as it wrote it (whatever today's code would make of
    // it is irrelevant to the migration, which re-deploys the translated design).
    let old: Design = OLD_SPEC.parse().unwrap();
    let run = deploy(&old, &DeployRequest::default(), &mut |_| true).unwrap();
    let record = DesignRecord::from_parts(
        &old,
        OLD_SPEC,
        Origin::User,
        &run.report,
        linkages(&old).ok().as_ref(),
    )
    .unwrap();
    let mut w = StoreWriter::open(path, None, Check::Full).unwrap();
    w.save_user_design(&record).unwrap();
    drop(w);
    rusqlite::Connection::open(path)
        .unwrap()
        .execute(
            "UPDATE meta SET value = '2' WHERE key = 'schema_version'",
            [],
        )
        .unwrap();
}

#[test]
fn old_files_are_refused_naming_the_migration_and_migrated_into_a_new_file() {
    let dir_guard = temp("migrate");
    let dir = dir_guard.path();
    let old = dir.join("old.db");
    old_database(&old);
    let before = std::fs::read(&old).unwrap();

    let e = Store::open_read(&old, Check::Quick).unwrap_err();
    assert!(matches!(e, StoreError::OldEdgeLabels), "{e:?}");
    assert!(e.to_string().contains("isogami db migrate"), "{e}");
    assert!(StoreWriter::open(&old, None, Check::Quick).is_err());

    let new = dir.join("new.db");
    let outcome = migrate(&old, &new, 2, &mut |_| {}, &AtomicBool::new(false)).unwrap();
    assert_eq!(
        std::fs::read(&old).unwrap(),
        before,
        "the old file is only read"
    );
    assert_eq!(outcome.from_version, 2);
    let explored = outcome.explored.as_ref().unwrap();
    assert_eq!(explored.planned, 2);
    assert!(explored.failures.is_empty());
    assert_eq!((outcome.user_designs, outcome.user_saved), (1, 1));
    assert_eq!(outcome.user_relabelled, 1, "{outcome:?}");

    let store = Store::open_read(&new, Check::Full).unwrap();
    let current = Design::from_legacy_spec(OLD_SPEC).unwrap();
    assert_ne!(current.to_string(), OLD_SPEC);
    let saved = store.design(&current.to_string()).unwrap();
    assert!(saved.is_some(), "the user design under its current spec");
    assert!(
        store.design(OLD_SPEC).unwrap().is_none(),
        "never under the old one"
    );
    // The stored row is what deploying the translated design gives today.
    let fresh = deploy(&current, &DeployRequest::default(), &mut |_| true).unwrap();
    let stored = saved.unwrap();
    assert_eq!(stored.report.max_area_ratio, fresh.report.max_area_ratio);

    // Migrating again into the finished file adds nothing and fails nothing.
    let again = migrate(&old, &new, 1, &mut |_| {}, &AtomicBool::new(false)).unwrap();
    assert_eq!(again.explored.as_ref().unwrap().committed, 0);
    assert_eq!((again.user_saved, again.user_merged), (0, 1));
}

/// Issue 42: `db migrate` of a healthy current database called it damaged and told the user
/// to restore it from a copy. It says the file is current and usable, writes no new file,
/// and leaves the old one as it was.
#[test]
fn a_current_database_is_not_called_damaged() {
    let dir_guard = temp("migrate-current");
    let dir = dir_guard.path();
    let current = dir.join("current.db");
    explore_into(
        &current,
        &common::two_family_request(1),
        &mut |_| {},
        &AtomicBool::new(false),
    )
    .unwrap();
    let before = std::fs::read(&current).unwrap();
    let new = dir.join("new.db");
    let e = migrate(&current, &new, 1, &mut |_| {}, &AtomicBool::new(false)).unwrap_err();
    assert!(
        matches!(e, StoreError::AlreadyCurrent { version } if version == isogami_store::SCHEMA_VERSION),
        "{e:?}"
    );
    let said = e.to_string();
    assert!(
        !said.contains("damaged") && !said.contains("restore"),
        "{said}"
    );
    assert_eq!(std::fs::read(&current).unwrap(), before);
    assert!(!new.exists(), "no new file for nothing to migrate");
    Store::open_read(&current, Check::Full).unwrap();
}

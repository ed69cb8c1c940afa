//! Peak memory per work unit (issue 13 item 4): measured while a unit runs, stored in the
//! optional `unit_memory` table with a checksum, copied by merge, and absent (not an error)
//! in databases made before it existed.

use crate::common;

use common::temp;
use isogami_store::{explore_into, Check, Store, StoreWriter};
use rusqlite::Connection;
use std::sync::atomic::AtomicBool;

fn explore(db: &std::path::Path) {
    let request = common::two_family_request(2);
    explore_into(db, &request, &mut |_| {}, &AtomicBool::new(false)).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn every_explored_unit_has_a_peak_at_least_the_process_baseline_and_merge_keeps_it() {
    let dir_guard = temp("unit-memory-measured");
    let dir = dir_guard.path();
    let db = dir.join("a.db");
    explore(&db);
    let units = Store::open_read(&db, Check::Full)
        .unwrap()
        .work_units()
        .unwrap();
    assert!(units.len() >= 2);
    for (u, _) in &units {
        let peak = u
            .peak_rss_bytes
            .unwrap_or_else(|| panic!("{} has no peak", u.id));
        // A running test process holds megabytes (code, the thread pool's stacks); a figure
        // in kilobytes or a wrapped negative would be a unit error.
        assert!((1 << 20..1 << 40).contains(&peak), "{}: {peak}", u.id);
    }
    let summaries = Store::open_read(&db, Check::Full)
        .unwrap()
        .unit_summaries()
        .unwrap();
    assert!(summaries.windows(2).all(|w| w[0].seconds >= w[1].seconds));
    let merged = dir.join("merged.db");
    {
        let source = Store::open_read(&db, Check::Full).unwrap();
        let mut w = StoreWriter::open(&merged, None, Check::Full).unwrap();
        w.merge_from(&source).unwrap();
    }
    let copied = Store::open_read(&merged, Check::Full)
        .unwrap()
        .work_units()
        .unwrap();
    assert_eq!(copied, units);
    let stats = Store::open_read(&merged, Check::Full)
        .unwrap()
        .stats()
        .unwrap();
    let top = units.iter().filter_map(|(u, _)| u.peak_rss_bytes).max();
    assert_eq!(stats.peak_memory.unwrap().peak_rss_bytes, top);
}

#[test]
fn a_database_without_the_table_reads_as_unmeasured_and_a_writer_adds_it() {
    let dir_guard = temp("unit-memory-old");
    let dir = dir_guard.path();
    let db = dir.join("old.db");
    explore(&db);
    // What a database made before the table existed looks like.
    Connection::open(&db)
        .unwrap()
        .execute_batch("DROP TABLE unit_memory")
        .unwrap();
    let store = Store::open_read(&db, Check::Full).unwrap();
    let units = store.work_units().unwrap();
    assert!(units.iter().all(|(u, _)| u.peak_rss_bytes.is_none()));
    assert!(store.stats().unwrap().peak_memory.is_none());
    drop(store);
    // Resuming the run opens it for writing: the table comes back, the old units stay
    // unmeasured, nothing else changes.
    explore(&db);
    let again = Store::open_read(&db, Check::Full)
        .unwrap()
        .work_units()
        .unwrap();
    assert_eq!(again, units);
}

#[cfg(target_os = "linux")]
#[test]
fn a_changed_peak_fails_its_checksum() {
    let dir_guard = temp("unit-memory-tampered");
    let dir = dir_guard.path();
    let db = dir.join("t.db");
    explore(&db);
    let changed = Connection::open(&db)
        .unwrap()
        .execute(
            "UPDATE unit_memory SET peak_rss_bytes = peak_rss_bytes + 4096
             WHERE work_unit = (SELECT min(work_unit) FROM unit_memory)",
            [],
        )
        .unwrap();
    assert_eq!(changed, 1);
    let err = Store::open_read(&db, Check::Full).unwrap_err().to_string();
    assert!(
        err.contains("memory row of work unit") && err.contains("checksum"),
        "{err}"
    );
}

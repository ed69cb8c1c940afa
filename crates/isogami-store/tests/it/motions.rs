//! Distinct motions stored (issue 13, item 5): every topology of the file in one class of
//! topologies that move alike; the same classes for any job count and for merged shards; a
//! class never holds two topologies of one cell; rows are checksummed.

use crate::common;

use common::{quick_settings, temp};
use isogami::explore::Shard;
use isogami::tiling::Family;
use isogami_store::{explore_into, Check, ExploreRequest, MotionClass, Store, StoreWriter};
use rusqlite::Connection;
use std::collections::BTreeSet;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// IH28 and IH29 share motions on their minimal cells (congruent default hexagons), as do
/// IH83 and IH90 (triangles).
fn request(jobs: usize, shard: Option<Shard>) -> ExploreRequest {
    ExploreRequest {
        settings: quick_settings(),
        families: [28, 29, 83, 90]
            .iter()
            .map(|&n| Family::from_number(n).unwrap())
            .collect(),
        cells: None,
        shard,
        jobs,
        parts: 1,
    }
}

fn explore(db: &Path, req: &ExploreRequest) {
    explore_into(db, req, &mut |_| {}, &AtomicBool::new(false)).unwrap();
}

fn classes(db: &Path) -> Vec<MotionClass> {
    Store::open_read(db, Check::Full)
        .unwrap()
        .motion_classes()
        .unwrap()
        .expect("a writer made the classes")
}

#[test]
fn classes_cover_every_topology_and_do_not_depend_on_jobs_or_shards() {
    let dir_guard = temp("motions-equal");
    let dir = dir_guard.path();
    let one = dir.join("one.db");
    explore(&one, &request(1, None));
    let reference = classes(&one);
    // Every topology in exactly one class; the representative is the class's smallest.
    let store = Store::open_read(&one, Check::Full).unwrap();
    let topologies: BTreeSet<String> = Connection::open(&one)
        .unwrap()
        .prepare("SELECT DISTINCT topology FROM designs")
        .unwrap()
        .query_map([], |r| r.get(0))
        .unwrap()
        .map(Result::unwrap)
        .collect();
    let classed: Vec<String> = reference
        .iter()
        .flat_map(|c| c.variants.iter().map(|v| v.topology.clone()))
        .collect();
    assert_eq!(classed.len(), topologies.len());
    assert_eq!(classed.iter().cloned().collect::<BTreeSet<_>>(), topologies);
    for c in &reference {
        assert_eq!(c.representative, c.variants[0].topology);
        assert!(c.variants.windows(2).all(|w| w[0].topology < w[1].topology));
        let cells: BTreeSet<(String, String)> = c
            .variants
            .iter()
            .map(|v| (v.family.clone(), v.cell.clone()))
            .collect();
        assert_eq!(cells.len(), c.variants.len(), "two of one cell: {c:?}");
        // The example opens a design of that topology.
        for v in &c.variants {
            let of = store.motion_class_of(&v.example).unwrap().unwrap();
            assert_eq!(&of, c);
        }
    }
    assert!(
        reference.iter().filter(|c| c.families() > 1).count() >= 2,
        "{reference:?}"
    );
    assert!(store.motion_class_of("IH1:0.1:1x1:a").unwrap().is_none());

    let two = dir.join("two.db");
    explore(&two, &request(2, None));
    assert_eq!(classes(&two), reference);

    let merged = dir.join("merged.db");
    let shards: Vec<_> = (0..3)
        .map(|i| {
            let path = dir.join(format!("s{i}.db"));
            explore(&path, &request(1, Some(Shard::new(i, 3).unwrap())));
            path
        })
        .collect();
    // Merged in an order other than the shards'.
    let mut w = StoreWriter::open(&merged, None, Check::Full).unwrap();
    for s in shards.iter().rev() {
        w.merge_from(&Store::open_read(s, Check::Full).unwrap())
            .unwrap();
    }
    drop(w);
    assert_eq!(classes(&merged), reference);
}

#[test]
fn a_changed_class_fails_its_checksum_and_an_old_file_gets_its_classes() {
    let dir_guard = temp("motions-tamper");
    let dir = dir_guard.path();
    let db = dir.join("t.db");
    explore(&db, &request(2, None));
    let reference = classes(&db);
    let c = Connection::open(&db).unwrap();
    // A file from before the table existed reads as "not computed"…
    c.execute_batch("ALTER TABLE motion_classes RENAME TO kept_aside")
        .unwrap();
    assert!(Store::open_read(&db, Check::Full)
        .unwrap()
        .motion_classes()
        .unwrap()
        .is_none());
    // …and a rerun that adds no unit classifies it.
    explore(&db, &request(2, None));
    assert_eq!(classes(&db), reference);
    c.execute(
        "UPDATE motion_classes SET representative = topology
         WHERE topology = (SELECT max(topology) FROM motion_classes WHERE topology != representative)",
        [],
    )
    .unwrap();
    let err = Store::open_read(&db, Check::Full).unwrap_err().to_string();
    assert!(
        err.contains("motion class row") && err.contains("checksum"),
        "{err}"
    );
}

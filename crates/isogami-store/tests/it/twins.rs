//! Cell twins stored once (issue 40, item 3): after an exploration no two stored designs have
//! the same family, shape and path on different cells; every folded spec is the same design
//! as the one it is stored with; the same designs are stored for any job count and for merged
//! shards; a stored design lists its other cells and is found by any of its specs.
//!
//! The cases are chosen by a rule, not by hand: every family whose 1×2 and 2×1 cells both
//! exist with at most [`MAX_EDGES`] unique edges, explored on those two cells (the rotated
//! twins the per-cell deduplication cannot see). Paths are compared by deploying both
//! designs, frame by frame, not by the stored figures the fold itself reads.

use crate::common;

use common::temp;
use isogami::api::{deploy, resolve_design, DeployRequest, FrameSelection};
use isogami::catalog::CatalogSettings;
use isogami::cell::CellDims;
use isogami::explore::pipeline::cells_to_explore;
use isogami::explore::Shard;
use isogami::tiling::Family;
use isogami_store::{explore_into, Check, ExploreRequest, Store, StoreWriter};
use std::collections::BTreeSet;
use std::path::Path;
use std::sync::atomic::AtomicBool;

/// Largest number of unique edges of an explored cell (keeps the test to seconds).
const MAX_EDGES: usize = 8;

/// Frames compared per path.
const FRAMES: usize = 11;

fn twin_cells() -> Vec<CellDims> {
    vec![CellDims::new(1, 2).unwrap(), CellDims::new(2, 1).unwrap()]
}

fn families() -> Vec<Family> {
    let mut settings = CatalogSettings::default().topology;
    settings.max_dims = 2;
    settings.max_edges = MAX_EDGES;
    let wanted = twin_cells();
    let out: Vec<Family> = Family::all()
        .filter(|&f| {
            let cells: Vec<CellDims> = cells_to_explore(f, &settings)
                .into_iter()
                .map(|(d, _)| d)
                .collect();
            wanted.iter().all(|w| cells.contains(w))
        })
        .collect();
    assert!(out.len() >= 3, "the rule picks too few families: {out:?}");
    out
}

fn request(jobs: usize, shard: Option<Shard>) -> ExploreRequest {
    ExploreRequest {
        settings: CatalogSettings {
            samples: 4,
            ..CatalogSettings::default()
        },
        families: families(),
        cells: Some(twin_cells()),
        shard,
        jobs,
        parts: 1,
    }
}

fn explore(db: &Path, req: &ExploreRequest) {
    explore_into(db, req, &mut |_| {}, &AtomicBool::new(false)).unwrap();
}

/// Area ratio and principal expansions at evenly spaced frames of a fresh deployment.
fn path(spec: &str) -> Option<Vec<[f64; 3]>> {
    let design = resolve_design(spec).unwrap();
    let request = DeployRequest {
        frames: FrameSelection::Evenly(FRAMES),
        ..DeployRequest::default()
    };
    let run = deploy(&design, &request, &mut |_| true).ok()?;
    Some(
        run.report
            .frames
            .iter()
            .map(|f| {
                let m = &f.measures;
                [m.area_ratio, m.max_expansion, m.min_expansion]
            })
            .collect(),
    )
}

fn same_path(a: &[[f64; 3]], b: &[[f64; 3]]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            x.iter()
                .zip(y)
                .all(|(p, q)| (p - q).abs() <= 1e-7 * p.abs().max(1.0))
        })
}

/// (family and shape, cell) of a spec: everything but the joints, split at the cell.
fn shape_and_cell(spec: &str) -> (String, String) {
    let parts: Vec<&str> = spec.split(':').collect();
    (format!("{}:{}", parts[0], parts[1]), parts[2].to_string())
}

fn stored_specs(db: &Path) -> BTreeSet<String> {
    let store = Store::open_read(db, Check::Full).unwrap();
    store
        .summaries()
        .unwrap()
        .into_iter()
        .map(|s| s.spec)
        .collect()
}

#[test]
fn twins_are_stored_once_with_their_other_cells_for_any_jobs_or_shards() {
    let dir_guard = temp("twins");
    let dir = dir_guard.path();
    let one = dir.join("one.db");
    explore(&one, &request(2, None));
    let store = Store::open_read(&one, Check::Full).unwrap();
    let twins = store.cell_twins().unwrap();
    assert!(!twins.is_empty(), "the rule's cells hold no twins");
    assert_eq!(
        store.stats().unwrap().cell_twins,
        twins.len() as u64,
        "stats count the folded specs"
    );
    let specs = stored_specs(&one);

    // Every folded spec is the same design as the one it is stored with: same family and
    // shape, another cell, the same path deployed afresh; and that design lists it.
    for (twin, kept) in &twins {
        assert!(!specs.contains(twin), "{twin} is folded and stored");
        assert!(specs.contains(kept), "{kept} is not stored");
        let (ts, tc) = shape_and_cell(twin);
        let (ks, kc) = shape_and_cell(kept);
        assert_eq!(ts, ks, "{twin} vs {kept}");
        assert_ne!(tc, kc, "{twin} vs {kept}");
        let (a, b) = (path(twin).unwrap(), path(kept).unwrap());
        assert!(same_path(&a, &b), "{twin} and {kept} move apart");
        let found = store
            .design(twin)
            .unwrap()
            .expect("a twin spec finds its design");
        assert_eq!(&found.summary.spec, kept);
        assert!(found.other_cells.contains(twin));
    }

    // No two stored designs of one family and shape on different cells share a path.
    let specs: Vec<&String> = specs.iter().collect();
    let paths: Vec<Option<Vec<[f64; 3]>>> = specs.iter().map(|s| path(s)).collect();
    for i in 0..specs.len() {
        for j in i + 1..specs.len() {
            let (si, ci) = shape_and_cell(specs[i]);
            let (sj, cj) = shape_and_cell(specs[j]);
            if si != sj || ci == cj {
                continue;
            }
            if let (Some(a), Some(b)) = (&paths[i], &paths[j]) {
                assert!(
                    !same_path(a, b),
                    "{} and {} are stored twice",
                    specs[i],
                    specs[j]
                );
            }
        }
    }

    // The same designs and folds for one job and for shards merged in reverse order.
    let single = dir.join("single.db");
    explore(&single, &request(1, None));
    assert_eq!(stored_specs(&single), stored_specs(&one));
    let merged = dir.join("merged.db");
    let shards: Vec<_> = (0..2)
        .map(|i| {
            let path = dir.join(format!("s{i}.db"));
            explore(&path, &request(1, Some(Shard::new(i, 2).unwrap())));
            path
        })
        .collect();
    let mut w = StoreWriter::open(&merged, None, Check::Full).unwrap();
    for s in shards.iter().rev() {
        w.merge_from(&Store::open_read(s, Check::Full).unwrap())
            .unwrap();
    }
    drop(w);
    assert_eq!(stored_specs(&merged), stored_specs(&one));
    let merged_twins = Store::open_read(&merged, Check::Full)
        .unwrap()
        .cell_twins()
        .unwrap();
    assert_eq!(merged_twins, twins);
}

#[test]
fn a_changed_twin_row_fails_its_checksum() {
    let dir_guard = temp("twins-tamper");
    let dir = dir_guard.path();
    let db = dir.join("t.db");
    explore(&db, &request(2, None));
    let c = rusqlite::Connection::open(&db).unwrap();
    let changed = c
        .execute(
            "UPDATE cell_twins SET kept = kept || ' ' WHERE rowid = (SELECT min(rowid) FROM cell_twins)",
            [],
        )
        .unwrap();
    assert_eq!(changed, 1);
    drop(c);
    let err = Store::open_read(&db, Check::Full).unwrap_err();
    assert!(err.to_string().contains("cell twin"), "{err}");
}

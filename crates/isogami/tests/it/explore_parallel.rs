//! Parallelism inside a work unit changes nothing: the topology enumeration and the whole unit
//! (deployments, shape samples) give identical results on pools of 1 and 3 threads.

use isogami::catalog::{run_unit, CatalogSettings, UnitOutcome};
use isogami::cell::CellDims;
use isogami::explore::{enumerate_topologies, TopologyOptions, TopologyReport};
use isogami::tiling::Family;

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

fn fam(n: u32) -> Family {
    Family::from_number(n).unwrap()
}

/// A report without its timings (the only thing allowed to differ).
fn untimed(mut r: TopologyReport) -> TopologyReport {
    r.timings = Default::default();
    r
}

#[test]
fn enumeration_is_identical_for_any_thread_count() {
    // A low-symmetry hexagon cell (hundreds of masks and unique designs) and a square 2x2
    // cell (rotating squares; same-motion merges across orbits).
    for (f, a, b) in [(28, 1, 1), (76, 2, 2), (22, 1, 1)] {
        let dims = CellDims::new(a, b).unwrap();
        let options = TopologyOptions::default();
        let one = pool(1).install(|| enumerate_topologies(fam(f), dims, &options).unwrap());
        let three = pool(3).install(|| enumerate_topologies(fam(f), dims, &options).unwrap());
        assert!(one.masks_expanded > 1 && !one.designs.is_empty(), "IH{f}");
        assert_eq!(untimed(one), untimed(three), "IH{f} {dims}");
    }
}

/// Specs, topology and the full deployment report (as JSON) of every entry, and the stage
/// counts.
type Content = (Vec<(String, String, String)>, Vec<(String, u64, u64)>);

fn content(o: &UnitOutcome) -> Content {
    let entries = o
        .entries
        .iter()
        .map(|e| {
            (
                e.design.to_string(),
                e.topology.clone(),
                serde_json::to_string(&e.report).unwrap(),
            )
        })
        .collect();
    let stages = o
        .stages
        .iter()
        .map(|s| (s.stage.clone(), s.count_in, s.count_out))
        .collect();
    (entries, stages)
}

#[test]
fn a_work_unit_is_identical_for_any_thread_count() {
    let settings = CatalogSettings::default().quick();
    let run = |threads: usize| {
        pool(threads).install(|| run_unit(fam(28), CellDims::MINIMAL, &settings).unwrap())
    };
    let (one, three) = (content(&run(1)), content(&run(3)));
    assert!(
        one.0.len() > 3,
        "several designs with shape samples: {}",
        one.0.len()
    );
    assert_eq!(one, three);
}

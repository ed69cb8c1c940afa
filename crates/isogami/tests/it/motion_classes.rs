//! Distinct motions across cells and families (issue 13, item 5): a cell's designs are all
//! distinct motions (the per-cell deduplication), so they never share a class; a design and
//! its rotated b×a twin do; so do hexagon designs of families whose default sheets are
//! congruent; and the classes do not depend on how the topologies were found.

use isogami::cell::CellDims;
use isogami::explore::{enumerate_topologies, motion_classes, TopologyOptions};
use isogami::tiling::Family;
use isogami::topology::Design;
use std::collections::{BTreeMap, BTreeSet};

fn designs(family: u32, a: u8, b: u8) -> Vec<Design> {
    let options = TopologyOptions::default();
    enumerate_topologies(
        Family::from_number(family).unwrap(),
        CellDims::new(a, b).unwrap(),
        &options,
    )
    .unwrap()
    .designs
}

/// Classes of `all` (sorted by spec first, as the store does) as sets of specs.
fn classes(mut all: Vec<Design>) -> Vec<BTreeSet<String>> {
    all.sort_by_key(|d| d.to_string());
    let reps = motion_classes(&all, Default::default());
    let mut by: BTreeMap<usize, BTreeSet<String>> = BTreeMap::new();
    for (d, r) in all.iter().zip(&reps) {
        by.entry(r.expect("every explored topology has a motion"))
            .or_default()
            .insert(d.to_string());
    }
    by.into_values().collect()
}

fn cell_of(spec: &str) -> String {
    let parts: Vec<&str> = spec.split(':').collect();
    format!("{}/{}", parts[0], parts[2])
}

fn family_of(spec: &str) -> String {
    spec.split(':').next().unwrap().to_string()
}

#[test]
fn a_design_and_its_rotated_twin_share_a_class_and_a_cell_never_repeats_in_one() {
    // IH10's 2×1 and 1×2 cells are the same sheet turned by 90°.
    let all: Vec<Design> = [(2u8, 1u8), (1, 2)]
        .iter()
        .flat_map(|&(a, b)| designs(10, a, b))
        .collect();
    let n = all.len();
    assert!(n >= 4, "{n} designs");
    let cs = classes(all);
    assert_eq!(cs.len() * 2, n, "{cs:?}");
    for c in &cs {
        let cells: BTreeSet<String> = c.iter().map(|s| cell_of(s)).collect();
        assert_eq!(cells.len(), 2, "one design of each cell: {c:?}");
    }
}

#[test]
fn congruent_hexagon_families_share_classes_and_distinct_motions_stay_apart() {
    let families = [6u32, 27, 28, 29, 30, 31, 32];
    let all: Vec<Design> = families.iter().flat_map(|&f| designs(f, 1, 1)).collect();
    let n = all.len();
    let cs = classes(all);
    assert!(cs.len() < n, "{} classes of {n} designs", cs.len());
    let across = cs
        .iter()
        .filter(|c| {
            c.iter()
                .map(|s| family_of(s))
                .collect::<BTreeSet<_>>()
                .len()
                > 1
        })
        .count();
    assert!(across > 10, "{across} classes span families");
    // Within one family and cell the exploration already kept one design per motion: two of
    // them in one class would be a wrong match.
    for c in &cs {
        let cells: Vec<String> = c.iter().map(|s| cell_of(s)).collect();
        let distinct: BTreeSet<&String> = cells.iter().collect();
        assert_eq!(distinct.len(), cells.len(), "{c:?}");
    }
    // A named case: the same joints on IH27, IH28 and IH29, whose default sheets are
    // congruent, move alike.
    let same = cs
        .iter()
        .find(|c| {
            c.iter()
                .any(|s| s.starts_with("IH28:") && s.ends_with(":--a-babba-"))
        })
        .unwrap();
    let fams: BTreeSet<String> = same.iter().map(|s| family_of(s)).collect();
    assert!(fams.contains("IH27") && fams.contains("IH29"), "{same:?}");
}

//! Edge labels are combinatorial: the edge table of every family's cells — which tile is which
//! lattice copy of which aspect, which tile edges form each unique edge, with which integer cell
//! offset — is the same at every valid shape, so a joint string names one mechanism across
//! shape space (issue 21). Before the cell builder placed tiles by a floor() of their centroid
//! at each shape, the table of IH9 2×1 changed between p1 = 0.5 and 0.500000001.

use crate::common;

use common::Rng;
use isogami::api::{analyze, resolve_design};
use isogami::cell::{CellDims, UnitCell};
use isogami::mobility::MobilitySettings;
use isogami::tiling::{param_ranges, Family, Tiling};

/// Everything that names a tile or an edge, without the geometry.
#[derive(Debug, PartialEq)]
struct Labels {
    tiles: Vec<(usize, [u8; 2], Vec<usize>)>,
    edges: Vec<(usize, usize, usize, usize, [i32; 2])>,
}

fn labels(cell: &UnitCell) -> Labels {
    Labels {
        tiles: cell
            .tiles
            .iter()
            .map(|t| (t.aspect, t.copy, t.proto_edges.clone()))
            .collect(),
        edges: cell
            .edges
            .iter()
            .map(|e| (e.tile_a, e.edge_a, e.tile_b, e.edge_b, e.offset))
            .collect(),
    }
}

fn built(family: Family, params: &[f64], dims: CellDims) -> Option<UnitCell> {
    let tiling = Tiling::new(family, params).ok()?;
    Some(UnitCell::new(&tiling, dims).expect("a valid tiling builds every cell"))
}

/// Up to `count` random valid shapes of `family` in its sampling box widened to ±60 %.
fn random_shapes(rng: &mut Rng, family: Family, count: usize) -> Vec<Vec<f64>> {
    let ranges = param_ranges(family, 0.6);
    let mut out = Vec::new();
    for _ in 0..count * 40 {
        if out.len() == count || ranges.is_empty() {
            break;
        }
        let p: Vec<f64> = ranges
            .iter()
            .map(|&(lo, hi)| lo + (hi - lo) * rng.unit())
            .collect();
        if Tiling::new(family, &p).is_ok() {
            out.push(p);
        }
    }
    out
}

/// `params` with parameter `i` moved by `delta`.
fn nudged(params: &[f64], i: usize, delta: f64) -> Vec<f64> {
    let mut p = params.to_vec();
    p[i] += delta;
    p
}

#[test]
fn every_cell_of_every_family_has_one_edge_table_across_shape_space() {
    let mut rng = Rng::new(21);
    let mut shapes_checked = 0;
    for family in Family::all() {
        let defaults = family.default_params();
        let shapes = random_shapes(&mut rng, family, 20);
        if family.param_count() > 0 {
            assert!(
                shapes.len() >= 20,
                "{family}: only {} random valid shapes",
                shapes.len()
            );
        }
        for dims in CellDims::all() {
            let reference = labels(&built(family, &defaults, dims).unwrap());
            let mut check = |p: &[f64], what: &str| {
                if let Some(cell) = built(family, p, dims) {
                    assert!(
                        labels(&cell) == reference,
                        "{family} {dims}: the edge table at {p:?} ({what}) differs from the default's"
                    );
                    shapes_checked += 1;
                }
            };
            for p in &shapes {
                check(p, "random shape");
            }
            for i in 0..defaults.len() {
                for delta in [-1e-9, 1e-9] {
                    check(&nudged(&defaults, i, delta), "default ± 1e-9");
                    if let Some(p) = shapes.first() {
                        check(&nudged(p, i, delta), "random shape ± 1e-9");
                    }
                }
            }
        }
    }
    assert!(shapes_checked > 20_000, "{shapes_checked} cells compared");
}

#[test]
fn the_reported_jump_of_ih9_is_gone() {
    // The reproducer: tile 1 sat one lattice step away at p1 = 0.500000001, so edge 1
    // joined tile 0 to tile 1 instead of tile 3 and the joint string named another mechanism.
    let family: Family = "IH9".parse().unwrap();
    let dims: CellDims = "2x1".parse().unwrap();
    let at = |p1: f64| labels(&built(family, &[0.12239750492, p1, 0.225335752741], dims).unwrap());
    let middle = at(0.5);
    assert_eq!(middle, at(0.499999999));
    assert_eq!(middle, at(0.500000001));
    assert_eq!(middle.edges[1].2, 3, "edge 1 joins tile 0 to tile 3");
}

/// Mobility is continuous across a 1e-9 move of each parameter: the same DOF and, for one
/// DOF, the same motion to first order.
fn assert_mobility_continuous(spec: &str) {
    let design = resolve_design(spec).unwrap();
    let settings = MobilitySettings::default();
    let base = analyze(&design, settings).unwrap();
    for i in 0..design.params.len() {
        for delta in [-1e-9, 1e-9] {
            let moved = design.at_params(&nudged(&design.params, i, delta));
            let near = analyze(&moved, settings).unwrap();
            assert_eq!(
                near.mobility.dof, base.mobility.dof,
                "{spec}: p{i} {delta:+e}"
            );
            if let (Some(a), Some(b)) = (&base.mobility.motion, &near.mobility.motion) {
                let gap = (&a.vector - &b.vector)
                    .amax()
                    .min((&a.vector + &b.vector).amax());
                assert!(
                    gap < 1e-5,
                    "{spec}: p{i} {delta:+e} moves the motion by {gap:e}"
                );
            }
        }
    }
}

#[test]
fn designs_on_former_jumps_move_continuously() {
    for spec in [
        "IH9:0.12239750492,0.5,0.225335752741:2x1:---abb--a-bb",
        "IH44:0.5,0.102564102564:1x4:-aaabbaaaaaaaaaa",
        "IH46:0.5,0.230769230769,0.5,0.5:1x1:aaaa",
    ] {
        assert_mobility_continuous(spec);
    }
}

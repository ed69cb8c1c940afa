//! Linkage analysis: counts worked out by hand, periodic deduplication checked on supercell
//! copies of a design, and input validation.

mod common;

use isogami::cell::{CellDims, UnitCell};
use isogami::linkage::analyze_linkages;
use isogami::render::linkage_svg;
use isogami::tiling::{Family, Tiling};
use isogami::topology::{Design, JointChoice};
use std::collections::BTreeMap;

fn analysis(spec: &str) -> (UnitCell, Design, isogami::linkage::LinkageAnalysis) {
    let d = Design::resolve(spec).unwrap();
    let c = d.cell().unwrap();
    let a = analyze_linkages(&c, &d.joints).unwrap();
    (c, d, a)
}

/// The joints of `design` (on its cell) repeated over an a×b supercell of that cell: each
/// supercell edge is the copy of the small cell's edge through the same tile edge, with the
/// joint on the same vertex.
fn repeated(design: &Design, a: u8, b: u8) -> Design {
    assert_eq!(design.dims, CellDims::MINIMAL);
    let t = Tiling::new(design.family, &design.params).unwrap();
    let small = UnitCell::new(&t, CellDims::MINIMAL).unwrap();
    let big = UnitCell::new(&t, CellDims::new(a, b).unwrap()).unwrap();
    let joints = big
        .edges
        .iter()
        .map(|e| {
            let aspect = big.tiles[e.tile_a].aspect;
            let k = small.tile_edges[aspect][e.edge_a];
            let se = small.edges[k];
            let same_side = se.tile_a == aspect && se.edge_a == e.edge_a;
            match (design.joints[k], same_side) {
                (j, true) => j,
                (JointChoice::A, false) => JointChoice::B,
                (JointChoice::B, false) => JointChoice::A,
                (j, false) => j,
            }
        })
        .collect();
    Design {
        dims: CellDims::new(a, b).unwrap(),
        joints,
        ..design.clone()
    }
}

#[test]
fn rotating_squares_is_four_four_bars() {
    // 2×2 cell: 4 squares, 8 hinges. Every hole of rotating squares is bounded by four squares
    // (a 4-bar), and a connected sheet on the torus has E − V = 8 − 4 = 4 holes per cell.
    let (_, _, a) = analysis("rotating-squares");
    assert_eq!(a.signature, "4×4-bar");
    assert_eq!(a.linkages.len(), 4);
    assert!(a
        .linkages
        .iter()
        .all(|l| l.bars == 4 && l.nodes.len() == 4 && l.joints.len() == 4));
    assert_eq!(a.degree_histogram, BTreeMap::from([(4, 4)]));
    assert!(a.other_faces.is_empty());
}

#[test]
fn hexagon_design_has_two_six_bars_round_a_six_valent_tile() {
    // One hexagon pinned at all six corners to six neighbours, each of those pinned to two:
    // 6 joints for 4 tiles, so 6 − 4 = 2 holes per cell, both hexagonal loops.
    let (_, _, a) = analysis("IH18::2x2:--a--aa-a-aa");
    assert_eq!(a.signature, "2×6-bar");
    assert_eq!(a.degree_histogram, BTreeMap::from([(2, 3), (6, 1)]));
}

#[test]
fn counts_scale_with_the_supercell() {
    // The same design described on a bigger cell has the same linkages per area: periodic
    // duplicates are removed, never double counted or lost.
    for spec in [
        "IH90::1x1:aaa",
        "IH61::1x1:aaaa",
        "IH44:0.5,0.102564102564:1x1:-aaa",
    ] {
        let (_, d, small) = analysis(spec);
        for (a, b) in [(2, 1), (1, 2), (2, 2)] {
            let big = repeated(&d, a, b);
            let r = analyze_linkages(&big.cell().unwrap(), &big.joints).unwrap();
            let n = usize::from(a * b);
            let count = |x: &isogami::linkage::LinkageAnalysis| {
                let mut m = BTreeMap::new();
                for l in &x.linkages {
                    *m.entry(l.bars).or_insert(0) += 1;
                }
                m
            };
            let expected: BTreeMap<usize, usize> =
                count(&small).into_iter().map(|(k, v)| (k, v * n)).collect();
            assert_eq!(count(&r), expected, "{spec} on {a}x{b}");
            let hist: BTreeMap<usize, usize> = small
                .degree_histogram
                .iter()
                .map(|(k, v)| (*k, v * n))
                .collect();
            assert_eq!(r.degree_histogram, hist, "{spec} on {a}x{b}");
        }
    }
}

#[test]
fn unjointed_and_welded_sheets_have_no_linkages() {
    let f = Family::from_number(76).unwrap();
    let cell = UnitCell::new(&Tiling::default_for(f), CellDims::new(2, 2).unwrap()).unwrap();
    let none = analyze_linkages(&cell, &[JointChoice::None; 8]).unwrap();
    assert_eq!(none.signature, "none");
    assert_eq!(none.degree_histogram, BTreeMap::from([(0, 4)]));
    // Welded edges are single graph edges: every square has four welded neighbours and the
    // holes are the 4-cycles round each grid vertex.
    let welded = analyze_linkages(&cell, &[JointChoice::Both; 8]).unwrap();
    assert_eq!(welded.degree_histogram, BTreeMap::from([(4, 4)]));
}

#[test]
fn bad_input_is_an_error() {
    let (c, d, _) = analysis("rotating-squares");
    assert!(analyze_linkages(&c, &d.joints[..7]).is_err());
}

#[test]
fn svg_colours_linkages_by_bar_count() {
    let (c, d, a) = analysis("rotating-squares");
    let svg = linkage_svg(&c, &d.joints, &a);
    assert!(svg.starts_with("<?xml") || svg.starts_with("<svg"));
    assert!(svg.contains(isogami::render::linkage_colour(4)));
    assert!(!svg.contains("NaN"));
}

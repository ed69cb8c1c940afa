//! Linkage analysis: counts worked out by hand, periodic deduplication checked on supercell
//! copies of a design, Euler's formula on the torus, chords, welds, unbounded faces, the
//! paper's hexagon design, and input validation.

use isogami::cell::{CellDims, UnitCell};
use isogami::kinematics::Mechanism;
use isogami::linkage::{analyze_linkages, FaceIssue, LinkageError, Node};
use isogami::mobility::analyze;
use isogami::render::linkage_svg;
use isogami::tiling::{Family, Tiling};
use isogami::topology::{Design, JointChoice, SAMPLE_OPENING_DESIGNS};
use std::collections::{BTreeMap, BTreeSet};

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
    // (a 4-bar), and a connected sheet on the torus has E − V = 8 − 4 = 4 holes per cell. The
    // ring of eight squares round any square is a chordless cycle too, but it encloses that
    // square rather than a hole, and is not a linkage.
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
    assert!(matches!(
        analyze_linkages(&c, &d.joints[..7]),
        Err(LinkageError::JointCount { given: 7, edges: 8 })
    ));
    assert!(analyze_linkages(&c, &[]).is_err());
    // A hand-edited cell whose edge names a tile it does not have.
    let mut broken = c.clone();
    broken.edges[0].tile_b = 99;
    assert!(matches!(
        analyze_linkages(&broken, &d.joints),
        Err(LinkageError::EdgeRecord { edge: 0 })
    ));
    broken.edges[0].tile_b = c.edges[0].tile_b;
    broken.edges[0].edge_a = 17;
    assert!(analyze_linkages(&broken, &d.joints).is_err());
}

#[test]
fn svg_colours_linkages_by_bar_count() {
    let (c, d, a) = analysis("rotating-squares");
    let svg = linkage_svg(&c, &d.joints, &a);
    assert!(svg.starts_with("<?xml") || svg.starts_with("<svg"));
    assert!(svg.contains(isogami::render::linkage_colour(4)));
    assert!(!svg.contains("NaN"));
}

/// Joint-graph edges per cell: distinct pinned neighbours summed over tiles, halved.
fn graph_edges(a: &isogami::linkage::LinkageAnalysis) -> usize {
    a.degree_histogram.iter().map(|(d, n)| d * n).sum::<usize>() / 2
}

/// True when `edge` pins node `p` to node `q` with its `tile_a` in cell `at`.
fn pins(c: &UnitCell, edge: usize, at: [i32; 2], p: Node, q: Node) -> bool {
    let e = c.edges[edge];
    let a = (e.tile_a, at);
    let b = (e.tile_b, [at[0] + e.offset[0], at[1] + e.offset[1]]);
    (a, b) == (p, q) || (a, b) == (q, p)
}

/// Pairs of positions in `nodes` (not neighbours along the cycle) pinned by a joint of the
/// design, found from the cell's edge list directly.
fn chords(c: &UnitCell, joints: &[JointChoice], nodes: &[Node]) -> Vec<(usize, usize)> {
    let k = nodes.len();
    let mut out = Vec::new();
    for i in 0..k {
        for j in i + 2..k {
            if i == 0 && j == k - 1 {
                continue;
            }
            let (p, q) = (nodes[i], nodes[j]);
            // A joint pinning p and q has its tile_a at p or at q.
            let pinned = c.edges.iter().enumerate().any(|(e, ce)| {
                joints[e] != JointChoice::None
                    && ((ce.tile_a == p.0 && pins(c, e, p.1, p, q))
                        || (ce.tile_a == q.0 && pins(c, e, q.1, p, q)))
            });
            if pinned {
                out.push((i, j));
            }
        }
    }
    out
}

#[test]
fn the_papers_hexagon_design_interleaves_degree_three_and_six() {
    // Regular hexagons, three per cell: one pinned at all six corners, the other two at three.
    // With n₃ = 2n₆ tiles of degree 3 and 6, E = 6 and V = 3 per cell, so there are E − V = 3
    // holes whose bars add up to 2E = 12: three 4-bars. Found by exhaustive search over the
    // pin ends of the 1×1 cells of IH16 (and IH7, the same sheet); it is one degree of
    // freedom and deploys until the tiles have turned ±60° (120° relative), as in the paper.
    for spec in [
        "IH16:0.216506350946:1x1:aaaaaa---",
        "IH7:default:1x1:aaaaaa---",
    ] {
        let (c, d, a) = analysis(spec);
        assert_eq!(a.signature, "3×4-bar", "{spec}");
        assert_eq!(
            a.degree_histogram,
            BTreeMap::from([(3, 2), (6, 1)]),
            "{spec}"
        );
        let mech = Mechanism::new(&c, &d.joints).unwrap();
        assert_eq!(
            analyze(&mech, &mech.rest, Default::default()).unwrap().dof,
            1
        );
    }
}

#[test]
fn six_bars_next_to_a_six_valent_hexagon() {
    // With more degree-3 than twice the degree-6 tiles, 6-bars appear: one hub and eight
    // degree-3 hexagons per 3×1 cell, E = (6 + 24)/2 = 15, V = 9, so 6 holes and 30 bars. Found
    // by random search (hub tiles pinned all round, the others at three edges, random ends,
    // mobility 1); it is mobile to first order but contact stops it almost at once.
    let spec = "IH16:0.216506350946:3x1:--a-bb-a-a-ab--ab-a--ba-bab";
    let (c, d, a) = analysis(spec);
    assert_eq!(a.signature, "3×4-bar + 3×6-bar");
    assert_eq!(a.degree_histogram, BTreeMap::from([(3, 8), (6, 1)]));
    let mech = Mechanism::new(&c, &d.joints).unwrap();
    assert_eq!(
        analyze(&mech, &mech.rest, Default::default()).unwrap().dof,
        1
    );
}

#[test]
fn euler_on_the_torus_and_chordless_canonical_cycles() {
    // For a sheet connected in both directions every face is bounded, and V − E + F = 0 per
    // cell: F = E − V holes whose bar counts add up to 2E. When no face is disqualified, the
    // linkages are all the holes.
    let mut specs: Vec<&str> = SAMPLE_OPENING_DESIGNS.to_vec();
    specs.extend([
        "IH16:0.216506350946:1x1:aaaaaa---",
        "IH16:0.216506350946:3x1:--a-bb-a-a-ab--ab-a--ba-bab",
    ]);
    for spec in specs {
        let (c, d, a) = analysis(spec);
        assert!(a.other_faces.is_empty(), "{spec}");
        let e = graph_edges(&a);
        assert_eq!(a.linkages.len(), e - c.tiles.len(), "{spec}");
        assert_eq!(
            a.linkages.iter().map(|l| l.bars).sum::<usize>(),
            2 * e,
            "{spec}"
        );
        for l in &a.linkages {
            let k = l.bars;
            assert_eq!((l.nodes.len(), l.joints.len()), (k, k));
            // Canonical: the smallest node first, in cell 0.
            assert_eq!(l.nodes[0].1, [0, 0], "{spec}");
            assert!(l.nodes.iter().all(|n| *n >= l.nodes[0]), "{spec}");
            // Simple, jointed round the loop by the listed joints, and chordless.
            let set: BTreeSet<Node> = l.nodes.iter().copied().collect();
            assert_eq!(set.len(), k, "{spec}");
            for (i, j) in l.joints.iter().enumerate() {
                assert!(d.joints[j.edge].ends().contains(&j.end));
                assert!(pins(&c, j.edge, j.cell, l.nodes[i], l.nodes[(i + 1) % k]));
            }
            assert!(chords(&c, &d.joints, &l.nodes).is_empty(), "{spec}");
        }
        // One representative per translation class.
        for (i, p) in a.linkages.iter().enumerate() {
            for q in &a.linkages[i + 1..] {
                let shift = |n: &Node, t: [i32; 2]| (n.0, [n.1[0] + t[0], n.1[1] + t[1]]);
                let qs: BTreeSet<Node> = q.nodes.iter().copied().collect();
                for n in &q.nodes {
                    let t = [n.1[0] - p.nodes[0].1[0], n.1[1] - p.nodes[0].1[1]];
                    let ps: BTreeSet<Node> = p.nodes.iter().map(|m| shift(m, t)).collect();
                    assert_ne!(ps, qs, "{spec}: two translates of one linkage");
                }
            }
        }
    }
}

#[test]
fn a_hole_whose_boundary_has_a_chord_is_not_a_linkage() {
    // In this IH16 sheet one hole is bounded by seven tiles, two of which (not neighbours along
    // the loop) are also pinned to each other across a jointed triangle: the seven-tile loop is
    // not an induced cycle, so only the triangle is reported.
    let spec = "IH16:0.216506350946:1x1:aa-b-ab--";
    let (c, d, a) = analysis(spec);
    assert_eq!(a.signature, "1×3-bar");
    assert_eq!(a.other_faces.len(), 1);
    let face = &a.other_faces[0];
    assert_eq!(face.issue, FaceIssue::Chord);
    assert_eq!(face.nodes.len(), 7);
    assert!(!chords(&c, &d.joints, &face.nodes).is_empty());
    assert!(a.linkages.iter().all(|l| l.nodes != face.nodes));
}

#[test]
fn welded_squares_share_single_pins_and_strips_are_unbounded() {
    // Every edge of the square grid welded: the four squares round each grid vertex are all
    // pinned at that vertex, so the 4-cycle there encloses no hole that could open.
    let f = Family::from_number(76).unwrap();
    let cell = UnitCell::new(&Tiling::default_for(f), CellDims::new(2, 2).unwrap()).unwrap();
    let welded = analyze_linkages(&cell, &[JointChoice::Both; 8]).unwrap();
    assert_eq!(welded.signature, "none");
    assert_eq!(welded.other_faces.len(), 4);
    assert!(welded
        .other_faces
        .iter()
        .all(|o| o.issue == FaceIssue::SinglePoint && o.nodes.len() == 4));
    // A row of three squares pinned together and otherwise free (4×1 cell): the walk round
    // that finite cluster is its outline seen from outside, not a hole.
    let row = UnitCell::new(&Tiling::default_for(f), CellDims::new(4, 1).unwrap()).unwrap();
    let joints: Vec<JointChoice> = row
        .edges
        .iter()
        .map(|e| {
            let inside = e.offset == [0, 0] && e.tile_a.abs_diff(e.tile_b) == 1;
            if inside && e.tile_a.max(e.tile_b) <= 2 {
                JointChoice::A
            } else {
                JointChoice::None
            }
        })
        .collect();
    let cluster = analyze_linkages(&row, &joints).unwrap();
    assert_eq!(
        cluster.degree_histogram,
        BTreeMap::from([(0, 1), (1, 2), (2, 1)])
    );
    assert_eq!(cluster.signature, "none");
    assert!(cluster.other_faces.is_empty());
    // Squares pinned only along one tiling direction: infinite chains, no bounded face.
    let small = UnitCell::new(&Tiling::default_for(f), CellDims::MINIMAL).unwrap();
    let strips = analyze_linkages(&small, &[JointChoice::A, JointChoice::None]).unwrap();
    assert_eq!(strips.signature, "none");
    assert_eq!(strips.degree_histogram, BTreeMap::from([(2, 1)]));
    assert!(!strips.other_faces.is_empty());
    assert!(strips
        .other_faces
        .iter()
        .all(|o| o.issue == FaceIssue::Unbounded));
}

#[test]
fn a_welded_edge_is_one_graph_edge() {
    // Welding one hinge of rotating squares adds a pin but no neighbour and no hole: the two
    // pins of the weld bound a slit, which is not reported.
    let mut d = Design::resolve("rotating-squares").unwrap();
    let c = d.cell().unwrap();
    let plain = analyze_linkages(&c, &d.joints).unwrap();
    d.joints[0] = JointChoice::Both;
    let welded = analyze_linkages(&c, &d.joints).unwrap();
    assert_eq!(welded.signature, plain.signature);
    assert_eq!(welded.degree_histogram, plain.degree_histogram);
    assert!(welded.other_faces.is_empty());
}

#[test]
fn results_do_not_depend_on_units_or_orientation() {
    for spec in [
        "rotating-squares",
        "IH40::1x1:bbabbbbba",
        "IH16:0.216506350946:1x1:aa-b-ab--",
    ] {
        let (c, d, a) = analysis(spec);
        for (scale, angle) in [(1e-3, 0.3), (250.0, -2.0)] {
            let t = c.transformed(scale, angle);
            assert_eq!(analyze_linkages(&t, &d.joints).unwrap(), a, "{spec}");
        }
    }
}

#[test]
fn svg_has_a_legend_and_rasterises() {
    let (c, d, a) = analysis("IH16:0.216506350946:3x1:--a-bb-a-a-ab--ab-a--ba-bab");
    let svg = linkage_svg(&c, &d.joints, &a);
    assert!(svg.contains("3× 4-bar") && svg.contains("3× 6-bar"));
    assert!(svg.contains(isogami::render::linkage_colour(6)));
    #[cfg(feature = "render")]
    assert!(isogami::render::png_from_svg(&svg, 200, &isogami::render::Fonts::empty()).is_ok());
    // An analysis that does not belong to the cell draws no linkage, and does not panic.
    let other = analysis("rotating-squares").2;
    let _ = linkage_svg(&c, &d.joints[..2], &other);
}

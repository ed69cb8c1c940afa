//! Topology enumeration (paper §4.1): the four cheap checks on hand-made masks and against an
//! independent reference implementation, the pruned expansion against brute force, symmetry
//! and motion deduplication, and determinism.

use isogami::cell::{CellDims, UnitCell};
use isogami::explore::dedup::{is_repeat, joint_string};
use isogami::explore::{
    cells_to_explore, duplicates_across, enumerate_topologies, motion_invariant, sheet_symmetries,
    Expander, ExploreError, MaskVerdict, ReducedGraph, SeparationRule, SymmetryGroup,
    TopologyOptions,
};
use isogami::kinematics::Mechanism;
use isogami::mobility::{analyze, MobilitySettings};
use isogami::tiling::{Family, Tiling};
use isogami::topology::{Design, JointChoice};
use std::collections::{BTreeSet, HashSet, VecDeque};

fn cell(n: u32, a: u8, b: u8) -> UnitCell {
    let f = Family::from_number(n).unwrap();
    UnitCell::new(&Tiling::default_for(f), CellDims::new(a, b).unwrap()).unwrap()
}

fn all_mask(m: usize) -> u32 {
    ((1u64 << m) - 1) as u32
}

/// Independent reference for the four checks: explicit neighbour sets, BFS with offsets, and
/// a search for triangles among sheet tiles.
fn reference_verdict(c: &UnitCell, mask: u32) -> MaskVerdict {
    let n = c.tiles.len();
    let jointed: Vec<_> = c
        .edges
        .iter()
        .enumerate()
        .filter(|(k, _)| mask >> k & 1 == 1)
        .map(|(_, e)| *e)
        .collect();
    // Jointed neighbours of tile t (in cell 0) as sheet tiles (tile, offset).
    let nbrs = |t: usize| -> HashSet<(usize, [i32; 2])> {
        let mut s = HashSet::new();
        for e in &jointed {
            if e.tile_a == t {
                s.insert((e.tile_b, e.offset));
            }
            if e.tile_b == t {
                s.insert((e.tile_a, [-e.offset[0], -e.offset[1]]));
            }
        }
        s
    };
    if (0..n).any(|t| nbrs(t).len() < 2) {
        return MaskVerdict::Degree;
    }
    // BFS from tile 0, recording the copy offset at which each tile is reached.
    let mut pos: Vec<Option<[i32; 2]>> = vec![None; n];
    pos[0] = Some([0, 0]);
    let mut queue = VecDeque::from([0usize]);
    while let Some(t) = queue.pop_front() {
        let p = pos[t].unwrap();
        for (u, o) in nbrs(t) {
            if pos[u].is_none() {
                pos[u] = Some([p[0] + o[0], p[1] + o[1]]);
                queue.push_back(u);
            }
        }
    }
    if pos.iter().any(|p| p.is_none()) {
        return MaskVerdict::Connected;
    }
    let cycles: Vec<[i64; 2]> = jointed
        .iter()
        .map(|e| {
            let (pa, pb) = (pos[e.tile_a].unwrap(), pos[e.tile_b].unwrap());
            [
                i64::from(pa[0] + e.offset[0] - pb[0]),
                i64::from(pa[1] + e.offset[1] - pb[1]),
            ]
        })
        .collect();
    let rank2 = cycles
        .iter()
        .any(|a| cycles.iter().any(|b| a[0] * b[1] - a[1] * b[0] != 0));
    if !rank2 {
        return MaskVerdict::Directions;
    }
    for t in 0..n {
        let first: Vec<_> = nbrs(t).into_iter().collect();
        for (i, &(b, ob)) in first.iter().enumerate() {
            for &(cc, oc) in &first[i + 1..] {
                let rel = [oc[0] - ob[0], oc[1] - ob[1]];
                if nbrs(b).contains(&(cc, rel)) {
                    return MaskVerdict::Triangle;
                }
            }
        }
    }
    MaskVerdict::Pass
}

#[test]
fn rotating_squares_cell_hand_made_masks() {
    let c = cell(76, 2, 2);
    let g = ReducedGraph::new(&c).unwrap();
    let m = c.edges.len();
    assert_eq!(m, 8);
    // Every edge jointed passes all four checks.
    assert_eq!(g.verdict(all_mask(m)), MaskVerdict::Pass);
    // Leaving a tile one jointed edge (one neighbour) fails the degree check.
    for t in 0..c.tiles.len() {
        let incident: Vec<usize> = (0..m)
            .filter(|&k| c.edges[k].tile_a == t || c.edges[k].tile_b == t)
            .collect();
        assert_eq!(incident.len(), 4);
        for &keep in &incident {
            let mut mask = all_mask(m);
            for &k in &incident {
                if k != keep {
                    mask &= !(1 << k);
                }
            }
            assert_eq!(g.degree(t, mask), 1);
            assert_eq!(
                g.verdict(mask),
                MaskVerdict::Degree,
                "tile {t} keeps {keep}"
            );
        }
    }
    // Horizontal edges only (rows jointed within themselves): every square has its left and
    // right neighbour, but the two rows of the cell are not connected.
    let horizontal: u32 = (0..m)
        .filter(|&k| c.tiles[c.edges[k].tile_a].copy[1] == c.tiles[c.edges[k].tile_b].copy[1])
        .filter(|&k| c.edges[k].offset[1] == 0)
        .fold(0, |acc, k| acc | 1 << k);
    assert_eq!(horizontal.count_ones(), 4);
    assert_eq!(g.verdict(horizontal), MaskVerdict::Connected);
    // Adding the vertical edges inside the cell joins the rows into horizontal strips two
    // squares high: connected, but every cycle runs along u only.
    let inner_vertical: u32 = (0..m)
        .filter(|&k| horizontal >> k & 1 == 0 && c.edges[k].offset[1] == 0)
        .fold(0, |acc, k| acc | 1 << k);
    assert_eq!(inner_vertical.count_ones(), 2);
    assert_eq!(g.connectivity(horizontal | inner_vertical), (true, false));
    assert_eq!(
        g.verdict(horizontal | inner_vertical),
        MaskVerdict::Directions
    );
    // The same on the minimal cell: one square jointed to its right translate only has two
    // neighbours and is connected, but has one direction.
    let c1 = cell(76, 1, 1);
    let g1 = ReducedGraph::new(&c1).unwrap();
    let h1 = (0..2).find(|&k| c1.edges[k].offset[1] == 0).unwrap();
    assert_eq!(g1.degree(0, 1 << h1), 2);
    assert_eq!(g1.verdict(1 << h1), MaskVerdict::Directions);
    assert_eq!(g1.verdict(0b11), MaskVerdict::Pass);
    // The square grid has no three mutually adjacent squares: nothing fails check 4.
    assert!(g.triangles.is_empty());
    assert!((0..1u32 << m).all(|mask| g.verdict(mask) != MaskVerdict::Triangle));
    let r = g.enumerate();
    assert_eq!(r.after_directions, r.after_triangles);
    assert!(r.survivors.contains(&all_mask(m)));
}

#[test]
fn jointed_triangles_of_three_vertex_tiles() {
    // IH38: triangles with three-valent vertices; three tiles meet pairwise there.
    let c = cell(38, 1, 1);
    assert_eq!(c.tiles[0].polygon.len(), 3);
    let g = ReducedGraph::new(&c).unwrap();
    assert!(!g.triangles.is_empty());
    for tri in &g.triangles {
        let sides: Vec<u32> = tri.iter().map(|s| 1 << s.trailing_zeros()).collect();
        let joint_all = sides[0] | sides[1] | sides[2];
        assert!(g.has_jointed_triangle(joint_all));
        // The three sides are three different tile pairs among three tiles of the sheet.
        let tiles: BTreeSet<usize> = sides
            .iter()
            .flat_map(|s| {
                let e = c.edges[s.trailing_zeros() as usize];
                [e.tile_a, e.tile_b]
            })
            .collect();
        assert!(tiles.len() <= 3);
        for side in &sides {
            let two = joint_all & !side;
            assert!(!g.triangles.iter().any(|t| t.iter().all(|s| s & two != 0)));
        }
    }
    // All edges jointed: the only failing check is the triangle.
    assert_eq!(g.verdict(all_mask(c.edges.len())), MaskVerdict::Triangle);
    // A plain triangle tiling (IH93) has up and down triangles only: adjacency is bipartite
    // and no three tiles are mutually adjacent.
    let c93 = cell(93, 2, 2);
    assert_eq!(c93.tiles[0].polygon.len(), 3);
    let g93 = ReducedGraph::new(&c93).unwrap();
    assert!(g93.triangles.is_empty());
    // Hexagons (IH1): three meet at every vertex.
    let g1 = ReducedGraph::new(&cell(1, 1, 1)).unwrap();
    assert_eq!(g1.verdict(0b111), MaskVerdict::Triangle);
}

#[test]
fn checks_agree_with_reference_on_every_mask() {
    let mut cells = vec![
        cell(76, 2, 2),
        cell(76, 1, 3),
        cell(93, 2, 2),
        cell(1, 2, 1),
        cell(41, 2, 2),
    ];
    // Every family's minimal cell up to 12 edges.
    for f in Family::all() {
        let c = UnitCell::new(&Tiling::default_for(f), CellDims::MINIMAL).unwrap();
        if c.edges.len() <= 12 {
            cells.push(c);
        }
    }
    for c in &cells {
        let g = ReducedGraph::new(c).unwrap();
        let m = c.edges.len();
        let mut counts = [0u64; 5];
        for mask in 0..1u32 << m {
            let v = g.verdict(mask);
            assert_eq!(
                v,
                reference_verdict(c, mask),
                "{} {} mask {mask:b}",
                c.family,
                c.dims
            );
            counts[v as usize] += 1;
        }
        let r = g.enumerate();
        let pass = counts[MaskVerdict::Pass as usize];
        assert_eq!(r.after_triangles, pass);
        assert_eq!(r.survivors.len() as u64, pass);
        assert_eq!(
            r.after_degree,
            (1u64 << m) - counts[MaskVerdict::Degree as usize]
        );
        assert_eq!(
            r.after_directions,
            pass + counts[MaskVerdict::Triangle as usize]
        );
    }
}

/// All dof = 1 endpoint choices of every surviving mask, by analysing each one.
fn brute_force(c: &UnitCell) -> Vec<Vec<JointChoice>> {
    let g = ReducedGraph::new(c).unwrap();
    let m = c.edges.len();
    let mut out = Vec::new();
    for &mask in &g.enumerate().survivors {
        let edges: Vec<usize> = (0..m).filter(|&k| mask >> k & 1 == 1).collect();
        for bits in 0u32..1 << edges.len() {
            let mut j = vec![JointChoice::None; m];
            for (i, &e) in edges.iter().enumerate() {
                j[e] = if bits >> i & 1 == 0 {
                    JointChoice::A
                } else {
                    JointChoice::B
                };
            }
            let mech = Mechanism::new(c, &j).unwrap();
            let mob = analyze(&mech, &mech.rest, MobilitySettings::default()).unwrap();
            if mob.dof == 1 {
                out.push(j);
            }
        }
    }
    out
}

#[test]
fn pruned_expansion_matches_brute_force() {
    let mut pruned_somewhere = (0u64, 0u64, 0u64);
    for (n, a, b) in [
        (76, 2, 2),
        (44, 1, 1),
        (22, 1, 1),
        (49, 1, 1),
        (53, 1, 1),
        (93, 2, 1),
        (1, 2, 1),
        (7, 1, 1),
        (78, 1, 1),
        (41, 2, 2),
        (28, 1, 1),
    ] {
        let c = cell(n, a, b);
        let brute = brute_force(&c);
        let g = ReducedGraph::new(&c).unwrap();
        let ex = Expander::new(&c, MobilitySettings::default()).unwrap();
        let mut found = Vec::new();
        for &mask in &g.enumerate().survivors {
            let (j, s) = ex.expand_collect(mask);
            pruned_somewhere.0 += s.pruned_rigid;
            pruned_somewhere.1 += s.pruned_flexible;
            pruned_somewhere.2 += s.certified;
            found.extend(j);
        }
        let key = |v: &Vec<Vec<JointChoice>>| {
            let mut s: Vec<String> = v.iter().map(|j| joint_string(j)).collect();
            s.sort();
            s
        };
        assert_eq!(key(&found), key(&brute), "IH{n} {a}x{b}");
        // The pipeline expands one mask per symmetry orbit and weights by orbit size: its
        // count is the brute-force count.
        let r = enumerate_topologies(
            Family::from_number(n).unwrap(),
            CellDims::new(a, b).unwrap(),
            &TopologyOptions::default(),
        )
        .unwrap();
        assert_eq!(r.mobility_one, brute.len() as u64, "IH{n} {a}x{b}");
        assert_eq!(r.unconfirmed, 0);
    }
    assert!(pruned_somewhere.0 > 0 && pruned_somewhere.1 > 0 && pruned_somewhere.2 > 0);
}

#[test]
fn rotating_squares_is_among_the_unique_designs() {
    let rs = Design::resolve("rotating-squares").unwrap();
    let r = enumerate_topologies(rs.family, rs.dims, &TopologyOptions::default()).unwrap();
    assert!(r.unique > 0 && r.unique as usize == r.designs.len());
    let c = rs.cell().unwrap();
    let mech = Mechanism::new(&c, &rs.joints).unwrap();
    let mob = analyze(&mech, &mech.rest, MobilitySettings::default()).unwrap();
    assert_eq!(mob.dof, 1);
    let inv = motion_invariant(&c, &mech, &mob.motion.unwrap().vector);
    let matching: Vec<&Design> = r
        .designs
        .iter()
        .filter(|d| {
            let m = Mechanism::new(&c, &d.joints).unwrap();
            let mo = analyze(&m, &m.rest, MobilitySettings::default()).unwrap();
            assert_eq!(mo.dof, 1);
            motion_invariant(&c, &m, &mo.motion.unwrap().vector).matches(&inv, 1e-6)
        })
        .collect();
    assert_eq!(
        matching.len(),
        1,
        "exactly one kept design moves like rotating squares"
    );
    // The kept one is the smallest spec with that motion: no larger than the smallest image of
    // the named design under the sheet's symmetries.
    let group = SymmetryGroup::new(&c);
    assert!(group.key(&matching[0].joints) <= group.canonical_key(&rs.joints).0);
}

#[test]
fn symmetric_images_have_the_same_dof_and_motion() {
    for (n, a, b) in [(76, 2, 2), (28, 1, 1), (44, 2, 1), (90, 1, 2)] {
        let c = cell(n, a, b);
        let syms = sheet_symmetries(&c);
        assert!(syms.len() >= 2);
        let r = enumerate_topologies(c.family, c.dims, &TopologyOptions::default()).unwrap();
        for d in r.designs.iter().take(5) {
            let m = Mechanism::new(&c, &d.joints).unwrap();
            let mo = analyze(&m, &m.rest, MobilitySettings::default()).unwrap();
            let inv = motion_invariant(&c, &m, &mo.motion.unwrap().vector);
            for s in &syms {
                let img = s.apply(&d.joints);
                let mi = Mechanism::new(&c, &img).unwrap();
                let moi = analyze(&mi, &mi.rest, MobilitySettings::default()).unwrap();
                assert_eq!(moi.dof, 1, "IH{n} {a}x{b} image of {d}");
                let invi = motion_invariant(&c, &mi, &moi.motion.unwrap().vector);
                assert!(invi.matches(&inv, 1e-6), "IH{n} {a}x{b} image of {d}");
                // Joint strings of images are never smaller than the kept representative.
                assert!(joint_string(&img) >= joint_string(&d.joints));
            }
        }
    }
}

/// The 2×1 repeat of every kept 1×1 design is recognised as a repeat and not kept on 2×1.
#[test]
fn repeats_of_minimal_designs_are_removed() {
    for n in [44, 22, 53] {
        let f = Family::from_number(n).unwrap();
        let small =
            enumerate_topologies(f, CellDims::MINIMAL, &TopologyOptions::default()).unwrap();
        let big_dims = CellDims::new(2, 1).unwrap();
        let big_cell = cell(n, 2, 1);
        let big = enumerate_topologies(f, big_dims, &TopologyOptions::default()).unwrap();
        let group = SymmetryGroup::new(&big_cell);
        let kept: HashSet<u64> = big.designs.iter().map(|d| group.key(&d.joints)).collect();
        let aspects = small.tiles;
        assert!(!small.designs.is_empty());
        for d in &small.designs {
            let small_cell = d.cell().unwrap();
            // Copy the joints into both copies of the 2×1 cell.
            let mut joints = vec![JointChoice::None; big_cell.edges.len()];
            for (k, e) in small_cell.edges.iter().enumerate() {
                for copy in 0..2 {
                    let t = copy * aspects + e.tile_a;
                    let big_k = big_cell.tile_edges[t][e.edge_a];
                    let be = big_cell.edges[big_k];
                    let same_side = be.tile_a == t && be.edge_a == e.edge_a;
                    joints[big_k] = match (d.joints[k], same_side) {
                        (JointChoice::A, false) => JointChoice::B,
                        (JointChoice::B, false) => JointChoice::A,
                        (j, _) => j,
                    };
                }
            }
            let mech = Mechanism::new(&big_cell, &joints).unwrap();
            let mob = analyze(&mech, &mech.rest, MobilitySettings::default()).unwrap();
            // The repeat keeps the small design's motion; it may gain period-2 motions.
            assert!(mob.dof >= 1);
            if mob.dof == 1 {
                let v = mob.motion.unwrap().vector;
                let t1 = big_cell.u / 2.0;
                assert!(is_repeat(&big_cell, &mech, &joints, &v, t1), "IH{n} {d}");
                assert!(!kept.contains(&group.canonical_key(&joints).0), "IH{n} {d}");
            }
        }
    }
}

#[test]
fn separation_rules_nest() {
    let f = Family::from_number(28).unwrap();
    let count = |rule| {
        let opts = TopologyOptions {
            separation: rule,
            ..TopologyOptions::default()
        };
        enumerate_topologies(f, CellDims::MINIMAL, &opts).unwrap()
    };
    let any = count(SeparationRule::AnyEdge);
    let no_rigid = count(SeparationRule::NoRigidJoint);
    let every = count(SeparationRule::EveryEdge);
    assert_eq!(any.mobility_one, no_rigid.mobility_one);
    assert!(any.separating >= no_rigid.separating);
    assert!(no_rigid.separating >= every.separating);
    assert!(no_rigid.separating > 0);
    for d in &no_rigid.details {
        assert_eq!(d.separation.rigid_joints, 0);
        assert!(d.separation.moving_edges > 0);
    }
}

#[test]
fn counts_are_deterministic() {
    for (n, a, b) in [(21, 1, 1), (76, 2, 2), (30, 1, 1)] {
        let f = Family::from_number(n).unwrap();
        let d = CellDims::new(a, b).unwrap();
        let o = TopologyOptions::default();
        let r1 = enumerate_topologies(f, d, &o).unwrap();
        let r2 = enumerate_topologies(f, d, &o).unwrap();
        let counts = |r: &isogami::explore::TopologyReport| {
            (
                r.masks_total,
                r.after_degree,
                r.after_connected,
                r.after_directions,
                r.after_triangles,
                r.configurations_expanded,
                r.mobility_one,
                r.separating,
                r.symmetry_classes,
                r.after_repeats,
                r.unique,
            )
        };
        assert_eq!(counts(&r1), counts(&r2));
        assert_eq!(r1.designs, r2.designs);
        assert_eq!(r1.details, r2.details);
        // Sanity of the stage funnel.
        assert!(r1.masks_total >= r1.after_degree && r1.after_degree >= r1.after_connected);
        assert!(r1.after_connected >= r1.after_directions);
        assert!(r1.after_directions >= r1.after_triangles);
        assert!(r1.mobility_one >= r1.separating && r1.separating >= r1.symmetry_classes);
        assert!(r1.symmetry_classes >= r1.after_repeats && r1.after_repeats >= r1.unique);
        for (des, det) in r1.designs.iter().zip(&r1.details) {
            assert_eq!(des.to_string(), det.spec);
            assert_eq!(Design::resolve(&det.spec).unwrap(), *des);
        }
    }
}

#[test]
fn cells_to_explore_and_edge_limit() {
    let f = Family::from_number(76).unwrap();
    let cells = cells_to_explore(f, &TopologyOptions::default());
    // The square grid has 2 edges per square: a·b ≤ 8.
    assert_eq!(cells.len(), 12);
    assert!(cells
        .iter()
        .all(|(d, m)| *m == 2 * usize::from(d.a() * d.b()) && *m <= 16));
    assert!(cells.windows(2).all(|w| w[0].1 <= w[1].1));
    let small = TopologyOptions {
        max_edges: 4,
        max_dims: 2,
        ..TopologyOptions::default()
    };
    assert_eq!(cells_to_explore(f, &small).len(), 3);
    // IH77's minimal cell has 18 edges: refused with a message naming the limit.
    let e = enumerate_topologies(
        Family::from_number(77).unwrap(),
        CellDims::MINIMAL,
        &TopologyOptions::default(),
    )
    .unwrap_err();
    assert!(e.to_string().contains("18 unique edges"), "{e}");
    assert!(
        matches!(e, ExploreError::TooManyEdges { edges: 18, .. }),
        "{e:?}"
    );
}

#[test]
fn duplicates_across_cells_and_families() {
    let run = |n: u32, a: u8, b: u8| {
        enumerate_topologies(
            Family::from_number(n).unwrap(),
            CellDims::new(a, b).unwrap(),
            &TopologyOptions::default(),
        )
        .unwrap()
    };
    // The square grid's 2×3 and 3×2 cells are 90° twins: every 3×2 design moves like a 2×3
    // design, and nothing within one report is a duplicate (dedup already ran per cell).
    let twins = [run(76, 2, 3), run(76, 3, 2)];
    assert!(!twins[0].designs.is_empty());
    let d = duplicates_across(&twins, true);
    assert!(d[0].iter().all(|x| x.is_none()));
    assert!(d[1].iter().all(|x| matches!(x, Some((0, _)))));
    // IH2 and IH3 have congruent default sheets at 1×1: the same motions, seen only when
    // families are compared.
    let pair = [run(2, 1, 1), run(3, 1, 1)];
    assert_eq!(pair[0].unique, pair[1].unique);
    assert!(duplicates_across(&pair, true)[1]
        .iter()
        .all(|x| x.is_none()));
    assert!(duplicates_across(&pair, false)[1]
        .iter()
        .all(|x| matches!(x, Some((0, _)))));
    // Cells with different edge counts never match.
    let mixed = [run(76, 2, 2), run(76, 2, 3)];
    assert!(duplicates_across(&mixed, true)
        .iter()
        .flatten()
        .all(|x| x.is_none()));
}

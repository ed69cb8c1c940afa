//! Face tracing on the periodic sheet and the tests a face boundary must pass to be a linkage.
//!
//! A face is traced with the face on the left: arriving at a tile through one joint, the walk
//! follows the tile's boundary clockwise to the previous joint in the tile's counter-clockwise
//! order and leaves through it. Every dart lies on exactly one face. Tracing runs on the
//! quotient graph (tiles of one cell) while accumulating cell offsets, so each translation class
//! of faces of the infinite sheet is traced exactly once; a walk that closes with a non-zero
//! total offset (a drift) is an unbounded face.

use super::sheet::Sheet;
use std::collections::{BTreeSet, HashMap};

/// A node of the infinite sheet: a tile and the cell it sits in.
pub type Node = (usize, [i32; 2]);

/// One traced face: its darts in order and the node each dart leaves.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FaceWalk {
    /// Darts along the walk.
    pub darts: Vec<usize>,
    /// `nodes[i]` is the node that `darts[i]` leaves (the first one in cell 0).
    pub nodes: Vec<Node>,
    /// Total cell offset accumulated over the walk (zero for a bounded face).
    pub drift: [i32; 2],
}

fn add(a: [i32; 2], b: [i32; 2]) -> [i32; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

/// The dart that follows `d` on its face.
pub(crate) fn next_dart(sheet: &Sheet, d: usize) -> usize {
    let r = sheet.darts[d].rev;
    let rot = &sheet.rotation[sheet.darts[r].from];
    // `r` is in the rotation of its own tile by construction; fall back to itself otherwise.
    let p = rot.iter().position(|&x| x == r).unwrap_or(0);
    rot.get((p + rot.len() - 1) % rot.len().max(1))
        .copied()
        .unwrap_or(r)
}

/// All faces of the sheet, one per translation class.
pub(crate) fn trace_faces(sheet: &Sheet) -> Vec<FaceWalk> {
    let mut seen = vec![false; sheet.darts.len()];
    let mut faces = Vec::new();
    for start in 0..sheet.darts.len() {
        if seen[start] {
            continue;
        }
        let mut walk = FaceWalk {
            darts: Vec::new(),
            nodes: Vec::new(),
            drift: [0, 0],
        };
        let mut d = start;
        let mut at = [0, 0];
        // Each dart is visited once, so the loop ends after at most `darts.len()` steps.
        while !seen[d] {
            seen[d] = true;
            walk.darts.push(d);
            walk.nodes.push((sheet.darts[d].from, at));
            at = add(at, sheet.darts[d].offset);
            d = next_dart(sheet, d);
        }
        walk.drift = at;
        faces.push(walk);
    }
    faces
}

/// True when no node occurs twice.
pub(crate) fn is_simple(nodes: &[Node]) -> bool {
    let set: BTreeSet<&Node> = nodes.iter().collect();
    set.len() == nodes.len()
}

/// True when two nodes of the simple cycle `nodes` that are not neighbours along the cycle
/// are pinned together (`adjacent[t]` lists tile t's neighbours with relative offsets).
pub(crate) fn has_chord(nodes: &[Node], adjacent: &[BTreeSet<Node>]) -> bool {
    let k = nodes.len();
    let index: HashMap<Node, usize> = nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
    nodes.iter().enumerate().any(|(i, &(t, c))| {
        adjacent.get(t).is_some_and(|nb| {
            nb.iter().any(|&(t2, o)| match index.get(&(t2, add(c, o))) {
                Some(&j) => j != i && (i + 1) % k != j && (j + 1) % k != i,
                None => false,
            })
        })
    })
}

/// Translates and rotates a cyclic node list so that its smallest node, in (tile, cell) order,
/// comes first and sits in cell 0. Returns the rotation applied and the cell shift.
pub(crate) fn canonical_start(nodes: &[Node]) -> (usize, [i32; 2]) {
    let start = (0..nodes.len()).min_by_key(|&i| nodes[i]).unwrap_or(0);
    let c = nodes.get(start).map_or([0, 0], |n| n.1);
    (start, [-c[0], -c[1]])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::End;
    use crate::linkage::sheet::Dart;

    /// A finite planar graph given by, for each node, its neighbours in counter-clockwise order.
    fn hand_built(rot: &[&[usize]]) -> Sheet {
        let mut darts: Vec<Dart> = Vec::new();
        let mut index = HashMap::new();
        for (from, nbs) in rot.iter().enumerate() {
            for (k, &to) in nbs.iter().enumerate() {
                index.insert((from, to), darts.len());
                darts.push(Dart {
                    from,
                    to,
                    offset: [0, 0],
                    edge: 0,
                    end: End::A,
                    forward: from < to,
                    key: k,
                    rev: usize::MAX,
                });
            }
        }
        for d in &mut darts {
            d.rev = index[&(d.to, d.from)];
        }
        Sheet::from_darts(rot.len(), darts)
    }

    fn node_sets(faces: &[FaceWalk]) -> Vec<Vec<usize>> {
        let mut out: Vec<Vec<usize>> = faces
            .iter()
            .map(|f| {
                let mut v: Vec<usize> = f.nodes.iter().map(|n| n.0).collect();
                v.sort_unstable();
                v
            })
            .collect();
        out.sort();
        out
    }

    #[test]
    fn square_with_a_diagonal() {
        // 3 --- 2
        // |   / |
        // | /   |
        // 0 --- 1      the chord 0–2 splits the square into two triangles.
        let sheet = hand_built(&[&[1, 2, 3], &[2, 0], &[3, 0, 1], &[0, 2]]);
        let faces = trace_faces(&sheet);
        assert_eq!(
            node_sets(&faces),
            vec![vec![0, 1, 2], vec![0, 1, 2, 3], vec![0, 2, 3]]
        );
        let adj = sheet.neighbours();
        for f in &faces {
            assert!(is_simple(&f.nodes));
            assert_eq!(f.drift, [0, 0]);
            // The outer 4-cycle has the chord; the triangles cannot have one.
            assert_eq!(has_chord(&f.nodes, &adj), f.nodes.len() == 4, "{f:?}");
        }
    }

    #[test]
    fn dangling_node_makes_a_walk_repeat_a_node() {
        // Triangle 0,1,2 with node 3 hanging off node 0 inside the outer face.
        let sheet = hand_built(&[&[1, 2, 3], &[2, 0], &[0, 1], &[0]]);
        let faces = trace_faces(&sheet);
        assert_eq!(faces.len(), 2);
        let simple: Vec<bool> = faces.iter().map(|f| is_simple(&f.nodes)).collect();
        assert_eq!(simple.iter().filter(|&&s| s).count(), 1);
        // Every dart on exactly one face.
        assert_eq!(faces.iter().map(|f| f.darts.len()).sum::<usize>(), 8);
    }

    #[test]
    fn canonical_start_picks_smallest_node_and_moves_it_to_cell_zero() {
        let nodes = [(2, [1, 0]), (0, [1, 1]), (1, [0, 0])];
        assert_eq!(canonical_start(&nodes), (1, [-1, -1]));
    }
}

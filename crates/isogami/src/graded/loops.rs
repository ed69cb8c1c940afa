//! The pin graph of a graded sheet for its states part of the way: a basis of short cycles
//! (the loop closures), pin paths between tiles (the contact rows), and the placement of the
//! tiles from their rotations.
//!
//! In a state part of the way only the tiles' rotations are unknowns: once the pins close,
//! the positions follow from the rotations up to a translation, so carrying them would triple
//! the state's unknowns for nothing (at 400 tiles 4,882 unknowns instead of 10,482, and a
//! factorisation of the normal equations 20 ms instead of 50–60 ms). A chain of tiles joined
//! by pins places a point relative to where the chain starts: tile t, entered at node `from`
//! and left at node `to`, adds R(θ_t)(X_to − X_from). Around a cycle of the pin graph the sum
//! is zero when the pins close (a loop closure; closing a basis of cycles closes them all);
//! along a path it places one tile in another's frame (the contact rows).

use crate::math::{rotation, Real, Vec2};
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};
use std::collections::VecDeque;

/// One tile of a chain: the tile, the node it is entered at, the node it is left at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Segment {
    /// The tile.
    pub tile: usize,
    /// Node where the chain enters it.
    pub from: usize,
    /// Node where it leaves.
    pub to: usize,
}

/// Adjacency of the pin graph: per tile, (pin, other tile).
fn adjacency(tiles: usize, joints: &[(usize, usize, usize)]) -> Vec<Vec<(usize, usize)>> {
    let mut adj = vec![Vec::new(); tiles];
    for (p, &(a, b, _)) in joints.iter().enumerate() {
        adj[a].push((p, b));
        adj[b].push((p, a));
    }
    adj
}

/// Shortest pin path from `from` to `to` avoiding pin `avoid`: the pins in order, None when
/// there is none.
fn shortest_path(
    adj: &[Vec<(usize, usize)>],
    from: usize,
    to: usize,
    avoid: Option<usize>,
) -> Option<Vec<usize>> {
    let mut via: Vec<Option<(usize, usize)>> = vec![None; adj.len()];
    let mut seen = vec![false; adj.len()];
    seen[from] = true;
    let mut queue = VecDeque::from([from]);
    while let Some(t) = queue.pop_front() {
        if t == to {
            break;
        }
        for &(p, u) in &adj[t] {
            if Some(p) == avoid || seen[u] {
                continue;
            }
            seen[u] = true;
            via[u] = Some((p, t));
            queue.push_back(u);
        }
    }
    if !seen[to] {
        return None;
    }
    let mut pins = Vec::new();
    let mut t = to;
    while t != from {
        let (p, prev) = via[t].expect("a path");
        pins.push(p);
        t = prev;
    }
    pins.reverse();
    Some(pins)
}

/// The tiles of the closed walk `start` → (pins) → `start` as segments.
fn cycle_segments(joints: &[(usize, usize, usize)], start: usize, pins: &[usize]) -> Vec<Segment> {
    let k = pins.len();
    let mut tiles = Vec::with_capacity(k);
    let mut t = start;
    for &p in pins {
        tiles.push(t);
        let (a, b, _) = joints[p];
        t = if a == t { b } else { a };
    }
    debug_assert_eq!(t, start);
    // Tile j is left at pin j's node and entered at pin j−1's.
    (0..k)
        .map(|j| Segment {
            tile: tiles[j],
            from: joints[pins[(j + k - 1) % k]].2,
            to: joints[pins[j]].2,
        })
        .filter(|s| s.from != s.to)
        .collect()
}

/// GF(2) elimination over pin bitsets: inserts `v` if independent of what is kept.
struct Basis {
    /// Reduced vectors with their pivot bit.
    rows: Vec<(usize, Vec<u64>)>,
}

impl Basis {
    fn insert(&mut self, mut v: Vec<u64>) -> bool {
        for (pivot, row) in &self.rows {
            if v[pivot / 64] >> (pivot % 64) & 1 == 1 {
                for (a, b) in v.iter_mut().zip(row) {
                    *a ^= b;
                }
            }
        }
        match v.iter().position(|&w| w != 0) {
            Some(k) => {
                let pivot = 64 * k + v[k].trailing_zeros() as usize;
                self.rows.push((pivot, v));
                true
            }
            None => false,
        }
    }
}

/// The piece (connected component) of the pin graph each tile is in, and how many there are.
fn pieces(adj: &[Vec<(usize, usize)>]) -> (Vec<usize>, usize) {
    let mut piece = vec![usize::MAX; adj.len()];
    let mut count = 0;
    for s in 0..adj.len() {
        if piece[s] != usize::MAX {
            continue;
        }
        piece[s] = count;
        let mut stack = vec![s];
        while let Some(t) = stack.pop() {
            for &(_, u) in &adj[t] {
                if piece[u] == usize::MAX {
                    piece[u] = count;
                    stack.push(u);
                }
            }
        }
        count += 1;
    }
    (piece, count)
}

/// Longest cycle (in pins) enumerated exhaustively around every pin.
const SHORT_CYCLE: usize = 6;

/// Every simple pin path from `at` to `to` of at most `left` pins, pin `avoid` left out
/// (appended to `found`).
#[allow(clippy::too_many_arguments)]
fn short_paths(
    adj: &[Vec<(usize, usize)>],
    at: usize,
    to: usize,
    avoid: usize,
    left: usize,
    path: &mut Vec<usize>,
    on_path: &mut [bool],
    found: &mut Vec<Vec<usize>>,
) {
    if left == 0 {
        return;
    }
    for &(p, u) in &adj[at] {
        if p == avoid {
            continue;
        }
        if u == to {
            path.push(p);
            found.push(path.clone());
            path.pop();
            continue;
        }
        if on_path[u] {
            continue;
        }
        on_path[u] = true;
        path.push(p);
        short_paths(adj, u, to, avoid, left - 1, path, on_path, found);
        path.pop();
        on_path[u] = false;
    }
}

/// A basis of short cycles of the pin graph (the shortest cycle through every pin, kept
/// greedily by length while independent over GF(2); completed by fundamental cycles of a
/// BFS tree if that falls short), each as its segments.
pub fn cycle_basis(tiles: usize, joints: &[(usize, usize, usize)]) -> Vec<Vec<Segment>> {
    let adj = adjacency(tiles, joints);
    let rank = joints.len() + pieces(&adj).1 - tiles;
    let words = joints.len().div_ceil(64).max(1);
    let bits = |pins: &[usize]| {
        let mut v = vec![0u64; words];
        for &p in pins {
            v[p / 64] ^= 1 << (p % 64);
        }
        v
    };
    // Candidates: (pins of the cycle, starting tile). First every cycle of at most
    // SHORT_CYCLE pins through each pin (a depth-limited search: the shortest cycle of each
    // pin alone can leave a face of the pin graph to no pin, and the basis then needs a long
    // fundamental cycle instead: measured on 400 rotating squares, 72 of 361 cycles of 8 to
    // 36 pins), then the shortest cycle through each pin.
    let mut candidates: Vec<(Vec<usize>, usize)> = Vec::new();
    let mut known = std::collections::HashSet::new();
    for (p, &(a, b, _)) in joints.iter().enumerate() {
        let mut found = Vec::new();
        let mut path = Vec::new();
        let mut on_path = vec![false; tiles];
        on_path[b] = true;
        short_paths(
            &adj,
            b,
            a,
            p,
            SHORT_CYCLE - 1,
            &mut path,
            &mut on_path,
            &mut found,
        );
        for rest in found {
            let mut pins = vec![p];
            pins.extend(rest);
            let mut key = pins.clone();
            key.sort_unstable();
            if known.insert(key) {
                candidates.push((pins, a));
            }
        }
    }
    for (p, &(a, b, _)) in joints.iter().enumerate() {
        if let Some(path) = shortest_path(&adj, b, a, Some(p)) {
            let mut pins = vec![p];
            pins.extend(path);
            candidates.push((pins, a));
        }
    }
    // Fallback: fundamental cycles of a BFS tree from every component's first tile.
    let mut fallback: Vec<(Vec<usize>, usize)> = Vec::new();
    {
        let mut parent: Vec<Option<(usize, usize)>> = vec![None; tiles];
        let mut depth = vec![usize::MAX; tiles];
        let mut tree = vec![false; joints.len()];
        for s in 0..tiles {
            if depth[s] != usize::MAX {
                continue;
            }
            depth[s] = 0;
            let mut queue = VecDeque::from([s]);
            while let Some(t) = queue.pop_front() {
                for &(p, u) in &adj[t] {
                    if depth[u] == usize::MAX {
                        depth[u] = depth[t] + 1;
                        parent[u] = Some((p, t));
                        tree[p] = true;
                        queue.push_back(u);
                    }
                }
            }
        }
        for (p, &(a, b, _)) in joints.iter().enumerate() {
            if tree[p] {
                continue;
            }
            // Tree paths a → lca and b → lca.
            let (mut x, mut y) = (a, b);
            let (mut up_a, mut up_b) = (Vec::new(), Vec::new());
            while x != y {
                if depth[x] >= depth[y] {
                    let (q, t) = parent[x].unwrap();
                    up_a.push(q);
                    x = t;
                } else {
                    let (q, t) = parent[y].unwrap();
                    up_b.push(q);
                    y = t;
                }
            }
            // a → b by p, b → lca, lca → a.
            let mut pins = vec![p];
            pins.extend(up_b);
            up_a.reverse();
            pins.extend(up_a);
            fallback.push((pins, a));
        }
    }
    candidates.sort_by_key(|c| c.0.len());
    candidates.dedup_by(|x, y| {
        let (mut p, mut q) = (x.0.clone(), y.0.clone());
        p.sort_unstable();
        q.sort_unstable();
        p == q
    });
    fallback.sort_by_key(|c| c.0.len());
    let mut basis = Basis { rows: Vec::new() };
    let mut out = Vec::new();
    for (pins, start) in candidates.into_iter().chain(fallback) {
        if out.len() == rank {
            break;
        }
        if basis.insert(bits(&pins)) {
            out.push(cycle_segments(joints, start, &pins));
        }
    }
    assert_eq!(out.len(), rank, "the cycle basis falls short of the rank");
    out
}

/// The segments placing tile `b`'s entry node in tile `a`'s frame: a's first node → … →
/// b's entry node, and that entry node (None when b is not reachable). `pin`: the node a and b
/// are pinned at, if they are (one hop).
pub fn route(
    tiles: &[Vec<usize>],
    joints: &[(usize, usize, usize)],
    a: usize,
    b: usize,
    pin: Option<usize>,
) -> Option<(Vec<Segment>, usize)> {
    let first = tiles[a][0];
    if let Some(n) = pin {
        return Some((
            vec![Segment {
                tile: a,
                from: first,
                to: n,
            }],
            n,
        ));
    }
    let adj = adjacency(tiles.len(), joints);
    let pins = shortest_path(&adj, a, b, None)?;
    let mut segments = Vec::new();
    let (mut t, mut at) = (a, first);
    for &p in &pins {
        let (x, y, n) = joints[p];
        segments.push(Segment {
            tile: t,
            from: at,
            to: n,
        });
        t = if x == t { y } else { x };
        at = n;
    }
    Some((segments, at))
}

/// The positions of a state's tiles (their first nodes) from their rotations `thetas`: the
/// translations that close every pin best in least squares, each connected piece of the pin
/// graph keeping the mean position it had in `positions`.
///
/// The rotations of a fit close the loops only to its tolerance, so positions carried from
/// tile to tile along a tree of pins would add the loops' errors up towards the tree's
/// leaves; least squares spreads them over every pin instead (a graph Laplacian in the
/// translations, its gauge fixed at each piece's first tile).
pub fn place(
    firsts: &[usize],
    joints: &[(usize, usize, usize)],
    nodes: &[Vec2],
    thetas: &[Real],
    positions: &mut [Vec2],
) {
    let tiles = firsts.len();
    let adj = adjacency(tiles, joints);
    // Pieces of the pin graph; the first tile of each is held.
    let (piece, pieces) = pieces(&adj);
    let mut held = vec![false; pieces];
    let mut column = vec![None; tiles];
    let mut free = 0;
    for t in 0..tiles {
        if std::mem::replace(&mut held[piece[t]], true) {
            column[t] = Some(free);
            free += 1;
        }
    }
    if free == 0 {
        return;
    }
    // Pin (a, b, n): p_a + R_a (X_n − X_first(a)) − p_b − R_b (X_n − X_first(b)) = 0.
    let mut entries = Vec::with_capacity(3 * joints.len());
    let mut rhs = Mat::<Real>::zeros(free, 2);
    for &(a, b, n) in joints {
        let arm = |t: usize| rotation(thetas[t]) * (nodes[n] - nodes[firsts[t]]);
        let offset = arm(a) - arm(b);
        for (t, sign) in [(a, -1.0), (b, 1.0)] {
            if let Some(k) = column[t] {
                entries.push(Triplet::new(k, k, 1.0));
                rhs[(k, 0)] += sign * offset.x;
                rhs[(k, 1)] += sign * offset.y;
            }
        }
        if let (Some(i), Some(j)) = (column[a], column[b]) {
            entries.push(Triplet::new(i.max(j), i.min(j), -1.0));
        }
    }
    let laplacian = SparseColMat::<usize, Real>::try_new_from_triplets(free, free, &entries)
        .expect("indices within the reduced Laplacian");
    let llt = laplacian
        .sp_cholesky(Side::Lower)
        .expect("a graph Laplacian with a held tile in every piece is positive definite");
    llt.solve_in_place(rhs.as_mut());
    // Each piece keeps its mean position (the held tile is at 0 in the solution).
    let mut before = vec![(Vec2::zeros(), 0.0); pieces];
    let mut after = vec![Vec2::zeros(); pieces];
    for t in 0..tiles {
        let placed = column[t].map_or(Vec2::zeros(), |k| Vec2::new(rhs[(k, 0)], rhs[(k, 1)]));
        before[piece[t]].0 += positions[t];
        before[piece[t]].1 += 1.0;
        after[piece[t]] += placed;
        positions[t] = placed;
    }
    for t in 0..tiles {
        let (sum, count) = before[piece[t]];
        positions[t] += (sum - after[piece[t]]) / count;
    }
}

#[cfg(test)]
mod tests {
    use super::super::{setup, GradedRequest, GradedSheet};
    use super::*;

    /// Sheets of a square, a concave and a three-pin-per-corner design.
    fn sheets() -> Vec<GradedSheet> {
        [
            ("rotating-squares", 4, 5),
            ("IH27:0.141304,0.6046404,0.6953583:1x1:-aaaaaaaa-", 3, 3),
            ("IH61::1x1:aaaa", 3, 4),
        ]
        .into_iter()
        .map(|(design, rows, cols)| {
            let request = GradedRequest {
                design: design.into(),
                rows,
                cols,
                states: 3,
                ..GradedRequest::default()
            };
            setup(&request).unwrap().0
        })
        .collect()
    }

    fn joints(sheet: &GradedSheet) -> Vec<(usize, usize, usize)> {
        sheet.joints.iter().map(|j| (j.a, j.b, j.node)).collect()
    }

    /// The basis has as many cycles as the pin graph's cycle space is wide, and each is a
    /// closed walk: a segment leaves its tile at the node the next segment enters, and the
    /// two tiles are pinned there.
    #[test]
    fn the_cycle_basis_spans_the_cycle_space_with_closed_walks() {
        for sheet in sheets() {
            let joints = joints(&sheet);
            let tiles = sheet.tiles.len();
            let pieces = pieces(&adjacency(tiles, &joints)).1;
            let basis = cycle_basis(tiles, &joints);
            assert!(!basis.is_empty());
            assert_eq!(
                basis.len(),
                joints.len() + pieces - tiles,
                "{}",
                sheet.design
            );
            for cycle in &basis {
                for (k, seg) in cycle.iter().enumerate() {
                    let next = cycle[(k + 1) % cycle.len()];
                    assert_eq!(seg.to, next.from, "{}: {cycle:?}", sheet.design);
                    assert!(sheet.tiles[seg.tile].nodes.contains(&seg.from));
                    assert!(sheet.tiles[seg.tile].nodes.contains(&seg.to));
                    assert!(
                        joints.iter().any(|&(a, b, n)| n == seg.to
                            && ((a, b) == (seg.tile, next.tile)
                                || (b, a) == (seg.tile, next.tile))),
                        "{}: no pin between {} and {} at {}",
                        sheet.design,
                        seg.tile,
                        next.tile,
                        seg.to
                    );
                }
            }
        }
    }

    /// With the rotations of a state whose pins close, the placement gives back its
    /// positions; with rotations turned at random, the pins' residuals sum to zero at every
    /// tile (the least-squares condition) and every piece keeps its mean position.
    #[test]
    fn placing_closes_the_pins_in_least_squares() {
        for sheet in sheets() {
            let joints = joints(&sheet);
            let nodes: Vec<Vec2> = (0..sheet.nodes.len()).map(|k| sheet.node(k)).collect();
            let firsts: Vec<usize> = sheet.tiles.iter().map(|t| t.nodes[0]).collect();
            let state = &sheet.path[1];
            let original: Vec<Vec2> = state.iter().map(|p| Vec2::new(p.x, p.y)).collect();
            let mut thetas: Vec<Real> = state.iter().map(|p| p.theta).collect();
            let residual = |positions: &[Vec2],
                            thetas: &[Real],
                            (a, b, n): (usize, usize, usize)| {
                let at =
                    |t: usize| positions[t] + rotation(thetas[t]) * (nodes[n] - nodes[firsts[t]]);
                at(a) - at(b)
            };
            let widest = |positions: &[Vec2], thetas: &[Real]| {
                joints
                    .iter()
                    .map(|&j| residual(positions, thetas, j).norm())
                    .fold(0.0, Real::max)
            };
            assert!(widest(&original, &thetas) < 1e-9, "{}", sheet.design);
            let mut positions: Vec<Vec2> =
                original.iter().map(|p| p + Vec2::new(3.0, -1.0)).collect();
            place(&firsts, &joints, &nodes, &thetas, &mut positions);
            for (p, q) in positions.iter().zip(&original) {
                assert!(
                    (p - q - Vec2::new(3.0, -1.0)).norm() < 1e-9,
                    "{}",
                    sheet.design
                );
            }
            let mut seed = 5u64;
            for theta in thetas.iter_mut() {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                *theta += 0.05 * ((seed >> 11) as Real / (1u64 << 53) as Real - 0.5);
            }
            let mut positions = original.clone();
            place(&firsts, &joints, &nodes, &thetas, &mut positions);
            assert!(
                widest(&positions, &thetas) > 1e-4,
                "{}: turned",
                sheet.design
            );
            let mut force = vec![Vec2::zeros(); positions.len()];
            for &j in &joints {
                let r = residual(&positions, &thetas, j);
                force[j.0] += r;
                force[j.1] -= r;
            }
            for f in &force {
                assert!(f.norm() < 1e-9, "{}: {f:?}", sheet.design);
            }
            let mean = |p: &[Vec2]| p.iter().sum::<Vec2>() / p.len() as Real;
            assert!((mean(&positions) - mean(&original)).norm() < 1e-9);
        }
    }
}

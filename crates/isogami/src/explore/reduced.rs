//! The reduced topology space (paper §4.1): one bit per unique edge of the cell (bit k set =
//! edge k carries a joint, endpoint not yet chosen), filtered by the four cheap checks.
//!
//! Every check is evaluated on the periodic sheet, not on the cell's choice of representatives:
//!
//! 1. **degree ≥ 2** — a tile's neighbours are distinct (tile, relative cell offset) pairs over
//!    the jointed edges on either side of it; a tile jointed to its own translate at offset o
//!    has the two neighbours (tile, o) and (tile, −o).
//! 2. **path-connected** — union–find over the cell's tiles and the jointed edges.
//! 3. **two independent directions** — the offsets summed around the cycles of the cell's joint
//!    graph (a weighted union–find keeps each tile's offset relative to its root; every edge
//!    that closes a cycle contributes pot(a) + offset − pot(b)) span a rank-2 integer lattice.
//!    Raw edge offsets would depend on which copy represents a tile; cycle sums do not.
//! 4. **no jointed triangle** — no three distinct tiles of the infinite sheet that are pairwise
//!    adjacent and pairwise jointed (a 3-cycle of adjacencies whose offsets sum to zero).
//!
//! Masks are enumerated depth-first over the edges; as soon as every edge incident to a tile
//! has been decided, that tile's degree is final, and a subtree whose tile has degree < 2 is
//! dropped whole (all its masks fail check 1). All arithmetic on offsets is exact (integers).
//! Plain data in and out; no geometry beyond the cell's edge list, no kinematics, no I/O.

use crate::cell::UnitCell;
use serde::Serialize;

/// Largest number of unique edges the reduced space is enumerated for (masks are `u32`).
pub const MAX_REDUCED_EDGES: usize = 24;

/// A neighbour of a tile on the sheet, (tile, relative cell offset), with the mask of the
/// edges that realise it.
type ClassEntry = ((usize, [i32; 2]), u32);

/// The first check a joint mask fails, or `Pass`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum MaskVerdict {
    /// Some tile has fewer than two distinct jointed neighbours.
    Degree,
    /// The cell's tiles are not path-connected through joints.
    Connected,
    /// The cycle offsets of the joint graph do not span two independent directions.
    Directions,
    /// Three mutually adjacent tiles of the sheet are all jointed to each other.
    Triangle,
    /// All four checks pass.
    Pass,
}

/// The cell's adjacency structure, precomputed for fast mask tests.
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedGraph {
    /// Number of tiles.
    pub tiles: usize,
    /// Per unique edge: (tile_a, tile_b, offset of tile_b's copy).
    pub edges: Vec<(usize, usize, [i32; 2])>,
    /// Per tile: one bitmask of edges for each distinct neighbour (tile, offset) of the sheet.
    pub neighbour_classes: Vec<Vec<u32>>,
    /// Every triangle of mutually adjacent sheet tiles, as the edge masks of its three sides
    /// (a triangle is jointed when the mask meets all three).
    pub triangles: Vec<[u32; 3]>,
    /// Per edge k: the tiles whose incident edges all have index ≤ k (their degree is known
    /// once edge k is decided in the depth-first enumeration).
    completes_at: Vec<Vec<usize>>,
}

/// Counts of the reduced enumeration, and the surviving masks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReducedResult {
    /// 2^m.
    pub masks_total: u64,
    /// Masks with every tile of degree ≥ 2.
    pub after_degree: u64,
    /// … and path-connected.
    pub after_connected: u64,
    /// … and two independent cycle directions.
    pub after_directions: u64,
    /// … and no jointed triangle.
    pub after_triangles: u64,
    /// Survivors of the four checks that also pass Maxwell's count 2k ≥ 3n (k jointed edges,
    /// n tiles): with fewer joints every endpoint choice has dof ≥ 2. Reported, not filtered
    /// here; the expansion drops these masks at its root.
    pub after_counting: u64,
    /// The masks that pass all four checks, ascending.
    pub survivors: Vec<u32>,
}

impl ReducedGraph {
    /// Precomputes the neighbour classes and triangles of `cell`. `None` when the cell has
    /// more than [`MAX_REDUCED_EDGES`] unique edges.
    pub fn new(cell: &UnitCell) -> Option<ReducedGraph> {
        let edges: Vec<(usize, usize, [i32; 2])> = cell
            .edges
            .iter()
            .map(|e| (e.tile_a, e.tile_b, e.offset))
            .collect();
        ReducedGraph::from_edges(cell.tiles.len(), edges)
    }

    /// The same from a bare edge list (tile_a, tile_b, offset): for tests and other callers
    /// that have no cell. `None` when there are too many edges or an edge names a tile out of
    /// range.
    pub fn from_edges(tiles: usize, edges: Vec<(usize, usize, [i32; 2])>) -> Option<ReducedGraph> {
        if edges.len() > MAX_REDUCED_EDGES || edges.iter().any(|e| e.0 >= tiles || e.1 >= tiles) {
            return None;
        }
        // Neighbour keys (tile, offset) of each tile, with the edges that realise them.
        let mut keyed: Vec<Vec<ClassEntry>> = vec![Vec::new(); tiles];
        let mut add = |t: usize, key: (usize, [i32; 2]), bit: u32| match keyed[t]
            .iter_mut()
            .find(|(k, _)| *k == key)
        {
            Some((_, m)) => *m |= bit,
            None => keyed[t].push((key, bit)),
        };
        for (k, &(a, b, o)) in edges.iter().enumerate() {
            let bit = 1u32 << k;
            add(a, (b, o), bit);
            add(b, (a, [-o[0], -o[1]]), bit);
        }
        let neighbour_classes = keyed
            .iter()
            .map(|v| v.iter().map(|&(_, m)| m).collect())
            .collect();
        let triangles = find_triangles(&keyed);
        let mut completes_at = vec![Vec::new(); edges.len()];
        for t in 0..tiles {
            let last = edges
                .iter()
                .enumerate()
                .filter(|(_, e)| e.0 == t || e.1 == t)
                .map(|(k, _)| k)
                .max();
            if let Some(k) = last {
                completes_at[k].push(t);
            }
        }
        Some(ReducedGraph {
            tiles,
            edges,
            neighbour_classes,
            triangles,
            completes_at,
        })
    }

    /// Number of unique edges m.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// Number of distinct jointed neighbours of tile `t` under `mask`.
    pub fn degree(&self, t: usize, mask: u32) -> usize {
        self.neighbour_classes[t]
            .iter()
            .filter(|&&c| c & mask != 0)
            .count()
    }

    /// Check 1: every tile has at least two distinct jointed neighbours.
    pub fn degree_ok(&self, mask: u32) -> bool {
        (0..self.tiles).all(|t| self.degree_at_least_two(t, mask))
    }

    fn degree_at_least_two(&self, t: usize, mask: u32) -> bool {
        let mut hits = 0;
        for &c in &self.neighbour_classes[t] {
            if c & mask != 0 {
                hits += 1;
                if hits == 2 {
                    return true;
                }
            }
        }
        false
    }

    /// Checks 2 and 3 in one weighted union–find pass: `(connected, spans two directions)`.
    pub fn connectivity(&self, mask: u32) -> (bool, bool) {
        let mut uf = OffsetUnionFind::new(self.tiles);
        let mut first: Option<[i64; 2]> = None;
        let mut rank2 = false;
        let mut components = self.tiles;
        let mut bits = mask;
        while bits != 0 {
            let k = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            let (a, b, o) = self.edges[k];
            let o = [i64::from(o[0]), i64::from(o[1])];
            match uf.union(a, b, o) {
                None => components -= 1,
                Some(cycle) => {
                    if rank2 || cycle == [0, 0] {
                        continue;
                    }
                    match first {
                        None => first = Some(cycle),
                        Some(f) => rank2 = f[0] * cycle[1] - f[1] * cycle[0] != 0,
                    }
                }
            }
        }
        (components == 1, rank2)
    }

    /// Check 4: true when some triangle of sheet tiles is jointed on all three sides.
    pub fn has_jointed_triangle(&self, mask: u32) -> bool {
        self.triangles
            .iter()
            .any(|t| t[0] & mask != 0 && t[1] & mask != 0 && t[2] & mask != 0)
    }

    /// The first of the four checks that `mask` fails, in the paper's order.
    pub fn verdict(&self, mask: u32) -> MaskVerdict {
        if !self.degree_ok(mask) {
            return MaskVerdict::Degree;
        }
        self.verdict_after_degree(mask)
    }

    fn verdict_after_degree(&self, mask: u32) -> MaskVerdict {
        match self.connectivity(mask) {
            (false, _) => MaskVerdict::Connected,
            (true, false) => MaskVerdict::Directions,
            _ if self.has_jointed_triangle(mask) => MaskVerdict::Triangle,
            _ => MaskVerdict::Pass,
        }
    }

    /// Enumerates all 2^m masks depth-first with degree pruning and applies the four checks.
    pub fn enumerate(&self) -> ReducedResult {
        let m = self.edges.len();
        let mut out = ReducedResult {
            masks_total: 1u64 << m,
            after_degree: 0,
            after_connected: 0,
            after_directions: 0,
            after_triangles: 0,
            after_counting: 0,
            survivors: Vec::new(),
        };
        if self.tiles == 0 {
            return out;
        }
        self.descend(0, 0, &mut out);
        out.survivors.sort_unstable();
        out.after_counting = out
            .survivors
            .iter()
            .filter(|s| 2 * s.count_ones() as usize >= 3 * self.tiles)
            .count() as u64;
        out
    }

    /// Decides edge `k` both ways (recursion depth ≤ m ≤ 24).
    fn descend(&self, k: usize, mask: u32, out: &mut ReducedResult) {
        if k == self.edges.len() {
            out.after_degree += 1;
            match self.verdict_after_degree(mask) {
                MaskVerdict::Connected => {}
                MaskVerdict::Directions => out.after_connected += 1,
                MaskVerdict::Triangle => {
                    out.after_connected += 1;
                    out.after_directions += 1;
                }
                _ => {
                    out.after_connected += 1;
                    out.after_directions += 1;
                    out.after_triangles += 1;
                    out.survivors.push(mask);
                }
            }
            return;
        }
        for with in [false, true] {
            let next = if with { mask | (1 << k) } else { mask };
            if self.completes_at[k]
                .iter()
                .all(|&t| self.degree_at_least_two(t, next))
            {
                self.descend(k + 1, next, out);
            }
        }
    }
}

/// Union–find whose elements carry an integer offset relative to their root: `pot(x)` is the
/// cell offset of the copy of x reached from the root's copy at offset 0.
struct OffsetUnionFind {
    parent: Vec<usize>,
    pot: Vec<[i64; 2]>,
}

impl OffsetUnionFind {
    fn new(n: usize) -> Self {
        OffsetUnionFind {
            parent: (0..n).collect(),
            pot: vec![[0, 0]; n],
        }
    }

    /// Root of x and x's offset relative to it (with path compression).
    fn find(&mut self, x: usize) -> (usize, [i64; 2]) {
        let p = self.parent[x];
        if p == x {
            return (x, [0, 0]);
        }
        let (root, pp) = self.find(p);
        let px = self.pot[x];
        self.pot[x] = [px[0] + pp[0], px[1] + pp[1]];
        self.parent[x] = root;
        (root, self.pot[x])
    }

    /// Records that the copy of b at offset `o` is adjacent to a at offset 0. Returns `None`
    /// when this merged two components, or the cycle offset pot(a) + o − pot(b) when a and b
    /// were already connected.
    fn union(&mut self, a: usize, b: usize, o: [i64; 2]) -> Option<[i64; 2]> {
        let (ra, pa) = self.find(a);
        let (rb, pb) = self.find(b);
        if ra == rb {
            return Some([pa[0] + o[0] - pb[0], pa[1] + o[1] - pb[1]]);
        }
        // Place rb so that b sits at pa + o: pot(rb) = pa + o − pb relative to ra.
        self.parent[rb] = ra;
        self.pot[rb] = [pa[0] + o[0] - pb[0], pa[1] + o[1] - pb[1]];
        None
    }
}

/// All triangles of pairwise adjacent, distinct sheet tiles, as sorted triples of side masks
/// (deduplicated; translates of one triangle give the same triple).
fn find_triangles(keyed: &[Vec<ClassEntry>]) -> Vec<[u32; 3]> {
    let mut out: Vec<[u32; 3]> = Vec::new();
    for nbrs in keyed {
        for (i, &((b, ob), mab)) in nbrs.iter().enumerate() {
            for &((c, oc), mac) in &nbrs[i + 1..] {
                // Is (c, oc) adjacent to (b, ob)? Look for key (c, oc − ob) among b's classes.
                let rel = [oc[0] - ob[0], oc[1] - ob[1]];
                let Some(&(_, mbc)) = keyed[b].iter().find(|(k, _)| *k == (c, rel)) else {
                    continue;
                };
                // The three sheet tiles are distinct: keys of one class list are distinct and
                // a tile is never its own neighbour at offset 0.
                let mut t = [mab, mac, mbc];
                t.sort_unstable();
                if !out.contains(&t) {
                    out.push(t);
                }
            }
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One square per cell (square grid, minimal cell): edges to the right and up neighbour.
    #[test]
    fn single_square_cell() {
        let g = ReducedGraph::from_edges(1, vec![(0, 0, [1, 0]), (0, 0, [0, 1])]).unwrap();
        // One self-translate edge already gives two neighbours.
        assert_eq!(g.degree(0, 0b01), 2);
        assert_eq!(g.verdict(0b01), MaskVerdict::Directions);
        assert_eq!(g.verdict(0b11), MaskVerdict::Pass);
        assert!(g.triangles.is_empty());
        let r = g.enumerate();
        assert_eq!(
            (r.after_degree, r.after_connected, r.after_directions),
            (3, 3, 1)
        );
        assert_eq!(r.survivors, vec![0b11]);
    }

    /// Hexagon tiling, one tile per cell: three self-translate edges with offsets (1,0), (0,1),
    /// (1,1); three hexagons meet at every vertex.
    #[test]
    fn triangle_of_translates() {
        let g = ReducedGraph::from_edges(1, vec![(0, 0, [1, 0]), (0, 0, [0, 1]), (0, 0, [1, 1])])
            .unwrap();
        // (0,0),(1,0),(1,1) and (0,0),(0,1),(1,1) use the same three edges: one constraint.
        assert_eq!(g.triangles.len(), 1);
        assert_eq!(g.verdict(0b111), MaskVerdict::Triangle);
        assert_eq!(g.verdict(0b011), MaskVerdict::Pass);
    }

    #[test]
    fn cycle_offsets_not_raw_offsets() {
        // Two tiles: a–b at offset (1,0) and again a–b at offset (1,0) through another edge:
        // the raw offsets are non-zero but the cycle sums to zero (no direction at all).
        let g = ReducedGraph::from_edges(2, vec![(0, 1, [1, 0]), (0, 1, [1, 0]), (1, 0, [0, 1])])
            .unwrap();
        assert_eq!(g.connectivity(0b011), (true, false));
        // With the third edge: cycles (0,0) and (1,1): still rank 1.
        assert_eq!(g.connectivity(0b111), (true, false));
    }
}

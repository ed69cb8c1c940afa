//! The broad phase: which tiles of the infinite sheet can be near each other at a state.
//!
//! A pair is tile `a` of the centre cell against tile `b` of the cell at offset (k_u, k_w).
//! Each tile's collision polygon lies inside the circle of radius r (its extent) about the
//! tile's reference point, so two polygons are at least |p_b + k_u·u + k_w·w − p_a| − r_a − r_b
//! apart. [`near_pairs`] lists every pair whose circles come within a margin, over every
//! lattice translate (found exactly by [`super::lattice::Lattice`], not from a fixed block of
//! cells), each physical pair once. Energy, derivatives, clearance, the overlap test and
//! conservative advancement all take their pairs from here.

use super::lattice::LatticeProblem;
use super::placement::Placement;
use super::verlet::PairCache;
use crate::math::Real;

/// Tile `a` of the centre cell against tile `b` of the cell at `offset` = (k_u, k_w).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CandidatePair {
    /// Tile of the centre cell.
    pub a: usize,
    /// Tile of the other (or the centre) cell.
    pub b: usize,
    /// Cell offset of tile `b`'s copy.
    pub offset: [i32; 2],
}

impl CandidatePair {
    /// The listed orientation of the pair tile `a` (centre cell) – tile `b` (cell at
    /// `offset`), as [`near_pairs`] lists it: a < b, or a == b with the offset
    /// lexicographically positive. `None` for a tile against itself.
    pub fn canonical(a: usize, b: usize, offset: [i32; 2]) -> Option<CandidatePair> {
        let flipped = [-offset[0], -offset[1]];
        if a < b || (a == b && (offset[0], offset[1]) > (0, 0)) {
            Some(CandidatePair { a, b, offset })
        } else if a > b || (offset[0], offset[1]) < (0, 0) {
            Some(CandidatePair {
                a: b,
                b: a,
                offset: flipped,
            })
        } else {
            None
        }
    }
}

/// Fills `out` with every physical pair whose bounding circles (radii `extents` about the
/// tiles' reference points) are at most `margin` apart at `placed`. (a, 0)–(b, o) is the
/// translate of (b, 0)–(a, −o), so only a < b, or a == b with o lexicographically positive,
/// is listed; a tile is never paired with itself.
#[cfg(test)]
pub(crate) fn near_pairs(
    placed: &Placement,
    extents: &[Real],
    margin: Real,
    out: &mut Vec<CandidatePair>,
) -> Result<(), LatticeProblem> {
    out.clear();
    for_each_near_pair(placed, extents, margin, |p| out.push(p))
}

/// [`near_pairs`] without a list: calls `f` with each pair (the hot paths, which would
/// otherwise allocate a list per evaluation).
pub(crate) fn for_each_near_pair(
    placed: &Placement,
    extents: &[Real],
    margin: Real,
    mut f: impl FnMut(CandidatePair),
) -> Result<(), LatticeProblem> {
    let lattice = placed.lattice()?;
    let n = placed.tiles.len();
    for a in 0..n {
        for b in a..n {
            let d = placed.tiles[b].centre - placed.tiles[a].centre;
            let radius = extents[a] + extents[b] + margin;
            lattice.for_each_within(d, radius, |offset| {
                if a < b || (offset[0], offset[1]) > (0, 0) {
                    f(CandidatePair { a, b, offset });
                }
            })?;
        }
    }
    Ok(())
}

/// [`for_each_near_pair`], from the Verlet lists of `cache` when there is one (the same
/// pairs, see `verlet`).
pub(crate) fn for_each_near_pair_in(
    cache: Option<&mut PairCache>,
    placed: &Placement,
    extents: &[Real],
    margin: Real,
    f: impl FnMut(CandidatePair),
) -> Result<(), LatticeProblem> {
    match cache {
        Some(cache) => cache.for_each_near_pair(placed, extents, margin, f),
        None => for_each_near_pair(placed, extents, margin, f),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::StateLayout;
    use crate::math::{vec2, DVec, Vec2};
    use std::collections::HashSet;

    /// A unit square at the origin in a cell of `n` tiles on a row, u = (n, 0), w = (0, 1).
    fn row(n: usize) -> (Placement, Vec<Real>) {
        let layout = StateLayout { tiles: n };
        let sq = vec![
            vec2(-0.5, -0.5),
            vec2(0.5, -0.5),
            vec2(0.5, 0.5),
            vec2(-0.5, 0.5),
        ];
        let shapes: Vec<Vec<Vec2>> = vec![sq; n];
        let mut q = DVec::zeros(layout.len());
        for i in 0..n {
            q[layout.tile(i)] = i as Real;
        }
        q[layout.u()] = n as Real;
        q[layout.w() + 1] = 1.0;
        let extents = vec![0.5 * Real::sqrt(2.0); n];
        (Placement::new(layout, &shapes, &q), extents)
    }

    #[test]
    fn neighbours_of_a_square_grid_each_once() {
        for n in 1..5 {
            let (placed, extents) = row(n);
            let mut pairs = Vec::new();
            // Circles of the 8 neighbours of a unit square touch or overlap it; the next ring
            // (centre distance 2) lies beyond 2r = 1.414.
            near_pairs(&placed, &extents, 0.0, &mut pairs).unwrap();
            assert_eq!(pairs.len(), 4 * n, "n = {n}");
            let set: HashSet<_> = pairs.iter().map(|p| (p.a, p.b, p.offset)).collect();
            assert_eq!(set.len(), pairs.len());
            for p in &pairs {
                assert!(p.a <= p.b && !(p.a == p.b && p.offset == [0, 0]));
                let mirror = (p.b, p.a, [-p.offset[0], -p.offset[1]]);
                assert!(p.a == p.b || !set.contains(&mirror));
            }
            // A wider margin reaches the next ring: 24 neighbours within distance 2√2.
            near_pairs(&placed, &extents, Real::sqrt(2.0), &mut pairs).unwrap();
            assert_eq!(pairs.len(), 12 * n, "n = {n}");
        }
    }
}

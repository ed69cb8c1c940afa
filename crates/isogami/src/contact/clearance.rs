//! Clearance between collision polygons and the exact overlap test (independent of the
//! barrier).

use super::model::ContactModel;
use super::narrow::{min_vertex_edge_distance, polygon_distance, shifted_into, OVERLAP_TOL};
use super::pairs::CandidatePair;
use super::placement::Placement;
use super::verlet::PairCache;
use crate::geometry::interiors_overlap;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real, Vec2};

/// Pairs whose bounding boxes are farther apart than this (units of L) get the box gap as
/// their clearance in [`pair_clearance`] instead of the exact distance.
const EXACT_WITHIN: Real = 0.25;

/// Clearances are searched up to this distance (units of L): a reported clearance is the
/// smallest distance between collision polygons, or this value when every pair is farther.
pub const CLEARANCE_REACH: Real = 0.5;

/// Where two collision polygons of the sheet overlap.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Overlap {
    /// Tile `a` of the centre cell overlaps tile `b` of the cell at `offset`.
    Tiles(CandidatePair),
    /// The tiling vectors no longer span the plane (or the cell is far too small for its
    /// tiles), so translates of a tile coincide.
    DegenerateLattice,
}

impl std::fmt::Display for Overlap {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Overlap::Tiles(p) => write!(
                f,
                "tile {} in cell [0, 0] overlaps tile {} in cell {:?}",
                p.a, p.b, p.offset
            ),
            Overlap::DegenerateLattice => {
                f.write_str("the tiling vectors no longer span the plane")
            }
        }
    }
}

impl ContactModel {
    /// Smallest distance between any two collision polygons of the infinite sheet at q
    /// (non-dimensional), capped at [`CLEARANCE_REACH`]. For polygons that do not overlap this
    /// is the smallest vertex–edge distance; overlapping polygons count as 0, and so does a q
    /// that does not fit or whose lattice is degenerate. Always a lower bound of every pair's
    /// distance.
    pub fn min_clearance(&self, mech: &Mechanism, q: &DVec) -> Real {
        self.clearance(mech, q, true, None)
    }

    /// [`ContactModel::min_clearance`] for a state already known to be intersection-free
    /// (every state a conservatively advanced line search reaches from an intersection-free
    /// one): skips the exact overlap test, which dominates the cost. On an overlapping state
    /// the result is meaningless.
    pub fn min_clearance_in_free_set(&self, mech: &Mechanism, q: &DVec) -> Real {
        self.clearance(mech, q, false, None)
    }

    /// [`ContactModel::min_clearance_in_free_set`] with candidate pairs from `cache`.
    pub(crate) fn min_clearance_in_free_set_cached(
        &self,
        mech: &Mechanism,
        q: &DVec,
        cache: &mut PairCache,
    ) -> Real {
        self.clearance(mech, q, false, Some(cache))
    }

    fn clearance(
        &self,
        mech: &Mechanism,
        q: &DVec,
        check_overlap: bool,
        cache: Option<&mut PairCache>,
    ) -> Real {
        let Some(placed) = self.place(mech, q) else {
            return 0.0;
        };
        let mut best = CLEARANCE_REACH;
        let mut other = Vec::new();
        let listed = self.for_each_pair(cache, &placed, CLEARANCE_REACH, |pair| {
            let shift = placed.shift(pair.offset);
            let (ta, tb) = (&placed.tiles[pair.a], &placed.tiles[pair.b]);
            if ta.aabb.gap(&tb.aabb.shifted(shift)) >= best {
                return;
            }
            shifted_into(&tb.world, shift, &mut other);
            let d = if check_overlap {
                polygon_distance(&ta.world, &other)
            } else {
                min_vertex_edge_distance(&ta.world, &other)
            };
            best = best.min(d);
        });
        if listed.is_err() {
            return 0.0;
        }
        best
    }

    /// The first pair of collision polygons of the infinite sheet that overlap at q, by the
    /// exact polygon test [`crate::geometry::interiors_overlap`] with a 10⁻¹² L tolerance,
    /// over every lattice translate whose bounding circle meets the tile's. `None` when no
    /// pair overlaps or when `mech`, q do not fit (see [`ContactModel::check`]).
    pub fn overlapping_pair(&self, mech: &Mechanism, q: &DVec) -> Option<Overlap> {
        let placed = self.place(mech, q)?;
        let Some(pairs) = self.near(&placed, 0.0) else {
            return Some(Overlap::DegenerateLattice);
        };
        let mut other = Vec::new();
        pairs.into_iter().find_map(|pair| {
            let ta = &placed.tiles[pair.a];
            shifted_into(
                &placed.tiles[pair.b].world,
                placed.shift(pair.offset),
                &mut other,
            );
            interiors_overlap(&ta.world, &other, OVERLAP_TOL).then_some(Overlap::Tiles(pair))
        })
    }
}

/// A lower bound of one pair's distance at a placement: the box gap when the boxes are
/// farther apart than [`EXACT_WITHIN`], else the exact distance. With `check_overlap` the
/// exact distance is 0 for overlapping polygons; without it, it is the smallest vertex–edge
/// distance (valid only when the polygons are known not to overlap).
pub(crate) fn pair_clearance(
    placed: &Placement,
    pair: &CandidatePair,
    check_overlap: bool,
    other: &mut Vec<Vec2>,
) -> Real {
    let shift = placed.shift(pair.offset);
    let (ta, tb) = (&placed.tiles[pair.a], &placed.tiles[pair.b]);
    let gap = ta.aabb.gap(&tb.aabb.shifted(shift));
    if gap > EXACT_WITHIN {
        return gap;
    }
    shifted_into(&tb.world, shift, other);
    if check_overlap {
        polygon_distance(&ta.world, other)
    } else {
        min_vertex_edge_distance(&ta.world, other)
    }
}

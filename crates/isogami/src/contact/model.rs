//! The contact model of one mechanism: inset collision polygons and candidate pairs.

use super::error::ContactError;
use super::inset::inset_polygon;
use super::lattice::LatticeProblem;
use super::pairs::{for_each_near_pair_in, CandidatePair};
use super::placement::Placement;
use super::settings::ContactSettings;
use super::verlet::PairCache;
use crate::kinematics::{Mechanism, StateLayout};
use crate::math::{DVec, Real, Vec2};
use std::collections::HashSet;
use std::sync::Arc;

/// Collision geometry and barrier of one mechanism, precomputed once.
///
/// Every query takes the mechanism the model was built from and a state q. When they do not
/// fit (another tile count, a q of the wrong length or with NaN/∞ entries; see
/// [`ContactModel::check`]) the queries do not panic: they answer conservatively (energy
/// +∞, clearance 0, safe step 0, nothing added to gradient and Hessian, no polygons).
#[derive(Debug, Clone)]
pub struct ContactModel {
    pub(crate) settings: ContactSettings,
    pub(crate) layout: StateLayout,
    /// Inset polygons in each tile's frame (counter-clockwise, units of L).
    pub(crate) shapes: Vec<Vec<Vec2>>,
    /// Largest |s| over each inset polygon's vertices: the lever arm of a rotation and the
    /// radius of the polygon's bounding circle about its reference point.
    pub(crate) extents: Vec<Real>,
    /// When set, the only pairs that can touch (canonical, see [`CandidatePair::canonical`]):
    /// the pairs of tiles a finite sheet holds ([`ContactModel::restricted_to`]).
    pub(crate) only: Option<Arc<HashSet<CandidatePair>>>,
}

impl ContactModel {
    /// Insets every tile of `mech` by kerf / 2. Which tiles can touch is decided afresh at
    /// every state, over every lattice translate (see [`ContactModel::pairs_at`]).
    ///
    /// Fails on invalid settings, or naming the tile whose inset polygon is not simple,
    /// flips orientation or loses an edge (the kerf is too wide for that tile).
    pub fn new(mech: &Mechanism, settings: ContactSettings) -> Result<ContactModel, ContactError> {
        settings.validate()?;
        let layout = mech.layout;
        if mech.tile_shapes.len() != layout.tiles || mech.rest.len() != layout.len() {
            return Err(ContactError::MechanismShape {
                shapes: mech.tile_shapes.len(),
                rest: mech.rest.len(),
                tiles: layout.tiles,
            });
        }
        if mech.rest.iter().any(|x| !x.is_finite()) {
            return Err(ContactError::NonFiniteRest);
        }
        let shapes = inset_all(&mech.tile_shapes, 0.5 * settings.kerf)?;
        let extents = shapes
            .iter()
            .map(|s| s.iter().map(|v| v.norm()).fold(0.0, Real::max))
            .collect();
        Ok(ContactModel {
            settings,
            layout,
            shapes,
            extents,
            only: None,
        })
    }

    /// This model with contact only between `pairs` (in either orientation): a finite sheet
    /// that moves with the periodic motion touches only where two of its own tiles meet, so
    /// its contact is the periodic model's restricted to the pairs of tiles it holds. Every
    /// query (energy, derivatives, clearance, overlap, safe step) sees only those pairs.
    pub fn restricted_to(mut self, pairs: impl IntoIterator<Item = CandidatePair>) -> ContactModel {
        let set = pairs
            .into_iter()
            .filter_map(|p| CandidatePair::canonical(p.a, p.b, p.offset))
            .collect();
        self.only = Some(Arc::new(set));
        self
    }

    /// Whether the model sees only some pairs ([`ContactModel::restricted_to`]).
    pub fn is_restricted(&self) -> bool {
        self.only.is_some()
    }

    /// Calls `f` with every pair the model sees whose bounding circles come within `margin`
    /// at `placed` (from the Verlet lists of `cache` when given): the one place every
    /// contact query takes its pairs from.
    pub(crate) fn for_each_pair(
        &self,
        cache: Option<&mut PairCache>,
        placed: &Placement,
        margin: Real,
        mut f: impl FnMut(CandidatePair),
    ) -> Result<(), LatticeProblem> {
        match &self.only {
            None => for_each_near_pair_in(cache, placed, &self.extents, margin, f),
            Some(only) => for_each_near_pair_in(cache, placed, &self.extents, margin, |p| {
                if only.contains(&p) {
                    f(p)
                }
            }),
        }
    }

    /// The settings the model was built with.
    pub fn settings(&self) -> &ContactSettings {
        &self.settings
    }

    /// Each tile's collision polygon in its own frame (vertex k is the inset of the tile's
    /// vertex k).
    pub fn collision_shapes(&self) -> &[Vec<Vec2>] {
        &self.shapes
    }

    /// Every physical pair of tiles of the infinite sheet (tile `a` of the centre cell, tile
    /// `b` of the cell at `offset`, each pair once) whose collision polygons' bounding circles
    /// come within `margin` (units of L) of each other at state q. Every pair whose polygons
    /// are closer than `margin` is among them, from whatever lattice translate. `None` when
    /// `mech`, q do not fit the model or the lattice of q is degenerate (u ∥ w).
    pub fn pairs_at(&self, mech: &Mechanism, q: &DVec, margin: Real) -> Option<Vec<CandidatePair>> {
        let placed = self.place(mech, q)?;
        self.near(&placed, margin)
    }

    /// [`ContactModel::pairs_at`] on a placement.
    pub(crate) fn near(&self, placed: &Placement, margin: Real) -> Option<Vec<CandidatePair>> {
        let mut out = Vec::new();
        self.for_each_pair(None, placed, margin, |p| out.push(p))
            .ok()?;
        Some(out)
    }

    /// Checks that `mech` and `q` fit this model: same number of tiles, q of length 3n + 4,
    /// every entry finite.
    pub fn check(&self, mech: &Mechanism, q: &DVec) -> Result<(), ContactError> {
        if mech.layout != self.layout {
            return Err(ContactError::MechanismMismatch {
                model: self.layout.tiles,
                mechanism: mech.layout.tiles,
            });
        }
        if q.len() != self.layout.len() {
            return Err(ContactError::StateLength {
                len: q.len(),
                expected: self.layout.len(),
            });
        }
        if q.iter().any(|x| !x.is_finite()) {
            return Err(ContactError::NonFiniteState);
        }
        Ok(())
    }

    /// The collision polygons placed at q, or `None` when `mech`, q do not fit.
    pub(crate) fn place(&self, mech: &Mechanism, q: &DVec) -> Option<Placement> {
        self.check(mech, q).ok()?;
        Some(Placement::new(self.layout, &self.shapes, q))
    }

    /// World collision polygons of every tile in every cell of the 3×3 block at state q
    /// (for rendering): (tile, [k_u, k_w], polygon). Empty when `mech`, q do not fit.
    pub fn collision_polygons(
        &self,
        mech: &Mechanism,
        q: &DVec,
    ) -> Vec<(usize, [i32; 2], Vec<Vec2>)> {
        let Some(placed) = self.place(mech, q) else {
            return Vec::new();
        };
        let mut out = Vec::with_capacity(9 * self.layout.tiles);
        for ku in -1..=1 {
            for kw in -1..=1 {
                for i in 0..self.layout.tiles {
                    out.push((i, [ku, kw], placed.polygon(i, [ku, kw])));
                }
            }
        }
        out
    }
}

/// Every tile inset by `h`, or an error naming the first tile that cannot be.
fn inset_all(tiles: &[Vec<Vec2>], h: Real) -> Result<Vec<Vec<Vec2>>, ContactError> {
    tiles
        .iter()
        .enumerate()
        .map(|(i, poly)| {
            inset_polygon(poly, h).map_err(|problem| ContactError::Inset {
                tile: i,
                inset: h,
                problem,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::topology::Design;

    /// Rotating squares turned into overlap: tile 1 by a tenth of a radian.
    fn squares() -> (Mechanism, ContactModel, DVec) {
        let design = Design::resolve("rotating-squares").unwrap();
        let mech = Mechanism::new(&design.cell().unwrap(), &design.joints).unwrap();
        let model = ContactModel::new(&mech, ContactSettings::default()).unwrap();
        let mut q = mech.rest.clone();
        q[mech.layout.tile(1) + 2] += 0.1;
        (mech, model, q)
    }

    #[test]
    fn a_model_restricted_to_every_near_pair_is_the_whole_model() {
        let (mech, full, q) = squares();
        let pairs = full.pairs_at(&mech, &q, 1.0).unwrap();
        assert!(!pairs.is_empty());
        // Listed in the other orientation: the restriction canonicalises.
        let flipped = pairs.iter().map(|p| CandidatePair {
            a: p.b,
            b: p.a,
            offset: [-p.offset[0], -p.offset[1]],
        });
        let restricted = full.clone().restricted_to(flipped);
        assert!(restricted.is_restricted());
        assert_eq!(restricted.pairs_at(&mech, &q, 1.0).unwrap(), pairs);
        assert!(full.overlapping_pair(&mech, &q).is_some());
        assert_eq!(
            restricted.overlapping_pair(&mech, &q),
            full.overlapping_pair(&mech, &q)
        );
        let rest = &mech.rest;
        assert_eq!(
            restricted.min_clearance(&mech, rest),
            full.min_clearance(&mech, rest)
        );
    }

    #[test]
    fn a_model_restricted_to_no_pair_sees_no_contact() {
        let (mech, full, q) = squares();
        let none = full.restricted_to(std::iter::empty());
        assert_eq!(none.pairs_at(&mech, &q, 1.0).unwrap(), Vec::new());
        assert!(none.overlapping_pair(&mech, &q).is_none());
        assert_eq!(none.energy(&mech, &q), 0.0);
        assert_eq!(none.min_clearance(&mech, &q), super::super::CLEARANCE_REACH);
    }
}

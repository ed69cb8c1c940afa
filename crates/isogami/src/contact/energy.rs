//! The barrier energy E_coll(q).

use super::barrier::barrier_energy;
use super::model::ContactModel;
use super::narrow::{for_each_close, shifted_into, OVERLAP_TOL};
use super::verlet::PairCache;
use crate::geometry::interiors_overlap;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};

impl ContactModel {
    /// E_coll(q): the sum over candidate pairs of b(d) for every vertex–edge combination (both
    /// directions) closer than d̂. A corner near a corner is counted once per adjacent edge,
    /// as in IPC's 2D point–edge formulation.
    ///
    /// +∞ when some vertex lies on an edge (d ≤ 0), when two collision polygons overlap (the
    /// exact test, so a tile that jumped through another is caught), or when `mech`, q do
    /// not fit the model or its lattice is degenerate. Pairs come from the broad phase (every
    /// lattice translate whose bounding circle is within d̂), then one box test each.
    pub fn energy(&self, mech: &Mechanism, q: &DVec) -> Real {
        self.barrier_sum(mech, q, true, None)
    }

    /// [`ContactModel::energy`] for a state already known to be intersection-free (see
    /// [`ContactModel::min_clearance_in_free_set`]): skips the exact overlap test.
    pub fn energy_in_free_set(&self, mech: &Mechanism, q: &DVec) -> Real {
        self.barrier_sum(mech, q, false, None)
    }

    /// [`ContactModel::energy_in_free_set`] with candidate pairs from `cache`.
    pub(crate) fn energy_in_free_set_cached(
        &self,
        mech: &Mechanism,
        q: &DVec,
        cache: &mut PairCache,
    ) -> Real {
        self.barrier_sum(mech, q, false, Some(cache))
    }

    fn barrier_sum(
        &self,
        mech: &Mechanism,
        q: &DVec,
        check_overlap: bool,
        cache: Option<&mut PairCache>,
    ) -> Real {
        let Some(placed) = self.place(mech, q) else {
            return Real::INFINITY;
        };
        let (dhat, kappa) = (self.settings.dhat, self.settings.stiffness);
        let mut total = 0.0;
        let mut other = Vec::new();
        let mut blocked = false;
        let listed = self.for_each_pair(cache, &placed, dhat, |pair| {
            if blocked {
                return;
            }
            let shift = placed.shift(pair.offset);
            let (ta, tb) = (&placed.tiles[pair.a], &placed.tiles[pair.b]);
            if !ta.aabb.near(&tb.aabb.shifted(shift), dhat) {
                return;
            }
            shifted_into(&tb.world, shift, &mut other);
            let mut e = 0.0;
            for_each_close(&ta.world, &other, dhat, |c| {
                e += barrier_energy(c.d, dhat, kappa);
            });
            if !e.is_finite()
                || (check_overlap && interiors_overlap(&ta.world, &other, OVERLAP_TOL))
            {
                blocked = true;
            }
            total += e;
        });
        if blocked || listed.is_err() {
            return Real::INFINITY;
        }
        total
    }
}

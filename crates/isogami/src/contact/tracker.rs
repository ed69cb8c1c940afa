//! A cheap guard in front of conservative advancement: a lower bound on the sheet's
//! clearance, carried from step to step, that lets most line-search steps through without
//! any geometry.

use super::clearance::CLEARANCE_REACH;
use super::model::ContactModel;
use super::placement::Placement;
use super::reach::{clearance_drop_rate, Rates, Spread};
use super::verlet::PairCache;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};

/// Keeps a lower bound on the smallest distance between any two collision polygons of the
/// infinite sheet while a solver moves the state. Pairs whose bounding circles are within
/// [`CLEARANCE_REACH`] are listed with their cell offsets, and a step α·Δ brings each closer by
/// at most α times its exact approach rate; every other pair is farther than the reach and
/// is covered for all lattice translates at once by `reach::clearance_drop_rate`. While both
/// bounds stay below 90 % of what they must not exceed, the whole step is safe without any
/// distance computation. Otherwise the clearance is recomputed, and if that is still not
/// enough the exact conservative advancement [`ContactModel::max_safe_step`] decides.
#[derive(Debug, Clone)]
pub struct ClearanceTracker {
    clearance_lb: Option<Real>,
    /// Per unit step of the last direction asked about: the largest approach rate of a pair
    /// within reach, and the drop rate bound of the pairs beyond it (`None`: unknown).
    pending: Option<(Real, Real)>,
}

impl ClearanceTracker {
    /// A tracker with a known lower bound on the starting state's clearance, if there is one.
    pub fn new(clearance: Option<Real>) -> ClearanceTracker {
        ClearanceTracker {
            clearance_lb: clearance.filter(|c| c.is_finite() && *c >= 0.0),
            pending: None,
        }
    }

    /// A fraction α ∈ [0, 1] of `d` that is safe from `q` (which must be intersection-free).
    pub fn fraction(
        &mut self,
        mech: &Mechanism,
        contact: &ContactModel,
        q: &DVec,
        d: &DVec,
    ) -> Real {
        self.fraction_from(mech, contact, q, d, None)
    }

    /// [`ClearanceTracker::fraction`] with candidate pairs from `cache`.
    pub(crate) fn fraction_cached(
        &mut self,
        mech: &Mechanism,
        contact: &ContactModel,
        q: &DVec,
        d: &DVec,
        cache: &mut PairCache,
    ) -> Real {
        self.fraction_from(mech, contact, q, d, Some(cache))
    }

    fn fraction_from(
        &mut self,
        mech: &Mechanism,
        contact: &ContactModel,
        q: &DVec,
        d: &DVec,
        mut cache: Option<&mut PairCache>,
    ) -> Real {
        self.pending = None;
        if contact.check(mech, q).is_err() || d.len() != q.len() || d.iter().any(|x| !x.is_finite())
        {
            return 0.0;
        }
        let placed = Placement::centres_only(contact.layout, q);
        let Some(spread) = Spread::of(&placed, &contact.extents) else {
            return 0.0;
        };
        let rates = Rates::of(contact.layout, &contact.extents, d);
        if rates.point == 0.0 && rates.lattice == 0.0 {
            self.pending = Some((0.0, 0.0));
            return 1.0;
        }
        let rate = contact.approach_rate(d);
        let mut near: Real = 0.0;
        let listed = contact.for_each_pair(cache.as_deref_mut(), &placed, CLEARANCE_REACH, |p| {
            near = near.max(rate(&p))
        });
        if listed.is_err() {
            return 0.0;
        }
        let far = clearance_drop_rate(&spread, &rates, CLEARANCE_REACH);
        self.pending = far.map(|f| (near, f));
        let far_safe = far.is_some_and(|f| 0.9 * CLEARANCE_REACH >= f);
        let near_safe = |c: Real| 0.9 * c >= near;
        if far_safe && self.clearance_lb.is_some_and(near_safe) {
            return 1.0;
        }
        let c = match cache.as_deref_mut() {
            Some(cache) => contact.min_clearance_in_free_set_cached(mech, q, cache),
            None => contact.min_clearance_in_free_set(mech, q),
        };
        self.clearance_lb = Some(c);
        if far_safe && near_safe(c) {
            return 1.0;
        }
        // q is intersection-free (this method's precondition): no exact overlap test again.
        contact
            .max_safe_step_in_free_set(mech, q, d, cache)
            .min(1.0)
    }

    /// The current lower bound on the clearance, if known.
    pub fn clearance(&self) -> Option<Real> {
        self.clearance_lb
    }

    /// Records that the state moved by α·d, d the direction of the last
    /// [`ClearanceTracker::fraction`] call, α at most what it returned.
    pub fn moved(&mut self, alpha: Real) {
        self.clearance_lb = match (self.clearance_lb, self.pending) {
            (Some(c), Some((near, far))) => Some(
                (c - alpha * near)
                    .min(CLEARANCE_REACH - alpha * far)
                    .max(0.0),
            ),
            _ => None,
        };
    }
}

//! A cheap guard in front of conservative advancement: a lower bound on the sheet's
//! clearance, carried from step to step, that lets most line-search steps through without
//! any geometry.

use super::model::ContactModel;
use super::reach::{clearance_drop_rate, Rates, Spread};
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};

/// Keeps a lower bound on the smallest distance between any two collision polygons of the
/// infinite sheet while a solver moves the state. A step α·Δ lowers every pair's distance by
/// at most α·b (`reach::clearance_drop_rate`, valid for every lattice translate); while
/// b stays below 90 % of the bound, the whole step is safe without any geometry. Otherwise
/// the clearance is recomputed, and if that is still not enough the exact conservative
/// advancement [`ContactModel::max_safe_step`] decides.
#[derive(Debug, Clone)]
pub struct ClearanceTracker {
    clearance_lb: Option<Real>,
    /// Drop rate of the last direction asked about, and whether it was known.
    pending: Option<Real>,
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
        self.pending = None;
        if contact.check(mech, q).is_err() || d.len() != q.len() || d.iter().any(|x| !x.is_finite())
        {
            return 0.0;
        }
        let Some(placed) = contact.place(mech, q) else {
            return 0.0;
        };
        let Some(spread) = Spread::of(&placed, &contact.extents) else {
            return 0.0;
        };
        let rates = Rates::of(contact.layout, &contact.extents, d);
        if rates.point == 0.0 && rates.lattice == 0.0 {
            self.pending = Some(0.0);
            return 1.0;
        }
        let safe = |c: Real| clearance_drop_rate(&spread, &rates, c).filter(|b| 0.9 * c >= *b);
        if let Some(b) = self.clearance_lb.and_then(safe) {
            self.pending = Some(b);
            return 1.0;
        }
        let c = contact.min_clearance_in_free_set(mech, q);
        self.clearance_lb = Some(c);
        if let Some(b) = safe(c) {
            self.pending = Some(b);
            return 1.0;
        }
        self.pending = clearance_drop_rate(&spread, &rates, c);
        contact.max_safe_step(mech, q, d).min(1.0)
    }

    /// The current lower bound on the clearance, if known.
    pub fn clearance(&self) -> Option<Real> {
        self.clearance_lb
    }

    /// Records that the state moved by α·d, d the direction of the last
    /// [`ClearanceTracker::fraction`] call, α at most what it returned.
    pub fn moved(&mut self, alpha: Real) {
        self.clearance_lb = match (self.clearance_lb, self.pending) {
            (Some(c), Some(b)) => Some((c - alpha * b).max(0.0)),
            _ => None,
        };
    }
}

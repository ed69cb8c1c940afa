//! Conservative advancement: how far along a search direction the state can move with every
//! collision polygon staying clear of every other.

use super::clearance::pair_clearance;
use super::model::ContactModel;
use super::placement::Placement;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real, Vec2};

/// Fraction of each pair's current clearance that [`ContactModel::max_safe_step`] keeps.
pub const KEEP_FRACTION: Real = 0.1;
/// Most advancement rounds.
const MAX_ROUNDS: usize = 32;
/// Stop advancing once a round adds less than this fraction of the step so far.
const MIN_PROGRESS: Real = 1e-3;
/// After a round, pairs that allowed less than this multiple of the round's step have their
/// clearance recomputed; the others keep their (still valid) linear lower bound.
const RECOMPUTE_WITHIN: Real = 2.0;

impl ContactModel {
    /// The largest α ∈ [0, 1] found such that on the whole path q + s·dq, s ∈ [0, α], no two
    /// collision polygons intersect and every candidate pair keeps at least
    /// [`KEEP_FRACTION`] of its clearance at q (for pairs whose boxes are far apart, of the
    /// gap between the boxes, a lower bound of the clearance).
    ///
    /// The guarantee rests on a bound, linear in s, of how far any point of a tile in cell
    /// (k_u, k_w) can move: s·(|Δp| + |Δθ|·r + |k_u||Δu| + |k_w||Δw|), r the largest lever
    /// arm of its collision polygon (|R(θ+sΔθ)x − R(θ)x| ≤ s|Δθ||x|). A pair of clearance c
    /// whose two bounds add up to ℓ stays clear for s ≤ (1 − KEEP_FRACTION)·c/ℓ. As in
    /// additive CCD, the state is then advanced to the smallest such s over all pairs, the
    /// clearances of the limiting pairs recomputed, and the process repeated (at most 32
    /// rounds) until the step reaches 1 or stops growing; so α is close to the true limit
    /// where the bound is tight and not needlessly small where it is not.
    ///
    /// Returns 0 when q already has touching or overlapping polygons, or when `mech`, q or
    /// `dq` do not fit the model (wrong length, NaN, a step so large that its motion bound
    /// overflows). Only the candidate pairs are considered, as everywhere in this module.
    pub fn max_safe_step(&self, mech: &Mechanism, q: &DVec, dq: &DVec) -> Real {
        if self.check(mech, q).is_err() || dq.len() != q.len() || dq.iter().any(|x| !x.is_finite())
        {
            return 0.0;
        }
        let rates = self.approach_rates(dq);
        if rates.iter().any(|r| !r.is_finite()) {
            // A step so large that the motion bound overflows.
            return 0.0;
        }
        let placed = Placement::new(self.layout, &self.shapes, q);
        let mut other = Vec::new();
        // Per pair: a clearance and the step s at which it was measured. It bounds the
        // clearance at any later s from below by clearance − (s − s₀)·rate.
        let mut known = Vec::with_capacity(self.pairs.len());
        for pair in &self.pairs {
            let c = pair_clearance(&placed, pair, true, &mut other);
            if c.is_nan() || c <= 0.0 {
                return 0.0;
            }
            known.push((c, 0.0));
        }
        let floor: Vec<Real> = known.iter().map(|(c, _)| KEEP_FRACTION * c).collect();
        let mut allow = vec![Real::INFINITY; self.pairs.len()];
        let mut t = 0.0;
        for _ in 0..MAX_ROUNDS {
            let mut step = Real::INFINITY;
            for (p, a) in allow.iter_mut().enumerate() {
                let (c, s0) = known[p];
                if rates[p] > 0.0 {
                    *a = (c - (t - s0) * rates[p] - floor[p]) / rates[p];
                    step = step.min(*a);
                }
            }
            if step.is_nan() || step <= 0.0 {
                break;
            }
            if t + step >= 1.0 {
                return 1.0;
            }
            t += step;
            let placed = Placement::new(self.layout, &self.shapes, &(q + dq * t));
            for (p, pair) in self.pairs.iter().enumerate() {
                if allow[p] <= RECOMPUTE_WITHIN * step {
                    known[p] = (pair_clearance(&placed, pair, false, &mut other), t);
                }
            }
            if step < MIN_PROGRESS * t {
                break;
            }
        }
        t
    }

    /// For every candidate pair, the bound of how fast its two polygons can approach per unit
    /// step along `dq`.
    fn approach_rates(&self, dq: &DVec) -> Vec<Real> {
        let l = self.layout;
        let tile = |i: usize| {
            let k = l.tile(i);
            Vec2::new(dq[k], dq[k + 1]).norm() + dq[k + 2].abs() * self.extents[i]
        };
        let du = Vec2::new(dq[l.u()], dq[l.u() + 1]).norm();
        let dw = Vec2::new(dq[l.w()], dq[l.w() + 1]).norm();
        self.pairs
            .iter()
            .map(|p| {
                let lattice =
                    Real::from(p.offset[0].abs()) * du + Real::from(p.offset[1].abs()) * dw;
                tile(p.a) + tile(p.b) + lattice
            })
            .collect()
    }
}

//! Conservative advancement: how far along a search direction the state can move with every
//! collision polygon staying clear of every other.

use super::clearance::pair_clearance;
use super::model::ContactModel;
use super::pairs::CandidatePair;
use super::placement::Placement;
use super::reach::{far_limit, skin_for, Rates, Spread};
use super::verlet::PairCache;
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
    /// collision polygons of the infinite sheet intersect and every pair keeps at least
    /// [`KEEP_FRACTION`] of its clearance at q (for pairs whose boxes are far apart, of the
    /// gap between the boxes, a lower bound of the clearance; for pairs beyond the skin, of
    /// the skin).
    ///
    /// Pairs within a skin (a margin chosen from the step, see `reach`) are advanced one by
    /// one. The guarantee rests on a bound, linear in s, of how far any point of a tile in
    /// cell (k_u, k_w) can move: s·(|Δp| + |Δθ|·r + |k_u||Δu| + |k_w||Δw|), r the largest
    /// lever arm of its collision polygon (|R(θ+sΔθ)x − R(θ)x| ≤ s|Δθ||x|). A pair of
    /// clearance c whose two bounds add up to ℓ stays clear for s ≤ (1 − KEEP_FRACTION)·c/ℓ.
    /// As in additive CCD, the state is then advanced to the smallest such s over all pairs,
    /// the clearances of the limiting pairs recomputed, and the process repeated (at most 32
    /// rounds) until the step reaches its limit or stops growing; so α is close to the true
    /// limit where the bound is tight and not needlessly small where it is not. Pairs beyond
    /// the skin, whatever their lattice translate, are covered by `reach::far_limit`, which
    /// caps α.
    ///
    /// Returns 0 when q already has touching or overlapping polygons, or when `mech`, q or
    /// `dq` do not fit the model (wrong length, NaN, a step so large that its motion bound
    /// overflows, a degenerate lattice).
    pub fn max_safe_step(&self, mech: &Mechanism, q: &DVec, dq: &DVec) -> Real {
        self.max_safe_step_from(mech, q, dq, None, true)
    }

    /// [`ContactModel::max_safe_step`] for a q already known to be intersection-free (as
    /// every state of a conservatively advanced solver is), with candidate pairs from
    /// `cache` when there is one when there is one: skips the exact overlap test at q, as
    /// [`ContactModel::min_clearance_in_free_set`] does. On an overlapping q the result is
    /// meaningless.
    pub(crate) fn max_safe_step_in_free_set(
        &self,
        mech: &Mechanism,
        q: &DVec,
        dq: &DVec,
        cache: Option<&mut PairCache>,
    ) -> Real {
        self.max_safe_step_from(mech, q, dq, cache, false)
    }

    fn max_safe_step_from(
        &self,
        mech: &Mechanism,
        q: &DVec,
        dq: &DVec,
        cache: Option<&mut PairCache>,
        check_overlap: bool,
    ) -> Real {
        if self.check(mech, q).is_err() || dq.len() != q.len() || dq.iter().any(|x| !x.is_finite())
        {
            return 0.0;
        }
        let placed = Placement::new(self.layout, &self.shapes, q);
        let Some(spread) = Spread::of(&placed, &self.extents) else {
            return 0.0;
        };
        let step_rates = Rates::of(self.layout, &self.extents, dq);
        if ![step_rates.centre, step_rates.point, step_rates.lattice]
            .iter()
            .all(|r| r.is_finite())
        {
            return 0.0;
        }
        let skin = skin_for(&spread, &step_rates);
        let limit = far_limit(&spread, &step_rates, skin).min(1.0);
        let mut pairs = Vec::with_capacity(64);
        if self
            .for_each_pair(cache, &placed, skin, |p| pairs.push(p))
            .is_err()
        {
            return 0.0;
        }
        let rates = self.approach_rates(&pairs, dq);
        if rates.iter().any(|r| !r.is_finite()) {
            // A step so large that the motion bound overflows.
            return 0.0;
        }
        let mut other = Vec::new();
        // Per pair: a clearance and the step s at which it was measured. It bounds the
        // clearance at any later s from below by clearance − (s − s₀)·rate.
        let mut known = Vec::with_capacity(pairs.len());
        for pair in &pairs {
            let c = pair_clearance(&placed, pair, check_overlap, &mut other);
            if c.is_nan() || c <= 0.0 {
                return 0.0;
            }
            known.push((c, 0.0));
        }
        let floor: Vec<Real> = known.iter().map(|(c, _)| KEEP_FRACTION * c).collect();
        let mut allow = vec![Real::INFINITY; pairs.len()];
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
            if t + step >= limit {
                return limit;
            }
            t += step;
            let placed = Placement::new(self.layout, &self.shapes, &(q + dq * t));
            for (p, pair) in pairs.iter().enumerate() {
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

    /// For every pair, the bound of how fast its two polygons can approach per unit step
    /// along `dq`.
    fn approach_rates(&self, pairs: &[CandidatePair], dq: &DVec) -> Vec<Real> {
        let rate = self.approach_rate(dq);
        pairs.iter().map(rate).collect()
    }

    /// The bound of how fast a pair's two polygons can approach per unit step along `dq`:
    /// |Δp| + |Δθ|·r of each tile plus |k_u||Δu| + |k_w||Δw|.
    pub(crate) fn approach_rate(&self, dq: &DVec) -> impl Fn(&CandidatePair) -> Real + '_ {
        let l = self.layout;
        let du = Vec2::new(dq[l.u()], dq[l.u() + 1]).norm();
        let dw = Vec2::new(dq[l.w()], dq[l.w() + 1]).norm();
        let tiles: Vec<Real> = (0..l.tiles)
            .map(|i| {
                let k = l.tile(i);
                Vec2::new(dq[k], dq[k + 1]).norm() + dq[k + 2].abs() * self.extents[i]
            })
            .collect();
        move |p: &CandidatePair| {
            let lattice = Real::from(p.offset[0].abs()) * du + Real::from(p.offset[1].abs()) * dw;
            tiles[p.a] + tiles[p.b] + lattice
        }
    }
}

//! Nelder–Mead rounds (argmin) over a [`Tracker`]: each round starts a fresh simplex at the
//! best point so far; a round ends when its simplex has converged, its best value has not
//! improved for 4 (n + 1) evaluations, or the budget is spent; a round that improved nothing
//! halves the step of the next; the rounds end when the step falls below 1/100 of the first.

use super::track::{Tracker, INFEASIBLE};
use crate::math::Real;
use argmin::core::{CostFunction, Error as ArgminError, Executor};
use argmin::solver::neldermead::NelderMead;
use std::cell::Cell;

/// First simplex step along a shape parameter, in units of its scale.
pub const PARAM_STEP: Real = 0.1;
/// First simplex step along the kerf axis (log₂ of the kerf).
const KERF_STEP: Real = 0.5;
/// The rounds end when the step has shrunk by this factor.
const MIN_STEP_FRACTION: Real = 1e-2;
/// A round ends after this many evaluations per unknown (plus one) without improving.
const STALL_PER_UNKNOWN: usize = 4;

struct Round<'t, 'a, 'b> {
    tracker: &'t Tracker<'a, 'b>,
    /// Calls of this round (argmin's initial simplex takes the first n + 1).
    calls: Cell<usize>,
}

impl CostFunction for Round<'_, '_, '_> {
    type Param = Vec<Real>;
    type Output = Real;

    fn cost(&self, x: &Vec<Real>) -> Result<Real, ArgminError> {
        self.calls.set(self.calls.get() + 1);
        let n = self.tracker.space.dims();
        // Ending the round is allowed only after argmin's initial simplex (its `init` unwraps
        // every cost); before that an unavailable point just costs INFEASIBLE.
        let may_end = self.calls.get() > n + 1;
        let stalled = self.tracker.since_improvement() >= STALL_PER_UNKNOWN * (n + 1);
        if stalled && may_end {
            return Err(ArgminError::msg("round stalled"));
        }
        match self.tracker.eval(x) {
            Some(p) => Ok(p.cost),
            None if may_end => Err(ArgminError::msg("budget spent")),
            None => Ok(INFEASIBLE),
        }
    }
}

/// A simplex at `centre` stepping `step` along each parameter axis and `kerf_step` along the
/// kerf's.
fn simplex(tracker: &Tracker<'_, '_>, centre: &[Real], step: Real) -> Vec<Vec<Real>> {
    let mut out = vec![centre.to_vec()];
    for i in 0..centre.len() {
        let mut v = centre.to_vec();
        v[i] += if tracker.space.is_kerf(i) {
            KERF_STEP * step / PARAM_STEP
        } else {
            step
        };
        out.push(v);
    }
    out
}

/// Runs Nelder–Mead rounds until the budget is spent or the step has shrunk away.
pub(super) fn rounds(tracker: &Tracker<'_, '_>) {
    let mut step = PARAM_STEP;
    while tracker.space.dims() > 0 && step >= PARAM_STEP * MIN_STEP_FRACTION && !tracker.spent() {
        let before = tracker.best_x();
        let evaluations = tracker.evaluations();
        let round = Round {
            tracker,
            calls: Cell::new(0),
        };
        let solver = NelderMead::new(simplex(tracker, &before, step))
            .with_sd_tolerance(1e-10)
            .expect("a positive tolerance is accepted");
        // A round ends by an error from the cost function (budget, stall), the simplex's
        // spread or the iteration cap; the tracker keeps the best point either way.
        let cap = 4 * (tracker.space.dims() + 1) * 100;
        drop(
            Executor::new(round, solver)
                .configure(|s| s.max_iters(cap as u64))
                .run(),
        );
        let improved = tracker.best_x() != before;
        if !improved || tracker.evaluations() == evaluations {
            step *= 0.5;
        }
    }
}

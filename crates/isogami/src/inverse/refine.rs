//! Stage 2, refinement: optimise a screened design's continuous shape parameters (and, when
//! asked, its kerf) with the topology fixed.
//!
//! The method is Nelder–Mead from `argmin`: derivative-free, deterministic, a handful of
//! unknowns (at most six shape parameters and the kerf). Derivative-free because the
//! objective is only piecewise smooth: where the contact limit switches from one pair of
//! tiles to another, or a frame selection changes, the end state jumps.
//!
//! Coordinates are scaled so that one unit is a parameter's scale max(|Kaplan default|, 0.25)
//! (the exploration's grid uses the same scale) and, for the kerf, a factor 2
//! (kerf = kerf₀ · 2ˣ). The first simplex steps 0.1 of a scale along each parameter (0.5 along
//! the kerf axis). An infeasible point — invalid tiles, a cell that does not build, mobility
//! other than 1, locked at the start, below the threshold, a constraint or goal unmet — costs
//! [`INFEASIBLE`], far above any objective, so the simplex moves away from it; the best
//! *valid* evaluation seen is what refinement returns (the start itself when nothing better
//! is found), so every returned design is valid by construction. Each call evaluates at most
//! `budget` points (the start is not evaluated again).

use super::evaluate::{Evaluation, Evaluator, Outcome, Stopped};
use super::monitor::Monitor;
use crate::math::Real;
use crate::topology::Design;
use argmin::core::{CostFunction, Error as ArgminError, Executor};
use argmin::solver::neldermead::NelderMead;
use std::cell::RefCell;

/// The cost of an infeasible point.
pub const INFEASIBLE: Real = 1e9;
/// First simplex step along a shape parameter, in units of its scale.
const PARAM_STEP: Real = 0.1;
/// First simplex step along the kerf axis (log₂ of the kerf).
const KERF_STEP: Real = 0.5;

/// The result of refining one design.
#[derive(Debug, Clone)]
pub(crate) struct Refined {
    /// The best valid evaluation (the start when nothing better was found).
    pub best: Evaluation,
    /// Points evaluated.
    pub evaluations: usize,
    /// Of those, invalid.
    pub invalid: usize,
}

/// Maps scaled coordinates to a design and kerf.
struct Space {
    start: Design,
    scale: Vec<Real>,
    kerf: Real,
    refine_kerf: bool,
}

impl Space {
    fn dims(&self) -> usize {
        self.scale.len() + usize::from(self.refine_kerf)
    }

    fn point(&self, x: &[Real]) -> (Design, Real) {
        let params = self
            .start
            .params
            .iter()
            .zip(&self.scale)
            .zip(x)
            .map(|((p, s), xi)| p + s * xi)
            .collect();
        let kerf = if self.refine_kerf {
            self.kerf * x[self.scale.len()].exp2()
        } else {
            self.kerf
        };
        (
            Design {
                params,
                ..self.start.clone()
            },
            kerf,
        )
    }
}

/// Mutable bookkeeping of the cost function (argmin's `cost` takes `&self`).
struct Track {
    best: Evaluation,
    calls: usize,
    evaluations: usize,
    invalid: usize,
    stopped: bool,
}

struct Problem<'a, 'b> {
    space: &'a Space,
    ev: &'a Evaluator<'b>,
    monitor: &'a Monitor<'a>,
    budget: usize,
    start_objective: Real,
    track: &'a RefCell<Track>,
}

impl CostFunction for Problem<'_, '_> {
    type Param = Vec<Real>;
    type Output = Real;

    fn cost(&self, x: &Vec<Real>) -> Result<Real, ArgminError> {
        let mut t = self.track.borrow_mut();
        if x.iter().all(|&v| v == 0.0) {
            // The start, already evaluated (and valid).
            return Ok(self.start_objective);
        }
        t.calls += 1;
        if t.stopped || t.evaluations >= self.budget {
            // Ending the run is allowed only after argmin's initial simplex (its `init`
            // unwraps every cost).
            return if t.calls > self.space.dims() + 1 {
                Err(ArgminError::msg("evaluation budget spent"))
            } else {
                Ok(INFEASIBLE)
            };
        }
        if x.iter().any(|v| !v.is_finite()) {
            return Ok(INFEASIBLE);
        }
        let (design, kerf) = self.space.point(x);
        t.evaluations += 1;
        let e = match self.ev.evaluate(&design, kerf, self.monitor.stop_flag()) {
            Ok(e) => e,
            Err(Stopped) => {
                t.stopped = true;
                return Ok(INFEASIBLE);
            }
        };
        self.monitor.evaluated(e.objective());
        match e.objective() {
            Some(v) => {
                if v < t.best.objective().unwrap_or(Real::INFINITY) {
                    t.best = e;
                }
                Ok(v)
            }
            None => {
                t.invalid += 1;
                Ok(INFEASIBLE)
            }
        }
    }
}

/// Refines the valid evaluation `start` with at most `budget` evaluations.
pub(crate) fn refine(
    start: &Evaluation,
    budget: usize,
    refine_kerf: bool,
    ev: &Evaluator<'_>,
    monitor: &Monitor<'_>,
) -> Result<Refined, Stopped> {
    let defaults = start.design.family.default_params();
    let space = Space {
        start: start.design.clone(),
        scale: defaults.iter().map(|d| d.abs().max(0.25)).collect(),
        kerf: start.kerf,
        refine_kerf,
    };
    let n = space.dims();
    let untouched = Refined {
        best: start.clone(),
        evaluations: 0,
        invalid: 0,
    };
    if n == 0 || budget == 0 || !matches!(start.outcome, Outcome::Valid { .. }) {
        return Ok(untouched);
    }
    let mut simplex = vec![vec![0.0; n]];
    for i in 0..n {
        let mut v = vec![0.0; n];
        v[i] = if refine_kerf && i == n - 1 {
            KERF_STEP
        } else {
            PARAM_STEP
        };
        simplex.push(v);
    }
    let track = RefCell::new(Track {
        best: start.clone(),
        calls: 0,
        evaluations: 0,
        invalid: 0,
        stopped: false,
    });
    let problem = Problem {
        space: &space,
        ev,
        monitor,
        budget,
        start_objective: start.objective().unwrap_or(INFEASIBLE),
        track: &track,
    };
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(1e-10)
        .expect("a positive tolerance is accepted");
    // The run ends by the budget (an error from the cost function), the simplex's spread or
    // the iteration cap.
    let outcome = Executor::new(problem, solver)
        .configure(|s| s.max_iters((4 * budget) as u64))
        .run();
    // An error is the spent budget (or argmin's own): the best point tracked so far is valid
    // either way.
    drop(outcome);
    let t = track.into_inner();
    if t.stopped || monitor.stopped() {
        return Err(Stopped);
    }
    Ok(Refined {
        best: t.best,
        evaluations: t.evaluations,
        invalid: t.invalid,
    })
}

//! Stage 2, refinement: optimise a screened design's continuous shape parameters (and, when
//! asked, its kerf) with the topology fixed.
//!
//! The general method is Nelder–Mead from `argmin` ([`simplex`]): derivative-free,
//! deterministic, a handful of unknowns (at most six shape parameters and the kerf), and
//! indifferent to the creases of the objective (where the contact pair that ends the
//! deployment changes, the end state turns a corner). When every goal of the target is a
//! match (lock, lock-f, path, area(r), expansion(θ, e)), the objective is a norm of
//! residuals that vanishes at the answer, and Levenberg–Marquardt on those residuals ([`lm`], forward-difference Jacobians)
//! converges in a few Jacobians where Nelder–Mead needs hundreds of points: it runs first,
//! and Nelder–Mead continues from its result with whatever budget is left.
//!
//! Coordinates are scaled ([`track::Space`]): one unit is a parameter's scale
//! max(|Kaplan default|, 0.25) (the exploration's grid uses the same scale), and a factor 2
//! of the kerf. An infeasible point — invalid tiles, a cell that does not build, mobility
//! other than 1, locked at the start, below the threshold, a constraint or goal unmet —
//! costs [`INFEASIBLE`], far above any objective, so both methods move away from it; the
//! best *valid* evaluation seen is what refinement returns (the start itself when nothing
//! better is found), so every returned design is valid by construction. At most `budget`
//! points are evaluated; no point is evaluated twice.

mod lm;
mod simplex;
mod track;

pub use track::INFEASIBLE;

use super::evaluate::{Evaluation, Evaluator, Stopped};
use super::monitor::Monitor;
use track::{Space, Tracker};

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

/// Refines the valid evaluation `start` (a design of `topology`) with at most `budget`
/// evaluations.
pub(crate) fn refine(
    start: &Evaluation,
    topology: &str,
    budget: usize,
    refine_kerf: bool,
    ev: &Evaluator<'_>,
    monitor: &Monitor<'_>,
) -> Result<Refined, Stopped> {
    let space = Space::new(start, refine_kerf);
    if start.objective().is_none() || space.dims() == 0 || budget == 0 {
        return Ok(Refined {
            best: start.clone(),
            evaluations: 0,
            invalid: 0,
        });
    }
    let tracker = Tracker::new(start, topology, space, ev, monitor, budget);
    lm::polish(&tracker);
    simplex::rounds(&tracker);
    let (best, evaluations, invalid) = tracker.finish()?;
    Ok(Refined {
        best,
        evaluations,
        invalid,
    })
}

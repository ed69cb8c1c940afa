//! The refinement's view of the design space: scaled coordinates → (design, kerf), and every
//! evaluation made through one tracker that counts them against the budget, remembers each
//! point's cost, keeps the best valid design, and notices a stop.

use crate::inverse::evaluate::{Evaluation, Evaluator, Stopped};
use crate::inverse::monitor::Monitor;
use crate::math::Real;
use crate::topology::Design;
use std::cell::RefCell;
use std::collections::HashMap;

/// The cost of an infeasible point.
pub const INFEASIBLE: Real = 1e9;

/// Maps scaled coordinates to a design and kerf: xᵢ in units of parameter i's scale
/// max(|Kaplan default|, 0.25) from the start's value; the last coordinate, when the kerf is
/// refined, is log₂(kerf / start kerf).
pub(super) struct Space {
    pub start: Design,
    pub scale: Vec<Real>,
    pub kerf: Real,
    pub refine_kerf: bool,
}

impl Space {
    pub fn new(start: &Evaluation, refine_kerf: bool) -> Space {
        Space {
            start: start.design.clone(),
            scale: start
                .design
                .family
                .default_params()
                .iter()
                .map(|d| d.abs().max(0.25))
                .collect(),
            kerf: start.kerf,
            refine_kerf,
        }
    }

    /// Number of unknowns.
    pub fn dims(&self) -> usize {
        self.scale.len() + usize::from(self.refine_kerf)
    }

    /// True when coordinate `i` is the kerf's.
    pub fn is_kerf(&self, i: usize) -> bool {
        self.refine_kerf && i == self.scale.len()
    }

    fn point(&self, x: &[Real]) -> (Design, Real) {
        let params: Vec<Real> = self
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
        // Every point the refinement evaluates is a canonical design: the spec it reports is
        // the shape it deployed.
        (self.start.at_params(&params), kerf)
    }
}

/// What one point cost.
#[derive(Debug, Clone)]
pub(super) struct Point {
    /// The objective, or [`INFEASIBLE`].
    pub cost: Real,
    /// The stacked residuals of a valid point of a matching target.
    pub residual: Option<Vec<Real>>,
}

struct State {
    best: Evaluation,
    best_x: Vec<Real>,
    best_value: Real,
    memo: HashMap<Vec<u64>, Point>,
    evaluations: usize,
    invalid: usize,
    /// `evaluations` when the best value last improved.
    improved_at: usize,
    stopped: bool,
}

/// Every evaluation of one refinement.
pub(super) struct Tracker<'a, 'b> {
    pub space: Space,
    ev: &'a Evaluator<'b>,
    monitor: &'a Monitor<'a>,
    /// The topology of every design evaluated (for the monitor's leader board).
    topology: &'a str,
    budget: usize,
    state: RefCell<State>,
}

fn key(x: &[Real]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

fn point_of(e: &Evaluation) -> Point {
    match &e.outcome {
        crate::inverse::Outcome::Valid { score, .. } => Point {
            cost: score.objective,
            residual: score.residual.clone(),
        },
        crate::inverse::Outcome::Invalid(_) => Point {
            cost: INFEASIBLE,
            residual: None,
        },
    }
}

impl<'a, 'b> Tracker<'a, 'b> {
    /// A tracker starting at the valid evaluation `start` (coordinates 0, not evaluated
    /// again).
    pub fn new(
        start: &Evaluation,
        topology: &'a str,
        space: Space,
        ev: &'a Evaluator<'b>,
        monitor: &'a Monitor<'a>,
        budget: usize,
    ) -> Self {
        let origin = vec![0.0; space.dims()];
        let p = point_of(start);
        Tracker {
            space,
            ev,
            monitor,
            topology,
            budget,
            state: RefCell::new(State {
                best: start.clone(),
                best_value: p.cost,
                memo: HashMap::from([(key(&origin), p)]),
                best_x: origin,
                evaluations: 0,
                invalid: 0,
                improved_at: 0,
                stopped: false,
            }),
        }
    }

    /// The cost of `x`: remembered, or evaluated when budget remains. `None` when the budget
    /// is spent or the caller stopped the run.
    pub fn eval(&self, x: &[Real]) -> Option<Point> {
        if let Some(p) = self.state.borrow().memo.get(&key(x)) {
            return Some(p.clone());
        }
        if self.spent() {
            return None;
        }
        if x.iter().any(|v| !v.is_finite()) {
            return Some(Point {
                cost: INFEASIBLE,
                residual: None,
            });
        }
        let (design, kerf) = self.space.point(x);
        self.state.borrow_mut().evaluations += 1;
        let e = match self.ev.evaluate(&design, kerf, self.monitor.stop_flag()) {
            Ok(e) => e,
            Err(Stopped) => {
                self.state.borrow_mut().stopped = true;
                return None;
            }
        };
        self.monitor.evaluated(&e, self.topology);
        let p = point_of(&e);
        let mut s = self.state.borrow_mut();
        if p.cost >= INFEASIBLE {
            s.invalid += 1;
        } else if p.cost < s.best_value {
            s.best_value = p.cost;
            s.best_x = x.to_vec();
            s.best = e;
            s.improved_at = s.evaluations;
        }
        s.memo.insert(key(x), p.clone());
        Some(p)
    }

    /// True when no evaluation is left (budget spent or stopped).
    pub fn spent(&self) -> bool {
        let s = self.state.borrow();
        s.stopped || s.evaluations >= self.budget || self.monitor.stopped()
    }

    /// Coordinates of the best point.
    pub fn best_x(&self) -> Vec<Real> {
        self.state.borrow().best_x.clone()
    }

    /// Evaluations so far.
    pub fn evaluations(&self) -> usize {
        self.state.borrow().evaluations
    }

    /// Evaluations since the best value last improved.
    pub fn since_improvement(&self) -> usize {
        let s = self.state.borrow();
        s.evaluations - s.improved_at
    }

    /// The best evaluation, the evaluation and invalid counts; an error when stopped.
    pub fn finish(self) -> Result<(Evaluation, usize, usize), Stopped> {
        let stopped = self.monitor.stopped();
        let s = self.state.into_inner();
        if s.stopped || stopped {
            return Err(Stopped);
        }
        Ok((s.best, s.evaluations, s.invalid))
    }
}

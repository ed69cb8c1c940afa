//! The result of a deployment: raw accepted steps and why it ended.

use crate::math::{DVec, Real};
use serde::Serialize;

/// One accepted state of the deployment.
#[derive(Debug, Clone)]
pub struct RawStep {
    /// The state (non-dimensional).
    pub q: DVec,
    /// Arc length of the state path from the closed state to here.
    pub arc: Real,
    /// Target step length β that produced it (0 for the closed state).
    pub beta: Real,
    /// Newton iterations of the step.
    pub iterations: usize,
    /// Largest joint residual (units of L).
    pub joint_residual: Real,
    /// Smallest distance between collision polygons (units of L).
    pub min_clearance: Real,
    /// Unit motion vector used for the step (zero for the closed state).
    pub direction: DVec,
    /// Nullity of H seen when choosing the direction (2 or more at turning points).
    pub nullity: usize,
}

/// Why a deployment stopped.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum EndReason {
    /// Contact blocks further motion: the physical limit of deployment.
    ContactLimit,
    /// Contact blocks both directions of the first step: the design does not open.
    Locked,
    /// β was halved the allowed number of times without an acceptable step, and contact was
    /// not the reason (e.g. a turning point the method cannot pass).
    StepSizeExhausted,
    /// The baseline stopped moving (springs: further load steps give no motion).
    Stalled,
    /// The step limit (accepted states or attempted steps) was reached before any other end.
    MaxSteps,
    /// The state ran away: the tiling vectors grew without limit (the sheet comes apart) or
    /// the solver produced a non-finite state. The trajectory stops at the last good state;
    /// `diagnostics` says what happened.
    Diverged {
        /// What ran away.
        diagnostics: String,
    },
    /// The solver failed; `diagnostics` says where and why.
    SolverFailure {
        /// What went wrong.
        diagnostics: String,
    },
}

impl std::fmt::Display for EndReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EndReason::ContactLimit => f.write_str("contact limit"),
            EndReason::Locked => f.write_str("locked by contact"),
            EndReason::StepSizeExhausted => f.write_str("step size exhausted"),
            EndReason::Stalled => f.write_str("stalled"),
            EndReason::MaxSteps => f.write_str("step limit reached"),
            EndReason::Diverged { diagnostics } => write!(f, "diverged: {diagnostics}"),
            EndReason::SolverFailure { diagnostics } => write!(f, "solver failure: {diagnostics}"),
        }
    }
}

/// A whole deployment.
#[derive(Debug, Clone)]
pub struct Trajectory {
    /// Accepted states, the closed state first.
    pub steps: Vec<RawStep>,
    /// Why it ended.
    pub end_reason: EndReason,
    /// The opening direction chosen at t = 0 (unit, non-dimensional).
    pub initial_direction: DVec,
    /// Attempted steps, accepted or not (a cost measure).
    pub attempts: usize,
    /// Degrees of freedom of the closed state (several: the path follows the fastest-opening
    /// first-order motion, see [`crate::mobility::Mobility::motion`]).
    pub dof: usize,
}

impl Trajectory {
    /// Total arc length.
    pub fn total_arc(&self) -> Real {
        self.steps.last().map_or(0.0, |s| s.arc)
    }

    /// Normalised arc length t ∈ [0, 1] of step k (0 for a trajectory that never moved).
    pub fn t(&self, k: usize) -> Real {
        let total = self.total_arc();
        if total > 0.0 {
            self.steps[k].arc / total
        } else {
            0.0
        }
    }

    /// Largest joint residual over all steps.
    pub fn max_joint_residual(&self) -> Real {
        self.steps
            .iter()
            .map(|s| s.joint_residual)
            .fold(0.0, Real::max)
    }

    /// Smallest clearance over all steps.
    pub fn min_clearance(&self) -> Real {
        self.steps
            .iter()
            .map(|s| s.min_clearance)
            .fold(Real::INFINITY, Real::min)
    }
}

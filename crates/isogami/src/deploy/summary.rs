//! Summary measures of a whole trajectory, over every accepted state.
//!
//! A summary must describe the design's motion, not the sampling a user asked for: folded over
//! output frames, IH88's largest area ratio was 3.99835 with 40 frames, 3.99910 with 60 and
//! 3.99996 over all steps. So every summary measure is folded over all accepted states of the
//! trajectory, and a deployment reports bit-identical summaries whatever frames it returns.
//! Inserted frames (between accepted states) never enter a summary.

use super::error::DeployError;
use super::trajectory::Trajectory;
use crate::kinematics::Mechanism;
use crate::math::Real;
use crate::measure::{
    classify_expansions, effective_poisson_ratio, BehaviourClass, BehaviourFigures,
    ClassifyTolerances, FrameMeasures, OPEN_FRACTION,
};

/// Measures count as open for the Poisson-like ratio when their largest principal expansion
/// reaches this fraction of the largest one of the whole deployment: below it both
/// expansions are so small that their ratio is dominated by solver noise. The behaviour class
/// is decided on the same states (it is [`OPEN_FRACTION`]).
pub const POISSON_OPEN_FRACTION: Real = OPEN_FRACTION;

/// The summary measures of a trajectory, each over all its accepted states.
#[derive(Debug, Clone, PartialEq)]
pub struct StepSummary {
    /// Largest principal expansion.
    pub max_expansion: Real,
    /// Smallest principal expansion.
    pub min_expansion: Real,
    /// Largest area ratio det F.
    pub max_area_ratio: Real,
    /// Largest tile rotation (radians).
    pub max_tile_rotation: Real,
    /// Largest joint residual (units of L), as the solver measured it on each state.
    pub max_joint_residual: Real,
    /// Smallest clearance (units of L), as the solver measured it on each state.
    pub min_clearance: Real,
    /// Behaviour class ([`classify_expansions`] over all states, default tolerances): decided
    /// on the open states of the Poisson-like range.
    pub behaviour: Option<BehaviourClass>,
    /// The figures the class was decided on (None when there is no class).
    pub behaviour_figures: Option<BehaviourFigures>,
    /// True when the design lies at a class boundary (its margin is at most
    /// [`ClassifyTolerances::boundary`]).
    pub behaviour_boundary: bool,
    /// Smallest and largest Poisson-like ratio over the open states (see [`poisson_range`]).
    pub poisson_range: Option<(Real, Real)>,
}

/// The measures of every accepted state of `traj` (the closed state first), each from
/// [`FrameMeasures::from_states`] as the frames get them.
pub fn step_measures(
    mech: &Mechanism,
    traj: &Trajectory,
) -> Result<Vec<FrameMeasures>, DeployError> {
    (0..traj.steps.len())
        .map(|k| {
            Ok(FrameMeasures::from_states(
                mech,
                &mech.rest,
                &traj.steps[k].q,
                traj.t(k),
            )?)
        })
        .collect()
}

/// Summarises `traj` over all its accepted states; fails only when a state cannot be measured
/// (an inverted or non-finite lattice).
pub fn summarize_steps(mech: &Mechanism, traj: &Trajectory) -> Result<StepSummary, DeployError> {
    let measures = step_measures(mech, traj)?;
    let fold = |init: Real, pick: fn(&FrameMeasures) -> Real, f: fn(Real, Real) -> Real| {
        measures.iter().map(pick).fold(init, f)
    };
    let max_expansion = fold(Real::NEG_INFINITY, |m| m.max_expansion, Real::max);
    let expansions = || measures.iter().map(|m| (m.min_expansion, m.max_expansion));
    let class = classify_expansions(expansions(), ClassifyTolerances::default());
    Ok(StepSummary {
        max_expansion,
        min_expansion: fold(Real::INFINITY, |m| m.min_expansion, Real::min),
        max_area_ratio: fold(Real::NEG_INFINITY, |m| m.area_ratio, Real::max),
        max_tile_rotation: fold(0.0, |m| m.max_tile_rotation, Real::max),
        max_joint_residual: traj.max_joint_residual(),
        min_clearance: traj.min_clearance(),
        behaviour: class.map(|c| c.class),
        behaviour_figures: class.map(|c| c.figures),
        behaviour_boundary: class.is_some_and(|c| c.boundary),
        poisson_range: poisson_range(expansions(), max_expansion),
    })
}

/// Smallest and largest Poisson-like ratio −ε_min/ε_max over the states given as
/// (ε_min, ε_max) that have opened: ε_max at least [`POISSON_OPEN_FRACTION`] of
/// `max_expansion`, the largest expansion of the whole deployment. None when no state has
/// opened or the deployment never expands.
pub fn poisson_range(
    expansions: impl Iterator<Item = (Real, Real)>,
    max_expansion: Real,
) -> Option<(Real, Real)> {
    if max_expansion.is_nan() || max_expansion <= 0.0 {
        return None;
    }
    let open = POISSON_OPEN_FRACTION * max_expansion;
    expansions
        .filter(|&(_, hi)| hi >= open)
        .filter_map(|(lo, hi)| effective_poisson_ratio(lo, hi))
        .fold(None, |acc, r| match acc {
            None => Some((r, r)),
            Some((lo, hi)) => Some((Real::min(lo, r), Real::max(hi, r))),
        })
}

//! Frames for output: accepted states picked evenly in t, each with its measures and its
//! invariants (joint residual, clearance) recomputed independently of the solver.

use super::error::{DeployError, FrameProblem};
use super::trajectory::Trajectory;
use crate::contact::ContactModel;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};
use crate::measure::FrameMeasures;

/// One output frame.
#[derive(Debug, Clone)]
pub struct FrameRecord {
    /// Index of the raw step.
    pub step: usize,
    /// Normalised arc length.
    pub t: Real,
    /// The state (non-dimensional).
    pub q: DVec,
    /// Expansion measures at this state.
    pub measures: FrameMeasures,
    /// Largest joint residual, recomputed (units of L).
    pub joint_residual: Real,
    /// Smallest clearance between collision polygons, recomputed (units of L).
    pub min_clearance: Real,
}

/// Indices of about `count` raw steps nearest to evenly spaced t (first and last always).
/// Accepted states are used as they are, never interpolated, so every frame is an exact
/// solution of the joint constraints.
pub fn select_frames(traj: &Trajectory, count: usize) -> Vec<usize> {
    let n = traj.steps.len();
    if n == 0 {
        return Vec::new();
    }
    let count = count.max(2);
    let mut out: Vec<usize> = Vec::with_capacity(count);
    let mut k = 0;
    for j in 0..count {
        let target = j as Real / (count - 1) as Real;
        while k + 1 < n && (traj.t(k + 1) - target).abs() <= (traj.t(k) - target).abs() {
            k += 1;
        }
        if out.last() != Some(&k) {
            out.push(k);
        }
    }
    if out.last() != Some(&(n - 1)) {
        out.push(n - 1);
    }
    out
}

/// Frame records for the chosen steps; fails if a frame breaks an invariant (a joint open
/// by more than `joint_tolerance`, overlapping tiles, a non-finite value).
pub fn frame_records(
    mech: &Mechanism,
    contact: &ContactModel,
    traj: &Trajectory,
    indices: &[usize],
    joint_tolerance: Real,
) -> Result<Vec<FrameRecord>, DeployError> {
    indices
        .iter()
        .map(|&k| {
            let q = &traj.steps[k].q;
            let fail = |problem| DeployError::Frame { step: k, problem };
            if q.iter().any(|x| !x.is_finite()) {
                return Err(fail(FrameProblem::NonFinite));
            }
            let joint_residual = mech.residual(q).amax();
            if joint_residual > joint_tolerance {
                return Err(fail(FrameProblem::JointResidual {
                    residual: joint_residual,
                    tolerance: joint_tolerance,
                }));
            }
            if let Some(overlap) = contact.overlapping_pair(mech, q) {
                return Err(fail(FrameProblem::Overlap(overlap)));
            }
            let t = traj.t(k);
            Ok(FrameRecord {
                step: k,
                t,
                q: q.clone(),
                measures: FrameMeasures::from_states(mech, &mech.rest, q, t)?,
                joint_residual,
                min_clearance: contact.min_clearance(mech, q),
            })
        })
        .collect()
}

//! Choosing the opening sign at t = 0 and running a whole deployment.
//!
//! Both ±v are first-order feasible in the closed state. The kerf lets either sign move a
//! little until the two sides of a jointed edge meet (a rotation of about kerf / edge
//! length), so a sign counts as opening only when it gets a probe distance of a few kerfs
//! away from the closed state. The sign that increases the cell area is tried first. When
//! neither sign gets that far because contact stops it, the design is locked.

use super::error::DeployError;
use super::march::{march, rest_step, MarchEnd, StepPolicy};
use super::settings::DeploySettings;
use super::trajectory::{EndReason, Trajectory};
use super::Progress;
use crate::contact::{ContactModel, PairCache};
use crate::kinematics::Mechanism;
use crate::math::DVec;

/// Arc length (in kerfs) a sign must travel to count as opening.
pub const PROBE_KERFS: f64 = 4.0;

/// Chooses the opening sign and deploys to the end (or until the arc length reaches
/// `arc_limit`, when given).
#[allow(clippy::too_many_arguments)]
pub(super) fn open_and_march(
    mech: &Mechanism,
    contact: &ContactModel,
    settings: &DeploySettings,
    v0: &DVec,
    dof: usize,
    policy: &dyn StepPolicy,
    arc_limit: Option<f64>,
    progress: Progress<'_>,
) -> Result<Trajectory, DeployError> {
    let v0 = v0.clone();
    let probe = PROBE_KERFS * settings.contact.kerf;
    let mut attempts = 0;
    let mut failures = Vec::new();
    // The broad phase's pair lists, kept for the whole deployment.
    let mut cache = PairCache::new();
    for sign in [1.0, -1.0] {
        let dir = &v0 * sign;
        let mut steps = vec![rest_step(mech, contact)];
        let go = |steps: &mut Vec<_>,
                  prev: &DVec,
                  limit,
                  attempts: &mut usize,
                  progress: Progress<'_>,
                  cache: &mut PairCache| {
            march(
                mech, contact, settings, policy, steps, &dir, prev, limit, attempts, progress,
                cache,
            )
        };
        match go(
            &mut steps,
            &dir,
            Some(probe),
            &mut attempts,
            progress,
            &mut cache,
        )? {
            MarchEnd::Reached => {
                let prev = steps.last().expect("has steps").direction.clone();
                let end = match go(
                    &mut steps,
                    &prev,
                    arc_limit,
                    &mut attempts,
                    progress,
                    &mut cache,
                )? {
                    MarchEnd::Ended(e) => e,
                    MarchEnd::Reached => EndReason::MaxSteps,
                };
                return Ok(Trajectory {
                    steps,
                    end_reason: end,
                    initial_direction: dir,
                    attempts,
                    dof,
                });
            }
            MarchEnd::Ended(e) => failures.push((e, steps, dir)),
        }
    }
    // Neither sign opened. Contact on both sides: locked. Otherwise report the first
    // failure that was not contact, with the steps it made.
    if failures.iter().all(|(e, ..)| *e == EndReason::ContactLimit) {
        return Ok(Trajectory {
            steps: vec![rest_step(mech, contact)],
            end_reason: EndReason::Locked,
            initial_direction: v0,
            attempts,
            dof,
        });
    }
    let (end_reason, steps, initial_direction) = failures
        .into_iter()
        .find(|(e, ..)| *e != EndReason::ContactLimit)
        .expect("some failure is not contact");
    Ok(Trajectory {
        steps,
        end_reason,
        initial_direction,
        attempts,
        dof,
    })
}

//! Nonlinear rigid modes (paper §3.2): the eigenvector is recomputed at every step.

use super::direction::motion_direction;
use super::error::DeployError;
use super::march::{StepInput, StepPolicy, StepTry};
use super::newton::{minimize_cached, Objective};
use super::settings::DeploySettings;
use crate::contact::ClearanceTracker;
use crate::contact::{ContactModel, PairCache};
use crate::kinematics::Mechanism;

/// The rigid-modes step: direction from the current null space, progress measured from the
/// current state.
pub(super) struct RigidModes;

impl StepPolicy for RigidModes {
    fn solve(
        &self,
        mech: &Mechanism,
        contact: &ContactModel,
        settings: &DeploySettings,
        input: &StepInput,
        cache: &mut PairCache,
    ) -> Result<StepTry, DeployError> {
        let StepInput {
            q,
            clearance,
            previous,
            beta,
            ..
        } = *input;
        let (v, nullity) = motion_direction(mech, q, previous)?;
        let predictor = &v * beta;
        let mut stepper = ClearanceTracker::new(Some(clearance));
        let alpha = stepper.fraction_cached(mech, contact, q, &predictor, cache);
        stepper.moved(alpha);
        let start = q + &predictor * alpha;
        let obj = Objective {
            progress: Some((v.clone(), q.clone(), beta, settings.step_weight)),
            springs: Vec::new(),
            spring_k: 0.0,
            drag: None,
        };
        let out = minimize_cached(mech, contact, &obj, &start, stepper.clearance(), 50, cache);
        let progress_error = ((&out.q - q).dot(&v) - beta).abs() / beta;
        Ok(StepTry {
            outcome: out,
            direction: v,
            nullity,
            progress_error,
        })
    }
}

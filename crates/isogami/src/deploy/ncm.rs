//! Nonlinear compliant modes (Duenser et al. 2022) as a baseline: the step problem of rigid
//! modes, but the progress is always the projection of q − q⁰ on the *initial* eigenvector.
//! Where the path turns away from that eigenvector the projection stops growing and the
//! method cannot go on.

use super::error::DeployError;
use super::march::{unit_displacement, StepInput, StepPolicy, StepTry};
use super::newton::{minimize_cached, Objective};
use super::settings::DeploySettings;
use crate::contact::ClearanceTracker;
use crate::contact::{ContactModel, PairCache};
use crate::kinematics::Mechanism;

/// The NCM step.
pub(super) struct Ncm;

impl StepPolicy for Ncm {
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
            initial,
            previous,
            beta,
            s,
        } = *input;
        // Predict along the last direction actually travelled.
        let predictor = previous * beta;
        let mut stepper = ClearanceTracker::new(Some(clearance));
        let alpha = stepper.fraction_cached(mech, contact, q, &predictor, cache);
        stepper.moved(alpha);
        let start = q + &predictor * alpha;
        let target = s + beta;
        let obj = Objective {
            progress: Some((
                initial.clone(),
                mech.rest.clone(),
                target,
                settings.step_weight,
            )),
            springs: Vec::new(),
            spring_k: 0.0,
            drag: None,
        };
        let out = minimize_cached(mech, contact, &obj, &start, stepper.clearance(), 50, cache);
        let achieved = (&out.q - &mech.rest).dot(initial);
        let progress_error = (achieved - target).abs() / beta;
        let direction = unit_displacement(&out.q, q, previous.clone());
        Ok(StepTry {
            outcome: out,
            direction,
            nullity: 1,
            progress_error,
        })
    }
}

//! Spring-based opening (Liu et al. 2022a) as a baseline: at every load step, springs pull the
//! tiling vectors from their current values towards an isotropically enlarged cell,
//! (1 + β)·u and (1 + β)·w, like a biaxial rig pulling at the sheet's boundary. Each load step
//! relaxes the sheet under the springs, then closes the joints exactly again (the springs
//! only say where to go). Where the mechanism's path no longer lets the cell grow the way the
//! springs pull, the sheet stops moving: stalled.

use super::error::DeployError;
use super::march::{unit_displacement, StepInput, StepPolicy, StepTry};
use super::newton::{minimize_cached, Objective};
use super::settings::DeploySettings;
use crate::contact::{ContactModel, PairCache};
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};

/// A load step that grows the cell area by less than this fraction of the load increment
/// (relative to the area) counts as no motion.
const STALL_FRACTION: Real = 1e-4;

fn cell_area(mech: &Mechanism, q: &DVec) -> Real {
    let (u, w) = mech.lattice(q);
    crate::math::cross(&u, &w).abs()
}

/// The spring load step.
pub(super) struct Springs;

impl StepPolicy for Springs {
    fn solve(
        &self,
        mech: &Mechanism,
        contact: &ContactModel,
        settings: &DeploySettings,
        input: &StepInput,
        cache: &mut PairCache,
    ) -> Result<StepTry, DeployError> {
        let StepInput {
            q, clearance, beta, ..
        } = *input;
        let l = mech.layout;
        let springs = [l.u(), l.u() + 1, l.w(), l.w() + 1]
            .into_iter()
            .map(|i| (i, (1.0 + beta) * q[i]))
            .collect();
        let relax = Objective {
            progress: None,
            springs,
            spring_k: settings.step_weight,
            drag: None,
        };
        let relaxed = minimize_cached(mech, contact, &relax, q, Some(clearance), 50, cache);
        let out = minimize_cached(
            mech,
            contact,
            &Objective::constraints_only(),
            &relaxed.q,
            None,
            50,
            cache,
        );
        let direction = unit_displacement(&out.q, q, DVec::zeros(q.len()));
        // "Progress error" 0 when the springs opened the cell further, ∞ when they did not:
        // a stall halves the load step, and repeated stalls end the run like a blocked step.
        let (a0, a1) = (cell_area(mech, q), cell_area(mech, &out.q));
        let progress_error = if a1 - a0 > STALL_FRACTION * beta * a0 {
            0.0
        } else {
            Real::INFINITY
        };
        Ok(StepTry {
            outcome: out,
            direction,
            nullity: 1,
            progress_error,
        })
    }
}

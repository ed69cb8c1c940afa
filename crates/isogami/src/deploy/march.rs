//! The step loop shared by every method: try a step of target length β, accept it or halve
//! β, grow β after successes, stop when a step fails at the smallest allowed β.

use super::error::DeployError;
use super::newton::SolveOutcome;
use super::settings::DeploySettings;
use super::trajectory::{EndReason, RawStep};
use super::Progress;
use crate::contact::{ContactModel, PairCache};
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};

/// One attempted step.
pub(super) struct StepTry {
    pub outcome: SolveOutcome,
    pub direction: DVec,
    pub nullity: usize,
    /// |achieved progress − β| / β.
    pub progress_error: Real,
}

/// Where a step starts from.
pub(super) struct StepInput<'a> {
    /// The current (accepted) state.
    pub q: &'a DVec,
    /// Its clearance.
    pub clearance: Real,
    /// The signed opening direction at t = 0.
    pub initial: &'a DVec,
    /// The last accepted direction.
    pub previous: &'a DVec,
    /// Target step length.
    pub beta: Real,
    /// The method's progress coordinate so far (the sum of accepted β).
    pub s: Real,
}

/// Unit vector along `to − from`, or `fallback` when the two coincide.
pub(super) fn unit_displacement(to: &DVec, from: &DVec, fallback: DVec) -> DVec {
    let moved = to - from;
    let norm = moved.norm();
    if norm > 0.0 {
        moved / norm
    } else {
        fallback
    }
}

/// How a method turns a [`StepInput`] into a candidate state.
pub(super) trait StepPolicy {
    /// Attempts one step.
    fn solve(
        &self,
        mech: &Mechanism,
        contact: &ContactModel,
        settings: &DeploySettings,
        input: &StepInput,
        cache: &mut PairCache,
    ) -> Result<StepTry, DeployError>;
}

/// How a march ended.
pub(super) enum MarchEnd {
    /// The arc-length limit was reached.
    Reached,
    /// The deployment is over.
    Ended(EndReason),
}

/// The closed state as the first step.
pub(super) fn rest_step(mech: &Mechanism, contact: &ContactModel) -> RawStep {
    RawStep {
        q: mech.rest.clone(),
        arc: 0.0,
        beta: 0.0,
        iterations: 0,
        joint_residual: mech.residual(&mech.rest).amax(),
        min_clearance: contact.min_clearance(mech, &mech.rest),
        direction: DVec::zeros(mech.rest.len()),
        nullity: 0,
    }
}

/// Steps from the last state in `steps` until contact, step exhaustion, the step limit, or
/// (when given) until the arc length reaches `arc_limit`.
#[allow(clippy::too_many_arguments)]
pub(super) fn march(
    mech: &Mechanism,
    contact: &ContactModel,
    settings: &DeploySettings,
    policy: &dyn StepPolicy,
    steps: &mut Vec<RawStep>,
    initial: &DVec,
    previous: &DVec,
    arc_limit: Option<Real>,
    attempts: &mut usize,
    progress: Progress<'_>,
    cache: &mut PairCache,
) -> Result<MarchEnd, DeployError> {
    let dhat = settings.contact.dhat;
    let mut prev = previous.clone();
    let mut beta = settings.initial_step;
    // Ten halvings of the initial step is the smallest step ever tried (paper: "if we cannot
    // take a full step after 10 bisections"); successes at tiny steps do not reset that floor,
    // so grinding towards contact with ever smaller steps ends.
    let min_beta = settings.initial_step / Real::powi(2.0, settings.max_halvings as i32);
    let mut s: Real = steps.iter().map(|st| st.beta).sum();
    let (u0, w0) = mech.lattice(&mech.rest);
    let stretch_limit = settings.max_stretch * (u0.norm() + w0.norm());
    loop {
        if steps.len() > settings.max_steps || *attempts >= settings.max_attempts {
            return Ok(MarchEnd::Ended(EndReason::MaxSteps));
        }
        let last = steps.last().expect("march starts from a state");
        let q = last.q.clone();
        *attempts += 1;
        let input = StepInput {
            q: &q,
            clearance: last.min_clearance,
            initial,
            previous: &prev,
            beta,
            s,
        };
        let tried = policy.solve(mech, contact, settings, &input, cache)?;
        let out = &tried.outcome;
        if out.q.iter().any(|x| !x.is_finite()) {
            return Ok(MarchEnd::Ended(EndReason::Diverged {
                diagnostics: format!(
                    "non-finite state after step {} (beta {beta:.3e})",
                    steps.len()
                ),
            }));
        }
        let (u, w) = mech.lattice(&out.q);
        if u.norm().max(w.norm()) > stretch_limit {
            return Ok(MarchEnd::Ended(EndReason::Diverged {
                diagnostics: format!(
                    "after step {} a tiling vector is {:.3e} times the closed cell's size: the \
                     sheet comes apart",
                    steps.len(),
                    u.norm().max(w.norm()) / (u0.norm() + w0.norm())
                ),
            }));
        }
        // The line search only accepts intersection-free states (the barrier is infinite on
        // overlap); the exact overlap test runs again on every stored frame.
        let accepted = tried.progress_error <= settings.step_tolerance
            && out.joint_residual <= settings.joint_tolerance;
        if accepted {
            let arc = last.arc + (&out.q - &q).norm();
            let min_clearance = contact.min_clearance_in_free_set_cached(mech, &out.q, cache);
            steps.push(RawStep {
                q: out.q.clone(),
                arc,
                beta,
                iterations: out.iterations,
                joint_residual: out.joint_residual,
                min_clearance,
                direction: tried.direction.clone(),
                nullity: tried.nullity,
            });
            if !progress(steps.len()) {
                return Err(DeployError::Cancelled);
            }
            s += beta;
            prev = tried.direction;
            beta = (beta * settings.growth).min(settings.max_step);
            if arc_limit.is_some_and(|limit| arc >= limit) {
                return Ok(MarchEnd::Reached);
            }
        } else {
            if beta * 0.5 < min_beta * (1.0 - 1e-12) {
                let contact_blocked = out.barrier > 0.0
                    || contact.min_clearance_in_free_set_cached(mech, &out.q, cache) < dhat
                    || last.min_clearance < dhat;
                return Ok(MarchEnd::Ended(if contact_blocked {
                    EndReason::ContactLimit
                } else {
                    EndReason::StepSizeExhausted
                }));
            }
            beta *= 0.5;
        }
    }
}

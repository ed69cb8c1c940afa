//! Deployment: the trajectory of a one-degree-of-freedom sheet from its closed state to the
//! contact-limited open state (paper §3.2), plus the two baselines of §5 on the same model.
//!
//! - [`Method::RigidModes`] (the paper's method): every step minimises
//!   E_joints + E_coll + w·E_step with Newton's method, E_step = ½((q − qⁱ)ᵀvⁱ − β)², where vⁱ
//!   is the motion vector recomputed at every step (sign kept; at turning points the
//!   null-space direction closest to the previous one). β halves when a step fails and grows
//!   after successes; a step that fails at ten halvings below the initial β ends the
//!   deployment.
//! - [`Method::Ncm`] (Duenser et al. 2022): the same step problem, but always projected on
//!   the *initial* eigenvector v⁰ and measured from the closed state.
//! - [`Method::Springs`] (Liu et al. 2022a): springs pull the tiling vectors towards an
//!   isotropically enlarged cell; each load step is a relaxation.
//! - [`pull_with`]: a finite sheet's mechanism pulled apart by two of its tiles, as a tester
//!   would, for sheets with any number of degrees of freedom (the same step problem, its
//!   progress term on the grip's move, plus a drag for the motions nothing resists).
//!
//! Every accepted state keeps every joint closed to 1e-9 L and is checked free of overlap by
//! the exact polygon test of `contact`. The line search never leaves the intersection-free
//! set (conservative advancement). This module solves; `measure` characterises the result
//! and `render` draws it. No I/O.

mod compare;
mod direction;
mod error;
mod frames;
mod insert;
mod march;
mod ncm;
mod newton;
mod opening;
mod pull;
mod report;
mod rigid_modes;
mod settings;
mod springs;
mod summary;
mod trajectory;

pub use compare::{
    compare_design, compare_design_with, compare_methods, compare_methods_with, DesignComparison,
    MethodResult, COMPARISON_DESIGNS, METHODS, PEAK_FRACTION,
};
pub use error::{DeployError, FrameProblem, InsertProblem, ReportField};
pub use frames::{
    frame_records, frame_records_for, plan_frames, select_frames, FramePick, FrameRecord,
};
pub use insert::{project_between, PROJECTION_MAX_ITER};
pub use newton::{minimize, Objective, SolveOutcome};
pub use opening::PROBE_KERFS;
pub use report::{build_report, frame_report, DeploymentReport, FrameReport, TilePose};
pub use settings::{DeploySettings, Method};
pub use summary::{
    poisson_range, step_measures, summarize_steps, StepSummary, POISSON_OPEN_FRACTION,
};
pub use trajectory::{EndReason, RawStep, Trajectory};

/// A progress callback: called with the number of states so far, returns `false` to cancel.
pub type Progress<'a> = &'a mut dyn FnMut(usize) -> bool;

use crate::contact::ContactModel;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};
use crate::mobility::analyze;

/// Deploys `mech` with `settings`. Refuses rigid designs with a clear error; a design whose
/// opening is blocked by contact at once comes back with [`EndReason::Locked`].
///
/// `progress` is called after every accepted step with the number of states so far; when it
/// returns `false` the deployment stops with [`DeployError::Cancelled`].
pub fn deploy(
    mech: &Mechanism,
    settings: &DeploySettings,
    progress: Progress<'_>,
) -> Result<Trajectory, DeployError> {
    settings.validate()?;
    let contact = ContactModel::new(mech, settings.contact)?;
    deploy_with(mech, &contact, settings, progress)
}

/// [`deploy`] with a contact model the caller already built for `mech` with
/// `settings.contact` (the entry point and the comparison check frames against the same
/// model, so it is built once).
pub fn deploy_with(
    mech: &Mechanism,
    contact: &ContactModel,
    settings: &DeploySettings,
    progress: Progress<'_>,
) -> Result<Trajectory, DeployError> {
    deploy_until(mech, contact, settings, None, progress)
}

/// [`deploy_with`] stopped once the path's arc length reaches `arc_limit` (when given; the
/// trajectory then ends with [`EndReason::MaxSteps`]): for probes that only need the path's
/// beginning.
pub(crate) fn deploy_until(
    mech: &Mechanism,
    contact: &ContactModel,
    settings: &DeploySettings,
    arc_limit: Option<Real>,
    progress: Progress<'_>,
) -> Result<Trajectory, DeployError> {
    settings.validate()?;
    if contact.settings() != &settings.contact {
        return Err(DeployError::Contact(
            crate::contact::ContactError::SettingsMismatch,
        ));
    }
    let mob = analyze(mech, &mech.rest, settings.mobility)?;
    if mob.dof == 0 {
        return Err(DeployError::Rigid);
    }
    let opening = match settings.mode {
        None => mob.motion.as_ref(),
        Some(k) => Some(mob.modes.get(k).ok_or(DeployError::ModeOutOfRange {
            mode: k,
            dof: mob.dof,
        })?),
    }
    .ok_or(DeployError::NoMotion { dof: mob.dof })?
    .vector
    .clone();
    let policy: &dyn march::StepPolicy = match settings.method {
        Method::RigidModes => &rigid_modes::RigidModes,
        Method::Ncm => &ncm::Ncm,
        Method::Springs => &springs::Springs,
    };
    let mut traj = opening::open_and_march(
        mech, contact, settings, &opening, mob.dof, policy, arc_limit, progress,
    )?;
    // The springs do not fail a step: they stop moving the sheet.
    if settings.method == Method::Springs && traj.end_reason == EndReason::StepSizeExhausted {
        traj.end_reason = EndReason::Stalled;
    }
    Ok(traj)
}

/// Pulls `mech` apart by two tiles, as a tester would: tile 0 held, tile `grip` pulled away
/// from it a load step at a time, on the same step loop, Newton solver and contact model as
/// every deployment (see `pull`). For a finite sheet's mechanism (no joint across cells,
/// tiling vectors far enough apart that no two copies of the sheet meet), with any number
/// of degrees of freedom. `dof` is recorded in the trajectory. Ends stalled when pulling no
/// longer moves the grip away, or at the contact limit.
pub fn pull_with(
    mech: &Mechanism,
    contact: &ContactModel,
    settings: &DeploySettings,
    grip: usize,
    dof: usize,
    progress: Progress<'_>,
) -> Result<Trajectory, DeployError> {
    settings.validate()?;
    if contact.settings() != &settings.contact {
        return Err(DeployError::Contact(
            crate::contact::ContactError::SettingsMismatch,
        ));
    }
    if grip == 0 || grip >= mech.tile_count() {
        return Err(DeployError::Grip {
            grip,
            tiles: mech.tile_count(),
        });
    }
    let policy = pull::Pull { grip };
    let mut steps = vec![march::rest_step(mech, contact)];
    let zero = DVec::zeros(mech.rest.len());
    let mut attempts = 0;
    let mut cache = crate::contact::PairCache::new();
    let end = match march::march(
        mech,
        contact,
        settings,
        &policy,
        &mut steps,
        &zero,
        &zero,
        None,
        &mut attempts,
        progress,
        &mut cache,
    )? {
        march::MarchEnd::Ended(EndReason::StepSizeExhausted) => EndReason::Stalled,
        march::MarchEnd::Ended(e) => e,
        march::MarchEnd::Reached => EndReason::MaxSteps,
    };
    let (_, axis) = pull::grip_axis(mech, &mech.rest, grip);
    let mut initial_direction = zero;
    let g = mech.layout.tile(grip);
    initial_direction[g] = axis.x;
    initial_direction[g + 1] = axis.y;
    Ok(Trajectory {
        steps,
        end_reason: end,
        initial_direction,
        attempts,
        dof,
    })
}

/// Distance between tile 0's and tile `grip`'s centres at q (units of L): what
/// [`pull_with`] pulls apart.
pub fn grip_distance(mech: &Mechanism, q: &DVec, grip: usize) -> crate::math::Real {
    pull::grip_axis(mech, q, grip).0
}

//! The finite-deployment entry point: a one-DOF finite sheet of a design opened to its own
//! contact limit, compared with the periodic sheet (see [`crate::finite::deploy`]).

use super::finite::sheet_on_its_path;
use super::{SheetAnalysis, SheetRequest};
use crate::deploy::{deploy_with, select_frames, EndReason, Progress, TilePose};
use crate::error::Result;
use crate::finite::{
    check_states, periodic_agreement, periodic_singular_states, sheet_pairs, sheet_singular_states,
    ClosedSheet, FiniteError, PeriodicAgreement, SheetMeasures, SingularState, StateCheck,
};
use crate::math::Real;
use crate::topology::Design;
use serde::Serialize;

/// What finite deployment to run.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetDeployRequest {
    /// The sheet: its region, and whether to complete it (a raw region deploys only when it
    /// is one-DOF with the periodic motion).
    pub sheet: SheetRequest,
    /// Frames of tile poses to return (at least 2: the closed and the last state).
    pub frames: usize,
    /// States along the way at which the sheet's degrees of freedom are counted.
    pub checks: usize,
}

impl Default for SheetDeployRequest {
    /// The default sheet (6×6 cells, completed), 24 frames, 8 checks.
    fn default() -> Self {
        SheetDeployRequest {
            sheet: SheetRequest::default(),
            frames: 24,
            checks: 8,
        }
    }
}

/// One frame of a finite deployment.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct SheetFrame {
    /// Step index of the finite deployment.
    pub step: usize,
    /// Its t (normalised arc length).
    pub t: Real,
    /// The sheet's measures there.
    pub measures: SheetMeasures,
    /// Smallest clearance between two of the sheet's collision polygons (units of L).
    pub min_clearance: Real,
    /// Pose of every tile of the sheet, in the order of [`SheetAnalysis::sheet`]'s tiles
    /// (tiling units; angles from the closed state).
    pub poses: Vec<TilePose>,
}

/// How the periodic sheet's deployment ended, seen on the finite sheet's tiles.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct PeriodicEnd {
    /// Why the periodic deployment ended.
    pub end_reason: EndReason,
    /// Its accepted states.
    pub steps: usize,
    /// The finite sheet's measures at the periodic deployment's last state.
    pub measures: SheetMeasures,
}

/// A finite sheet deployed with contact among its own tiles.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct SheetDeployment {
    /// The sheet: region, raw mobility and completion ([`SheetAnalysis::sheet`] is the one
    /// deployed).
    pub analysis: SheetAnalysis,
    /// Kinds of tile pair (tile, tile, cell offset) that can touch in the sheet.
    pub contact_pairs: usize,
    /// Why the finite deployment ended.
    pub end_reason: EndReason,
    /// Its accepted states.
    pub steps: usize,
    /// The sheet's measures at its last state.
    pub end: SheetMeasures,
    /// Largest hull area ratio over every state.
    pub max_hull_area_ratio: Real,
    /// The periodic deployment, for comparison.
    pub periodic: PeriodicEnd,
    /// How closely the finite deployment follows the periodic one before contact.
    pub agreement: PeriodicAgreement,
    /// The sheet's degrees of freedom at states along the way.
    pub checks: Vec<StateCheck>,
    /// Singular states of the finite deployment (every accepted state but the closed one
    /// counted; see [`crate::finite::singular`]): states where the sheet has extra
    /// first-order motions, so a sheet pulled through one can branch off the periodic
    /// motion there.
    pub singular: Vec<SingularState>,
    /// Singular states of the periodic deployment, counted the same way on the mechanism.
    pub periodic_singular: Vec<SingularState>,
    /// Whether every check found one degree of freedom with the periodic motion: when not,
    /// the sheet can leave the path computed here (see the checks; and the singular states,
    /// where it can too).
    pub one_dof_throughout: bool,
    /// Frames of tile poses, the closed state first and the last state last.
    pub frames: Vec<SheetFrame>,
}

/// Deploys the finite sheet `request` asks for: the periodic deployment first (for the
/// opened state the sheet is counted and completed at, and for comparison), then the same
/// deployment with contact only among the sheet's tiles. Refuses a sheet that is not one-DOF
/// with the periodic motion (complete it). `progress` is called by both deployments.
pub fn deploy_sheet(
    design: &Design,
    request: &SheetDeployRequest,
    progress: Progress<'_>,
) -> Result<SheetDeployment> {
    let (mech, path, analysis) = sheet_on_its_path(
        design,
        &request.sheet,
        request.frames,
        "finite deployment",
        &mut *progress,
    )?;
    if let Some(reason) = &analysis.refusal {
        return Err(FiniteError::NoOneDofSheet {
            reason: reason.clone(),
        }
        .into());
    }
    let settings = &request.sheet.settings;
    let mobility = analysis
        .completion
        .as_ref()
        .map_or(&analysis.raw_mobility, |c| &c.mobility);
    if mobility.dof != 1 || !mobility.follows_periodic {
        return Err(FiniteError::NoOneDofSheet {
            reason: format!(
                "the sheet has {} degrees of freedom{}; complete it to deploy it",
                mobility.dof,
                if mobility.follows_periodic {
                    ""
                } else {
                    " and does not move with the periodic sheet"
                }
            ),
        }
        .into());
    }
    let sheet = analysis.sheet().clone();
    let pairs = sheet_pairs(&sheet);
    let contact = path.contact.clone().restricted_to(pairs.iter().copied());
    let traj = deploy_with(&mech, &contact, settings, progress)?;
    let periodic = &path.trajectory;
    let closed = ClosedSheet::of(&sheet, &mech, &mech.rest).ok_or(FiniteError::BadRequest(
        "the sheet has fewer than three tiles or no area".into(),
    ))?;
    let measure = |q| {
        closed
            .measures(&sheet, &mech, q)
            .ok_or(FiniteError::BadRequest(
                "the sheet's measures are not finite".into(),
            ))
    };
    let checks = check_states(&sheet, &mech, &traj, request.checks, settings.mobility)?;
    let singular = sheet_singular_states(&sheet, &mech, &traj, 1, settings, crate::stop::NEVER)?;
    let periodic_singular = periodic_singular_states(&mech, periodic, settings)?;
    let mut max_hull_area_ratio: Real = 0.0;
    for s in &traj.steps {
        max_hull_area_ratio = max_hull_area_ratio.max(measure(&s.q)?.hull_area_ratio);
    }
    let scale = mech.length_scale;
    let frames = select_frames(&traj, request.frames)
        .into_iter()
        .map(|k| {
            let s = &traj.steps[k];
            // The exact overlap test on the sheet's own pairs (the solver's line search never
            // leaves the intersection-free set; this is the check every stored frame gets).
            if let Some(overlap) = contact.overlapping_pair(&mech, &s.q) {
                return Err(FiniteError::FrameCheck {
                    step: k,
                    problem: overlap.to_string(),
                }
                .into());
            }
            Ok(SheetFrame {
                step: k,
                t: traj.t(k),
                measures: measure(&s.q)?,
                min_clearance: s.min_clearance,
                poses: sheet
                    .poses(&mech, &s.q)
                    .into_iter()
                    .map(|(p, theta)| TilePose {
                        x: p.x * scale,
                        y: p.y * scale,
                        theta,
                    })
                    .collect(),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let last =
        |t: &crate::deploy::Trajectory| t.steps.last().expect("a deployment has states").q.clone();
    Ok(SheetDeployment {
        contact_pairs: pairs.len(),
        end_reason: traj.end_reason.clone(),
        steps: traj.steps.len(),
        end: measure(&last(&traj))?,
        max_hull_area_ratio,
        periodic: PeriodicEnd {
            end_reason: periodic.end_reason.clone(),
            steps: periodic.steps.len(),
            measures: measure(&last(periodic))?,
        },
        agreement: periodic_agreement(&sheet, &mech, &traj, periodic, settings.contact.dhat),
        one_dof_throughout: checks.iter().all(|c| c.dof == 1 && c.follows_periodic),
        singular,
        periodic_singular,
        checks,
        frames,
        analysis,
    })
}

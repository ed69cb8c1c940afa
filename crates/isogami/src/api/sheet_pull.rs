//! The pulled-sheet entry point: a finite sheet of a design — raw (floppy) or completed —
//! held by one tile and pulled apart by another, as a tester would, and how far its tiles
//! leave the periodic motion (see [`crate::finite::pull`]).

use super::finite::{opened_step, sheet_on_its_path};
use super::{SheetAnalysis, SheetRequest};
use crate::contact::ContactModel;
use crate::deploy::{pull_with, select_frames, EndReason, Progress, TilePose, PROBE_KERFS};
use crate::error::Result;
use crate::finite::{
    default_grips, motion_deviation, sheet_mechanism, state_check, ClosedSheet, FiniteError,
    SheetMeasures, LEAVE_TOLERANCE,
};
use crate::math::Real;
use crate::topology::Design;
use serde::Serialize;

/// What pull to run.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetPullRequest {
    /// The sheet: its region, and whether to complete it first (`complete: false` pulls the
    /// raw region, floppy boundary and all).
    pub sheet: SheetRequest,
    /// The held tile and the pulled one (indices into the pulled sheet's tiles); `None`:
    /// the sheet's leftmost and rightmost tiles held by two pins
    /// ([`crate::finite::default_grips`]).
    pub grips: Option<[usize; 2]>,
    /// Frames of tile poses to return (at least 2: the closed and the last state).
    pub frames: usize,
}

impl Default for SheetPullRequest {
    /// The default sheet request (completed, like every finite-sheet entry point: set
    /// `sheet.complete` to false for what an uncompleted patch does), default grips, 24
    /// frames.
    fn default() -> Self {
        SheetPullRequest {
            sheet: SheetRequest::default(),
            grips: None,
            frames: 24,
        }
    }
}

/// One frame of a pull.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct PullFrame {
    /// Step index of the pull.
    pub step: usize,
    /// Distance between the grips' centres over the closed sheet's.
    pub extension: Real,
    /// The sheet's measures there.
    pub measures: SheetMeasures,
    /// Largest distance of a tile vertex from where the periodic motion puts it, after the
    /// best rigid alignment, at the periodic state that fits best (units of L).
    pub deviation: Real,
    /// t of that periodic state.
    pub periodic_t: Real,
    /// Pose of every tile of the sheet, in the order of [`SheetAnalysis::sheet`]'s tiles
    /// (tiling units; angles from the closed state).
    pub poses: Vec<TilePose>,
}

/// A finite sheet pulled apart by two of its tiles.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct SheetPull {
    /// The sheet: region, raw mobility and completion ([`SheetAnalysis::sheet`] is the one
    /// pulled).
    pub analysis: SheetAnalysis,
    /// Degrees of freedom of the pulled sheet at the opened state it was counted at.
    pub dof: usize,
    /// The held tile and the pulled one (indices into the sheet's tiles).
    pub grips: [usize; 2],
    /// Why the pull ended: stalled (pulling moves the grip no further) or the contact limit.
    pub end_reason: EndReason,
    /// Its accepted states.
    pub steps: usize,
    /// Distance between the grips at the last state over the closed sheet's.
    pub extension: Real,
    /// The sheet's measures at its last state.
    pub end: SheetMeasures,
    /// Largest hull area ratio over the frames.
    pub max_hull_area_ratio: Real,
    /// Largest deviation from the periodic motion over the frames (units of L).
    pub max_deviation: Real,
    /// Tiles (indices into the sheet's tiles) that leave the periodic motion by more than
    /// [`LEAVE_TOLERANCE`] in some frame: the extra modes, seen.
    pub leaving: Vec<usize>,
    /// Where the sheet leaves the periodic motion, when it does.
    pub leaves: Option<PullLeave>,
    /// Frames of tile poses, the closed state first and the last state last.
    pub frames: Vec<PullFrame>,
}

/// Where a pulled sheet leaves the periodic motion: between two frames, and the sheet's
/// degrees of freedom on the periodic path in between. A floppy sheet leaves through its
/// extra modes; a one-DOF sheet can leave only at a branch point of its motion, where it
/// has a second one (2 DOF there).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct PullLeave {
    /// t of the periodic state nearest the last frame that still follows the motion.
    pub after_periodic_t: Real,
    /// Of the first frame that does not.
    pub before_periodic_t: Real,
    /// The sheet's largest DOF count at the periodic path's accepted states from the last at
    /// or before the one t to the first at or after the other.
    pub dof: usize,
}

/// Pulls the finite sheet `request` asks for: the periodic deployment first (for the opened
/// state the sheet is counted and completed at, and to compare with), then the sheet as a
/// mechanism of its own, held by one grip and pulled by the other with contact among its
/// own tiles, from the periodic sheet's state a probe distance
/// ([`PROBE_KERFS`] kerfs of arc) open. Works for any number of degrees of freedom.
/// Extension and measures are against the closed sheet. `progress` is called by both.
pub fn pull_sheet(
    design: &Design,
    request: &SheetPullRequest,
    progress: Progress<'_>,
) -> Result<SheetPull> {
    let (mech, path, analysis) = sheet_on_its_path(
        design,
        &request.sheet,
        request.frames,
        "pull",
        &mut *progress,
    )?;
    let settings = &request.sheet.settings;
    let sheet = analysis.sheet().clone();
    let dof = analysis
        .completion
        .as_ref()
        .map_or(analysis.raw_mobility.dof, |c| c.mobility.dof);
    let opened = path.trajectory.steps[opened_step(&path.trajectory, request.sheet.t)]
        .q
        .clone();
    let grips = match request.grips {
        Some([a, b]) => {
            if a == b || a >= sheet.len() || b >= sheet.len() {
                return Err(FiniteError::BadRequest(format!(
                    "grips {a} and {b} must be two different tiles of the sheet (0..{})",
                    sheet.len()
                ))
                .into());
            }
            [a, b]
        }
        None => default_grips(&sheet, &mech, &opened).ok_or(FiniteError::BadRequest(
            "the sheet has fewer than two tiles held by two pins to pull it by, or does \
                 not stretch"
                .into(),
        ))?,
    };
    // The pull starts where the periodic sheet has opened by the deployment's probe
    // distance: the closed state is a singular configuration (a closed sheet has many
    // first-order motions, most of which no finite motion follows), where a rigid pull has
    // no preferred way to go.
    let periodic = &path.trajectory;
    let probe = PROBE_KERFS * settings.contact.kerf;
    let start = periodic
        .steps
        .iter()
        .find(|s| s.arc >= probe)
        .or(periodic.steps.last())
        .expect("a deployment has states");
    let own = sheet_mechanism(&sheet, &mech, grips[0], &start.q)?;
    let contact = ContactModel::new(&own.mech, settings.contact)?;
    let grip = own.tile_of(grips[1]);
    let traj = pull_with(&own.mech, &contact, settings, grip, dof, progress)?;
    let closed_q = own.state_at(&sheet, &mech, &mech.rest);
    let closed = ClosedSheet::of(&own.sheet, &own.mech, &closed_q).ok_or(
        FiniteError::BadRequest("the sheet has fewer than three tiles or no area".into()),
    )?;
    let span = |q| crate::deploy::grip_distance(&own.mech, q, grip);
    let closed_span = span(&closed_q);
    let scale = mech.length_scale;
    let mut leaving = vec![false; sheet.len()];
    let (mut max_deviation, mut max_hull_area_ratio): (Real, Real) = (0.0, 0.0);
    let frames = select_frames(&traj, request.frames)
        .into_iter()
        .map(|k| {
            let q = &traj.steps[k].q;
            if let Some(overlap) = contact.overlapping_pair(&own.mech, q) {
                return Err(FiniteError::FrameCheck {
                    step: k,
                    problem: overlap.to_string(),
                }
                .into());
            }
            let measures =
                closed
                    .measures(&own.sheet, &own.mech, q)
                    .ok_or(FiniteError::BadRequest(
                        "the sheet's measures are not finite".into(),
                    ))?;
            let poses = own.poses(q);
            let deviation = motion_deviation(&sheet, &mech, periodic, settings, &poses);
            for (t, &d) in deviation.tiles.iter().enumerate() {
                leaving[t] |= d > LEAVE_TOLERANCE;
            }
            max_deviation = max_deviation.max(deviation.max);
            max_hull_area_ratio = max_hull_area_ratio.max(measures.hull_area_ratio);
            Ok(PullFrame {
                step: k,
                extension: span(q) / closed_span,
                measures,
                deviation: deviation.max,
                periodic_t: deviation.periodic_t,
                poses: poses
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
    let leaves = match frames.iter().position(|f| f.deviation > LEAVE_TOLERANCE) {
        Some(k) if k > 0 => {
            let (a, b) = (frames[k - 1].periodic_t, frames[k].periodic_t);
            let (lo, hi) = (a.min(b), a.max(b));
            // The accepted states from the last at or before `lo` to the first at or after
            // `hi` (the closed state left out: it is singular).
            let n = periodic.steps.len();
            let first = (0..n).rev().find(|&k| periodic.t(k) <= lo).unwrap_or(0);
            let last = (0..n).find(|&k| periodic.t(k) >= hi).unwrap_or(n - 1);
            let mut dof = 0;
            for step in first.max(1)..=last {
                dof = dof.max(state_check(&sheet, &mech, periodic, step, settings.mobility)?.dof);
            }
            Some(PullLeave {
                after_periodic_t: a,
                before_periodic_t: b,
                dof,
            })
        }
        _ => None,
    };
    let last = frames.last().expect("at least two frames");
    Ok(SheetPull {
        dof,
        grips,
        end_reason: traj.end_reason.clone(),
        steps: traj.steps.len(),
        extension: last.extension,
        end: last.measures,
        max_hull_area_ratio,
        max_deviation,
        leaving: (0..sheet.len()).filter(|&t| leaving[t]).collect(),
        leaves,
        frames,
        analysis,
    })
}

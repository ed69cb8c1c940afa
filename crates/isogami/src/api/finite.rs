//! The finite-sheet entry point: a region of a design, its mobility with a free boundary and
//! its completion to a one-DOF sheet (see [`crate::finite`]).

use super::{assemble, deploy_path};
use crate::cell::UnitCell;
use crate::deploy::{DeploySettings, Progress, Trajectory};
use crate::error::Result;
use crate::finite::{
    complete_counted, refusal_by_count, sheet_kernel, Completion, Context, FiniteError,
    FiniteSheet, Region, SheetMobility,
};
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};
use crate::stop::{watched, KeepGoing};
use crate::topology::Design;
use serde::Serialize;

/// What finite sheet to make.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetRequest {
    /// The region of the periodic sheet.
    pub region: Region,
    /// Mean edge length L in mm: the scale of a region given in mm.
    pub edge_mm: Real,
    /// The periodic state counts are made at: the accepted state nearest this t in (0, 1]
    /// (a generic opened state; the closed state is counted separately).
    pub t: Real,
    /// Complete the region to a one-DOF sheet (refused with
    /// [`FiniteError::NoOneDofSheet`] when none exists in it).
    pub complete: bool,
    /// Smallest fraction of the region's area a completed sheet must keep, in [0, 1].
    pub min_covered: Real,
    /// On a refused completion, answer with the raw region's analysis and the refusal's
    /// reason ([`SheetAnalysis::refusal`]) instead of the error.
    pub keep_raw_on_refusal: bool,
    /// The periodic deployment's settings (a finite sheet's zeros are decided by its
    /// spectrum's gap, see [`crate::finite::kernel`], not by the mobility tolerance).
    pub settings: DeploySettings,
}

impl SheetRequest {
    /// Checks the counting state t (in (0, 1]) and the smallest covered fraction (in
    /// [0, 1]); the region is checked when its tiles are made.
    pub fn validate(&self) -> Result<()> {
        let request = self;
        if !(request.t.is_finite() && request.t > 0.0 && request.t <= 1.0) {
            return Err(FiniteError::BadRequest(format!(
                "state t = {} must be in (0, 1] (an opened state)",
                request.t
            ))
            .into());
        }
        if !(0.0..=1.0).contains(&request.min_covered) {
            return Err(FiniteError::BadRequest(format!(
                "smallest covered fraction {} must be in [0, 1]",
                request.min_covered
            ))
            .into());
        }
        Ok(())
    }
}

impl Default for SheetRequest {
    /// 6×6 cells, 20 mm edges, counted at t = 0.3, completed keeping at least half the
    /// region, default settings.
    fn default() -> Self {
        SheetRequest {
            region: Region::Cells { rows: 6, cols: 6 },
            edge_mm: 20.0,
            t: 0.3,
            complete: true,
            min_covered: 0.5,
            keep_raw_on_refusal: false,
            settings: DeploySettings::default(),
        }
    }
}

/// A finite sheet of a design: the raw region and, when asked, its completion.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct SheetAnalysis {
    /// The design's spec.
    pub design: String,
    /// The region asked for.
    pub region: Region,
    /// t of the periodic state the counts were made at.
    pub t: Real,
    /// The raw region.
    pub raw: FiniteSheet,
    /// Its mobility at the opened state.
    pub raw_mobility: SheetMobility,
    /// Its degrees of freedom in the closed state (a singular configuration: usually more).
    pub raw_closed_dof: usize,
    /// The completed sheet, when asked for.
    pub completion: Option<Completion>,
    /// The completed sheet's degrees of freedom in the closed state.
    pub completed_closed_dof: Option<usize>,
    /// Why there is no completion, when one was asked for and refused (only with
    /// [`SheetRequest::keep_raw_on_refusal`]; otherwise the refusal is the error).
    #[serde(default)]
    pub refusal: Option<String>,
}

impl SheetAnalysis {
    /// The sheet a fabrication format should write: the completed one when there is one.
    pub fn sheet(&self) -> &FiniteSheet {
        self.completion.as_ref().map_or(&self.raw, |c| &c.sheet)
    }
}

/// The finite sheet of `design` that `request` asks for. The design is deployed once
/// (periodically, without frames) to find the opened state; `progress` is that
/// deployment's callback, and is asked on while the sheet is counted and completed (with
/// the deployment's last count: its `false` stops the work with a cancelled error).
pub fn finite_sheet(
    design: &Design,
    request: &SheetRequest,
    progress: Progress<'_>,
) -> Result<SheetAnalysis> {
    Ok(deployed_sheet(design, request, progress)?.2)
}

/// What the finite deployment and the pull start from: the design's mechanism, its periodic
/// deployment and the sheet `request` asks for, counted (and completed) on it. `frames` is
/// checked first (at least 2, closed and last; `what` names the run in the refusal).
pub(crate) fn sheet_on_its_path(
    design: &Design,
    request: &SheetRequest,
    frames: usize,
    what: &str,
    progress: Progress<'_>,
) -> Result<(Mechanism, super::DeployedPath, SheetAnalysis)> {
    if frames < 2 {
        return Err(FiniteError::BadRequest(format!(
            "{frames} frames: a {what} has at least 2 (closed and last)"
        ))
        .into());
    }
    deployed_sheet(design, request, progress)
}

/// [`finite_sheet`] with the mechanism and the periodic deployment it was counted on.
pub(crate) fn deployed_sheet(
    design: &Design,
    request: &SheetRequest,
    progress: Progress<'_>,
) -> Result<(Mechanism, super::DeployedPath, SheetAnalysis)> {
    request.validate()?;
    let (cell, mech) = assemble(design)?;
    // The region is made and checked before the deployment, which costs more, and so is a
    // completion that counting alone refuses.
    let requested = requested_sheet(&cell, &mech, request)?;
    if request.complete && !request.keep_raw_on_refusal {
        if let Some(refusal) = refusal_by_count(&cell, &mech, &requested, request.min_covered) {
            return Err(refusal.into());
        }
    }
    let path = deploy_path(design, &request.settings, &mut *progress)?;
    let states = path.trajectory.steps.len();
    let analysis = watched(progress, states, |keep_going| {
        sheet_of_trajectory(
            design,
            &cell,
            &mech,
            &path.trajectory,
            request,
            requested,
            keep_going,
        )
    })?;
    Ok((mech, path, analysis))
}

/// The raw sheet of the request's region (refused when it holds no tile).
pub(crate) fn requested_sheet(
    cell: &UnitCell,
    mech: &Mechanism,
    request: &SheetRequest,
) -> Result<FiniteSheet> {
    let requested = FiniteSheet::new(cell, mech, request.region.tiles(mech, request.edge_mm)?);
    if requested.is_empty() {
        return Err(FiniteError::EmptySheet.into());
    }
    Ok(requested)
}

/// Index of the opened state of `traj` (never the closed one) nearest `t`: where a sheet is
/// counted.
pub(crate) fn opened_step(traj: &Trajectory, t: Real) -> usize {
    (1..traj.steps.len())
        .min_by(|&a, &b| (traj.t(a) - t).abs().total_cmp(&(traj.t(b) - t).abs()))
        .unwrap_or(0)
}

/// [`finite_sheet`] on a deployment already made (`traj` of `mech`, assembled from `cell`) and
/// the region's sheet ([`requested_sheet`]): what the export uses, so that a patch is deployed
/// once. `keep_going` is polled between the counts and before every round of completion.
pub(crate) fn sheet_of_trajectory(
    design: &Design,
    cell: &UnitCell,
    mech: &Mechanism,
    traj: &Trajectory,
    request: &SheetRequest,
    requested: FiniteSheet,
    keep_going: KeepGoing<'_>,
) -> Result<SheetAnalysis> {
    if traj.steps.len() < 2 {
        return Err(FiniteError::NoOneDofSheet {
            reason: format!("the periodic sheet does not open ({})", traj.end_reason),
        }
        .into());
    }
    let k = opened_step(traj, request.t);
    let mobility = request.settings.mobility;
    let motion_at = |q: &DVec| -> Result<DVec> {
        let m = crate::mobility::analyze(mech, q, mobility)?;
        Ok(m.motion.map_or_else(|| DVec::zeros(q.len()), |m| m.vector))
    };
    let q = &traj.steps[k].q;
    let motion = motion_at(q)?;
    let ctx = Context {
        cell,
        mech,
        q,
        motion: &motion,
        min_covered: request.min_covered,
        keep_going,
    };
    let raw_mobility = ctx.mobility(&requested)?;
    // Only the count is wanted closed: the kernel, without the extra modes' localisation
    // (a closed 40×40 rotating-squares patch has 158 of them).
    let closed_dof = |sheet: &FiniteSheet| -> Result<usize> {
        let poses = sheet.poses(mech, &mech.rest);
        Ok(sheet_kernel(sheet, mech, &poses, keep_going)?.dof)
    };
    if !keep_going() {
        return Err(FiniteError::Cancelled.into());
    }
    let raw_closed_dof = closed_dof(&requested)?;
    let mut refusal = None;
    let (completion, completed_closed_dof) = if request.complete {
        match complete_counted(&ctx, &requested, &raw_mobility) {
            Ok(c) => {
                let dof = if c.sheet == requested {
                    raw_closed_dof
                } else {
                    closed_dof(&c.sheet)?
                };
                (Some(c), Some(dof))
            }
            Err(e @ FiniteError::NoOneDofSheet { .. }) if request.keep_raw_on_refusal => {
                refusal = Some(e.to_string());
                (None, None)
            }
            Err(e) => return Err(e.into()),
        }
    } else {
        (None, None)
    };
    Ok(SheetAnalysis {
        design: design.to_string(),
        region: request.region.clone(),
        t: traj.t(k),
        raw: requested,
        raw_mobility,
        raw_closed_dof,
        completion,
        completed_closed_dof,
        refusal,
    })
}

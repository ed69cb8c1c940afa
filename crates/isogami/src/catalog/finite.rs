//! The finite-sheet figures the catalogue stores per design (issue 22, item 5): the degrees of
//! freedom of the raw 6×6-cell patch and the fraction of it that its completion to a one-DOF
//! sheet covers, so that a user can filter and sort designs by how well a cut patch behaves.
//!
//! Computed from the periodic deployment the exploration makes anyway (the admission's
//! trajectory), at the state [`api::finite_sheet`] counts at, with the same region, counting
//! state and smallest covered fraction: the figures are those of
//! `api::finite_sheet(design, &finite_request(settings), ..)` (tested), without deploying
//! again and without the closed-state counts that analysis adds.

use super::settings::CatalogSettings;
use crate::api::{opened_step, requested_sheet, SheetRequest};
use crate::cell::UnitCell;
use crate::deploy::Trajectory;
use crate::error::{Error, Result};
use crate::finite::{complete_counted, Context, FiniteError, Region};
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};
use crate::topology::Design;
use serde::{Deserialize, Serialize};

/// Rows and columns of cells of the patch the catalogue measures.
pub const FINITE_PATCH_CELLS: usize = 6;

/// A design's finite 6×6 patch, as the catalogue stores it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FiniteFigures {
    /// Degrees of freedom of the raw 6×6-cell patch (free boundary, at the opened state; 1:
    /// the patch as cut opens with the design's one motion).
    pub raw_dof: usize,
    /// Fraction of the patch's area its completion to a one-DOF sheet keeps, in [0.5, 1];
    /// None when the region holds no one-DOF sheet covering at least half of it (e.g. an
    /// isostatic cell, whose pruned patch falls apart).
    pub covered: Option<Real>,
}

/// The finite-sheet request whose figures the catalogue stores: 6×6 cells, counted at the
/// default state (t = 0.3), completed keeping at least the default share of the region, with
/// the catalogue's deploy settings.
pub fn finite_request(settings: &CatalogSettings) -> SheetRequest {
    SheetRequest {
        region: Region::Cells {
            rows: FINITE_PATCH_CELLS,
            cols: FINITE_PATCH_CELLS,
        },
        complete: true,
        settings: settings.deploy_request().settings,
        ..SheetRequest::default()
    }
}

/// The figures of `design` from its periodic deployment `traj` (of `mech`, deployed with the
/// catalogue's settings). A design whose patch has no one-DOF sheet has `covered` None; any
/// other failure is an error.
pub(crate) fn figures_of_trajectory(
    design: &Design,
    cell: &UnitCell,
    mech: &Mechanism,
    traj: &Trajectory,
    settings: &CatalogSettings,
) -> Result<FiniteFigures> {
    let request = finite_request(settings);
    request.validate()?;
    let requested = requested_sheet(cell, mech, &request)?;
    if traj.steps.len() < 2 {
        return Err(FiniteError::NoOneDofSheet {
            reason: format!("{design}: the periodic sheet does not open"),
        }
        .into());
    }
    let q = &traj.steps[opened_step(traj, request.t)].q;
    let mobility = request.settings.mobility;
    let analysis = crate::mobility::analyze(mech, q, mobility)?;
    let motion = analysis
        .motion
        .map_or_else(|| DVec::zeros(q.len()), |m| m.vector);
    let ctx = Context {
        cell,
        mech,
        q,
        motion: &motion,
        min_covered: request.min_covered,
        keep_going: crate::stop::NEVER,
    };
    let raw = ctx.mobility(&requested)?;
    let raw_dof = raw.dof;
    let covered = match complete_counted(&ctx, &requested, &raw) {
        Ok(c) => Some(c.report.covered_fraction),
        Err(FiniteError::NoOneDofSheet { .. }) => None,
        Err(e) => return Err(Error::from(e)),
    };
    Ok(FiniteFigures { raw_dof, covered })
}

/// The figures of `design` deployed afresh with the catalogue's settings: for rows stored
/// before the catalogue had them (a database migration).
pub fn finite_figures(design: &Design, settings: &CatalogSettings) -> Result<FiniteFigures> {
    let request = settings.deploy_request();
    let path = crate::api::deploy_path(design, &request.settings, &mut |_| true)?;
    let cell = design.cell()?;
    figures_of_trajectory(design, &cell, &path.mechanism, &path.trajectory, settings)
}

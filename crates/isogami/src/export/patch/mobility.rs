//! The sheet a patch writes — the R×C rectangle's one-DOF completion, or the rectangle
//! itself — and what it is as a finite mechanism.

use super::PatchRequest;
use crate::api::{requested_sheet, sheet_of_trajectory, Deployment, SheetRequest};
use crate::deploy::DeploySettings;
use crate::export::error::ExportError;
use crate::finite::{FiniteSheet, SheetMobility};
use crate::math::Real;
use crate::stop::KeepGoing;
use crate::topology::Design;
use serde::Serialize;

/// The patch as a finite mechanism (see [`crate::finite`]), counted at the periodic state
/// nearest t = 0.3.
#[derive(Debug, Clone, Serialize)]
pub struct PatchMobility {
    /// True when the tiles are the completion of the rectangle.
    pub completed: bool,
    /// Degrees of freedom of the written sheet with a free boundary (1 when completed).
    pub dof: usize,
    /// Degrees of freedom of the raw R×C rectangle.
    pub raw_dof: usize,
    /// Tiles of the rectangle.
    pub requested_tiles: usize,
    /// Rectangle tiles left out by completion.
    pub removed_tiles: usize,
    /// Tiles outside the rectangle added by completion.
    pub added_tiles: usize,
    /// Area of the rectangle's tiles kept over the area of all of them.
    pub covered_fraction: Real,
    /// For a graded sheet (issue 25), what it is as a mechanism of its own; then `dof` and
    /// `raw_dof` are its [`GradedMobility::dof`] (0 when the count failed), `completed` is false
    /// and the tile counts are its own. None for a design's patch.
    pub graded: Option<GradedMobility>,
}

/// A graded sheet as a mechanism of its own: its tiles each have their own shape, so the
/// periodic design's count says nothing about it; its degrees of freedom are counted on its
/// own pins ([`crate::graded::deploy::dof`]) at one of its opened states.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GradedMobility {
    /// Opening of the state the degrees of freedom were counted at, as a fraction of the
    /// optimised state's (the opened state nearest half open: the closed tiling and a fully
    /// opened state can be singular).
    pub counted_at: Real,
    /// Degrees of freedom there, rigid motions taken out (counted up to
    /// [`crate::graded::rank::MAX_COUNTED`]); None when the count failed.
    pub dof: Option<usize>,
    /// Whether the path check written with the sheet (`isogami graded`'s `path`) followed it
    /// from opened to closed along one motion; None when the sheet came without one.
    pub path_reached: Option<bool>,
}

impl GradedMobility {
    /// The record of a graded sheet of `tiles` tiles.
    pub(super) fn patch_mobility(self, tiles: usize) -> PatchMobility {
        let dof = self.dof.unwrap_or(0);
        PatchMobility {
            completed: false,
            dof,
            raw_dof: dof,
            requested_tiles: tiles,
            removed_tiles: 0,
            added_tiles: 0,
            covered_fraction: 1.0,
            graded: Some(self),
        }
    }

    /// A warning for a graded sheet not known to open along one motion.
    fn warning(&self) -> Option<String> {
        let mut said = Vec::new();
        match self.dof {
            None => said.push("its degrees of freedom could not be counted".into()),
            Some(1) => {}
            Some(d) => said.push(format!(
                "it has {d} degrees of freedom at {:.0} % open, not one",
                100.0 * self.counted_at
            )),
        }
        if self.path_reached == Some(false) {
            said.push(
                "its path check did not follow it from opened to closed along one motion".into(),
            );
        }
        (!said.is_empty()).then(|| format!("this graded sheet: {}", said.join("; ")))
    }
}

impl PatchMobility {
    /// The record of the rectangle written as it is, with `dof` degrees of freedom.
    fn raw(dof: usize, tiles: usize) -> PatchMobility {
        PatchMobility {
            completed: false,
            dof,
            raw_dof: dof,
            requested_tiles: tiles,
            removed_tiles: 0,
            added_tiles: 0,
            covered_fraction: 1.0,
            graded: None,
        }
    }

    /// A warning for a sheet that is not one mechanism with one DOF, naming its DOF.
    pub fn warning(&self) -> Option<String> {
        if let Some(g) = &self.graded {
            return g.warning();
        }
        (self.dof != 1).then(|| {
            format!(
                "this raw patch has {} degrees of freedom with a free boundary (its boundary \
                 tiles flop), not the design's one; the completed sheet (the default export) \
                 opens with one",
                self.dof
            )
        })
    }
}

/// The sheet to write — the R×C rectangle's completion, or the rectangle itself with `raw`
/// — and what it is as a mechanism, from the deployment already made. `keep_going` may
/// stop the completion.
pub(super) fn finite_patch(
    design: &Design,
    cell: &crate::cell::UnitCell,
    run: &Deployment,
    request: &PatchRequest,
    settings: DeploySettings,
    keep_going: KeepGoing<'_>,
) -> Result<(FiniteSheet, PatchMobility), ExportError> {
    let sheet_request = SheetRequest {
        region: request.region(),
        edge_mm: request.region_edge_mm(),
        complete: request.complete,
        settings,
        ..SheetRequest::default()
    };
    let mech = &run.mechanism;
    let requested = requested_sheet(cell, mech, &sheet_request)?;
    if run.trajectory.steps.len() < 2 {
        // A design locked by contact has no opened state: its raw rectangle, counted closed.
        if request.complete {
            let reason = "the periodic sheet does not open (locked by contact)".into();
            return Err(
                crate::Error::from(crate::finite::FiniteError::NoOneDofSheet { reason }).into(),
            );
        }
        let poses = requested.poses(mech, &mech.rest);
        let m: SheetMobility =
            crate::finite::sheet_mobility(&requested, mech, &poses, None, keep_going)
                .map_err(crate::Error::from)?;
        let info = PatchMobility::raw(m.dof, requested.len());
        return Ok((requested, info));
    }
    let analysis = sheet_of_trajectory(
        design,
        cell,
        mech,
        &run.trajectory,
        &sheet_request,
        requested,
        keep_going,
    )?;
    let info = match &analysis.completion {
        Some(c) => PatchMobility {
            completed: true,
            dof: c.mobility.dof,
            raw_dof: analysis.raw_mobility.dof,
            requested_tiles: c.report.requested,
            removed_tiles: c.report.removed.len(),
            added_tiles: c.report.added.len(),
            covered_fraction: c.report.covered_fraction,
            graded: None,
        },
        None => PatchMobility::raw(analysis.raw_mobility.dof, analysis.raw.len()),
    };
    Ok((analysis.sheet().clone(), info))
}

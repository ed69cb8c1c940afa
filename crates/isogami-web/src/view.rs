//! The design view: everything the design page shows about one design, from the database
//! or from a live deployment — the report with its frames, the drawable geometry, the
//! linkages, and a notice when the motion needs explaining.

use crate::error::{ApiError, ApiResult};
use crate::live::explain;
use isogami::api::{
    linkages, resolve_design, sheet_geometry, tile_linkages, Deployment, Design, SheetGeometry,
};
use isogami::deploy::{DeploymentReport, EndReason};
use isogami::linkage::LinkageAnalysis;
use isogami_store::{DesignSummary, Origin, StoredDesign};
use serde::Serialize;

/// Something about a motion the user should know, with what to do.
#[derive(Debug, Clone, Serialize, PartialEq, Eq)]
pub struct Notice {
    /// `multi_dof`, `locked` or `barely_opens`.
    pub kind: &'static str,
    /// What happened.
    pub message: String,
    /// What to do.
    pub hint: String,
}

/// One design as the design page needs it.
#[derive(Debug, Clone, Serialize)]
pub struct DesignView {
    /// Spec string.
    pub spec: String,
    /// Where it is stored; `None` for a live deployment not in the database.
    pub origin: Option<Origin>,
    /// Its catalogue row, when stored.
    pub summary: Option<DesignSummary>,
    /// A remark on the motion, if one is due.
    pub notice: Option<Notice>,
    /// The deployment report with its frames.
    pub report: DeploymentReport,
    /// Tile polygons and cell edges.
    pub geometry: SheetGeometry,
    /// Linkages, when known.
    pub linkages: Option<LinkageAnalysis>,
    /// For each tile, the indices of every linkage through it (ascending; empty for none).
    pub tile_linkages: Vec<Vec<usize>>,
    /// The specs of the same design on other cells of its family, stored with this one
    /// (empty for a live deployment or a design without cell twins).
    pub other_cells: Vec<String>,
}

impl DesignView {
    /// The view of a stored design.
    pub fn stored(stored: StoredDesign) -> ApiResult<DesignView> {
        let design = resolve_design(&stored.summary.spec).map_err(|e| {
            ApiError::internal(format!(
                "stored spec {} does not build: {e}",
                stored.summary.spec
            ))
        })?;
        let geometry = sheet_geometry(&design).map_err(|e| ApiError::internal(e.to_string()))?;
        let mut view = DesignView::assemble(
            stored.summary.spec.clone(),
            Some(stored.summary.origin),
            Some(stored.summary),
            stored.report,
            geometry,
            stored.linkages,
        );
        view.other_cells = stored.other_cells;
        Ok(view)
    }

    /// The view of a fresh deployment of `design`.
    pub fn live(design: &Design, run: Deployment) -> ApiResult<DesignView> {
        let geometry = sheet_geometry(design).map_err(|e| explain(&e))?;
        // A design whose linkages cannot be analysed is still shown, uncoloured.
        let analysis = linkages(design).ok();
        Ok(DesignView::assemble(
            design.to_string(),
            None,
            None,
            run.report,
            geometry,
            analysis,
        ))
    }

    fn assemble(
        spec: String,
        origin: Option<Origin>,
        summary: Option<DesignSummary>,
        report: DeploymentReport,
        geometry: SheetGeometry,
        linkages: Option<LinkageAnalysis>,
    ) -> DesignView {
        let tiles = geometry.tiles.len();
        let tile_linkages = linkages
            .as_ref()
            .map_or_else(|| vec![Vec::new(); tiles], |l| tile_linkages(l, tiles));
        DesignView {
            spec,
            origin,
            summary,
            notice: notice(&report),
            report,
            geometry,
            linkages,
            tile_linkages,
            other_cells: Vec::new(),
        }
    }
}

/// Area gain below which a motion is called "barely opens".
const BARELY: f64 = 0.01;

/// The remark a report calls for: several degrees of freedom, locked by contact, or almost
/// no opening.
pub fn notice(report: &DeploymentReport) -> Option<Notice> {
    if matches!(report.end_reason, EndReason::Locked) {
        return Some(Notice {
            kind: "locked",
            message: "contact blocks the first step both ways: the sheet does not open".into(),
            hint: "narrow the kerf, or change the joints so other tiles turn first".into(),
        });
    }
    if report.dof > 1 {
        return Some(Notice {
            kind: "multi_dof",
            message: format!(
                "{} degrees of freedom: not self-deployable; shown is the fastest-opening of many motions",
                report.dof
            ),
            hint: "add joints (set cut edges to a or b) until one degree of freedom is left".into(),
        });
    }
    if report.max_area_ratio < 1.0 + BARELY {
        return Some(Notice {
            kind: "barely_opens",
            message: format!(
                "the sheet barely opens (area ratio {:.3}) before {}",
                report.max_area_ratio, report.end_reason
            ),
            hint: "narrow the kerf or change the shape so the tiles collide later".into(),
        });
    }
    None
}

//! Plain records exchanged with the store.

use isogami::cell::CellDims;
use isogami::deploy::{DeploymentReport, Method};
use isogami::linkage::LinkageAnalysis;
use isogami::measure::BehaviourClass;
use isogami::tiling::Family;
use serde::{Deserialize, Serialize};

/// One finished work unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WorkUnitRecord {
    /// Deterministic id, e.g. `IH28/2x1`.
    pub id: String,
    /// Family name.
    pub family: String,
    /// Cell, e.g. `2x1`.
    pub cell: String,
    /// What the unit did, e.g. `topology+shapes`.
    pub kind: String,
    /// Wall time.
    pub seconds: f64,
    /// Peak resident memory of the exploring process while the unit ran, in bytes (the unit's
    /// own peak when it ran alone, e.g. `--jobs 1` or a big unit at the end of a run; an upper
    /// bound when other units ran beside it). None where it cannot be measured (not Linux) and
    /// in databases made before it was recorded. Stored in the `unit_memory` table.
    #[serde(default)]
    pub peak_rss_bytes: Option<u64>,
}

/// Count in, count out and time of one filtering stage of a work unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageCount {
    /// Stage name, e.g. `degree`.
    pub stage: String,
    /// Candidates entering the stage.
    pub count_in: u64,
    /// Candidates leaving it.
    pub count_out: u64,
    /// Time spent.
    pub seconds: f64,
}

/// Where a design came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Origin {
    /// Found by the exploration (belongs to a work unit).
    Explored,
    /// Saved by a user, e.g. from live editing in the browser.
    User,
}

impl Origin {
    /// The name stored in the database and used in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Origin::Explored => "explored",
            Origin::User => "user",
        }
    }

    /// The origin with this stored name.
    pub fn from_name(name: &str) -> Option<Origin> {
        match name {
            "explored" => Some(Origin::Explored),
            "user" => Some(Origin::User),
            _ => None,
        }
    }
}

/// The summary of one design: every value a catalogue lists, filters, sorts, facets or plots.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignSummary {
    /// Spec string (unique in a database).
    pub spec: String,
    /// Explored or saved by a user.
    pub origin: Origin,
    /// Tiling family.
    pub family: Family,
    /// Supercell.
    pub cell: CellDims,
    /// Tiles in the cell.
    pub tile_count: u32,
    /// Joint characters, one per unique edge.
    pub joints: String,
    /// Spec of the topology at default parameters this design was sampled from.
    pub topology: String,
    /// Shape parameters (the family's count, at most six).
    pub params: Vec<f64>,
    /// Behaviour class (None when the sheet does not expand).
    pub behaviour: Option<BehaviourClass>,
    /// Linkage signature such as "2×4-bar + 1×6-bar" (None without a linkage analysis).
    pub linkage_signature: Option<String>,
    /// Why the deployment ended, as the report's `end_reason.kind`, e.g. `contact_limit`.
    pub end_reason: String,
    /// Deployment method.
    pub method: Method,
    /// Degrees of freedom of the closed state (1 for explored designs; a user design with more
    /// was deployed along one chosen motion, see the report).
    pub dof: u32,
    /// Kerf relative to the mean edge length.
    pub kerf: f64,
    /// Largest principal expansion reached.
    pub max_expansion: f64,
    /// Smallest principal expansion reached.
    pub min_expansion: f64,
    /// Largest area ratio reached.
    pub max_area_ratio: f64,
    /// Largest tile rotation reached (radians).
    pub max_tile_rotation: f64,
    /// Smallest Poisson-like ratio −ε_min/ε_max over the open frames (see
    /// [`DesignRecord::from_parts`]); None when the sheet never opens.
    pub poisson_min: Option<f64>,
    /// Largest Poisson-like ratio over the open frames.
    pub poisson_max: Option<f64>,
    /// Accepted deployment states.
    pub steps: u64,
    /// Degrees of freedom of the raw 6×6-cell patch, free boundary, at the opened state (1:
    /// the patch as cut opens with the design's one motion). Computed by the exploration;
    /// None for user designs and rows migrated without it.
    #[serde(default)]
    pub finite_raw_dof: Option<u32>,
    /// Fraction of the 6×6-cell patch's area its completion to a one-DOF sheet keeps (at
    /// least 0.5); None when it has no such sheet (e.g. an isostatic cell) or, like
    /// `finite_raw_dof`, was not computed.
    #[serde(default)]
    pub finite_covered: Option<f64>,
    /// t of the most open state (largest area ratio) of the path; 1 when the sheet is most
    /// open where the path ends. Computed by the exploration (like the margins below); None
    /// for user designs.
    #[serde(default)]
    pub open_t: Option<f64>,
    /// Area ratio of the state where the path ends (the contact limit): below
    /// `max_area_ratio` when the sheet closes again past its most open state.
    #[serde(default)]
    pub end_area_ratio: Option<f64>,
    /// Shape tolerance: the largest vertex displacement (relative to the mean edge length,
    /// from `isogami::catalog::TOLERANCE_LEVELS`) under which moved shapes keep 95 % of the
    /// largest area ratio; 0 for a special design (it opens only at its exact shape); None
    /// for a family without shape parameters, user designs and rows migrated without it.
    #[serde(default)]
    pub shape_tolerance: Option<f64>,
    /// At the fabrication tolerance (`isogami::catalog::FABRICATION_TOLERANCE`, ±0.05 mm at
    /// 20 mm edges): the smaller largest area ratio of the two moved shapes as a fraction of
    /// the design's; None like `shape_tolerance`.
    #[serde(default)]
    pub fabrication_kept: Option<f64>,
}

impl DesignSummary {
    /// True when the design can be made as the catalogue stores it: it has a one-DOF finite
    /// 6×6 sheet (`finite_covered`) and keeps its opening at the fabrication tolerance
    /// (`shape_tolerance` at least `isogami::catalog::FABRICATION_TOLERANCE`, or a family
    /// without shape parameters). False for designs without the figures (user designs).
    pub fn buildable(&self) -> bool {
        self.finite_covered.is_some()
            && self.open_t.is_some()
            && self
                .shape_tolerance
                .is_none_or(|t| t >= isogami::catalog::FABRICATION_TOLERANCE)
    }
}

/// One design as written: its summary and the JSON of its full results. Built from typed
/// library values by [`DesignRecord::from_parts`] or [`DesignRecord::from_entry`], so the
/// summary always agrees with the report and the JSON always reads back.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignRecord {
    pub(crate) summary: DesignSummary,
    pub(crate) report: String,
    pub(crate) linkages: Option<String>,
}

impl DesignRecord {
    /// The summary columns.
    pub fn summary(&self) -> &DesignSummary {
        &self.summary
    }

    /// The deployment report as stored (JSON).
    pub fn report_json(&self) -> &str {
        &self.report
    }

    /// The linkage analysis as stored (JSON), if any.
    pub fn linkages_json(&self) -> Option<&str> {
        self.linkages.as_deref()
    }
}

/// A design read back with its full results as the library's types.
#[derive(Debug, Clone)]
pub struct StoredDesign {
    /// Summary columns.
    pub summary: DesignSummary,
    /// The deployment report.
    pub report: DeploymentReport,
    /// The linkage analysis, if one was stored.
    pub linkages: Option<LinkageAnalysis>,
    /// The specs of the same design on other cells of its family (same shape and path),
    /// stored with this one (cell twins; empty when it has none).
    pub other_cells: Vec<String>,
}

/// Everything one work unit writes, in one transaction.
#[derive(Debug, Clone, PartialEq)]
pub struct UnitRecords {
    /// The unit.
    pub unit: WorkUnitRecord,
    /// Its stages in pipeline order.
    pub stages: Vec<StageCount>,
    /// Its kept designs (origin `explored`).
    pub designs: Vec<DesignRecord>,
}

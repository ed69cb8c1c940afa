//! Plain records exchanged with the store.

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

/// One kept design with its summary and full results.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignRecord {
    /// Spec string (primary key).
    pub spec: String,
    /// Family name.
    pub family: String,
    /// Shape parameters as a JSON array.
    pub params: String,
    /// Cell, e.g. `2x1`.
    pub cell: String,
    /// Joint characters.
    pub joints: String,
    /// Spec of the topology at default parameters this design was sampled from.
    pub topology: String,
    /// Behaviour class, if any.
    pub behaviour: Option<String>,
    /// End reason of the deployment.
    pub end_reason: String,
    /// Largest principal expansion.
    pub max_expansion: f64,
    /// Smallest principal expansion.
    pub min_expansion: f64,
    /// Largest area ratio.
    pub max_area_ratio: f64,
    /// Largest tile rotation (radians).
    pub max_tile_rotation: f64,
    /// Accepted deployment states.
    pub steps: u64,
    /// Linkage signature such as "2×4-bar + 1×6-bar".
    pub linkage_signature: Option<String>,
    /// Full deployment report (JSON).
    pub report: String,
    /// Full linkage analysis (JSON).
    pub linkages: Option<String>,
}

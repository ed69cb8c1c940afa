//! The JSON form of a design: `{"family": "IH76", "params": [], "cell": [2, 2],
//! "joints": [{"edge": 0, "at": "b"}, …]}`. Edges not listed carry no joint; `params` may be
//! left out for the family's defaults.

use super::design::{Design, JointChoice};
use super::error::DesignError;
use crate::cell::{CellDims, UnitCell};
use crate::math::Real;
use crate::tiling::{canonical_params, Family, Tiling};
use serde::{Deserialize, Serialize};

/// One joint of the JSON form.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointJson {
    /// Unique edge index.
    pub edge: usize,
    /// Where on the edge: "a", "b" or "both".
    pub at: JointChoice,
}

/// The JSON form of a design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignJson {
    /// Family name, e.g. "IH28".
    pub family: Family,
    /// Shape parameters; the family's defaults when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub params: Option<Vec<Real>>,
    /// Supercell size [a, b].
    pub cell: CellDims,
    /// The jointed edges.
    pub joints: Vec<JointJson>,
}

impl Design {
    /// The JSON form (only jointed edges listed).
    pub fn to_json(&self) -> DesignJson {
        DesignJson {
            family: self.family,
            params: Some(canonical_params(&self.params)),
            cell: self.dims,
            joints: self
                .joints
                .iter()
                .enumerate()
                .filter(|(_, j)| **j != JointChoice::None)
                .map(|(edge, &at)| JointJson { edge, at })
                .collect(),
        }
    }

    /// Reads the JSON form; builds the cell to know its edge count.
    pub fn from_json(text: &str) -> Result<Design, DesignError> {
        let j: DesignJson = serde_json::from_str(text).map_err(|e| DesignError::Json {
            detail: e.to_string(),
        })?;
        let params = canonical_params(&j.params.unwrap_or_else(|| j.family.default_params()));
        let cell = UnitCell::new(&Tiling::new(j.family, &params)?, j.cell)?;
        let m = cell.edges.len();
        let mut joints = vec![JointChoice::None; m];
        for jj in &j.joints {
            if jj.edge >= m {
                return Err(DesignError::JointIndex {
                    index: jj.edge,
                    edges: m,
                });
            }
            if joints[jj.edge] != JointChoice::None {
                return Err(DesignError::DuplicateEdge { edge: jj.edge });
            }
            joints[jj.edge] = jj.at;
        }
        Ok(Design {
            family: j.family,
            params,
            dims: j.cell,
            joints,
        })
    }

    /// Convenience: a design from a family at default parameters with a dense joint list.
    pub fn with_defaults(family: Family, dims: CellDims, joints: Vec<JointChoice>) -> Design {
        Design {
            family,
            params: family.default_params(),
            dims,
            joints,
        }
    }
}

impl CellDims {
    /// All supercell sizes a×b with 1 ≤ a, b ≤ 4.
    pub fn all() -> impl Iterator<Item = CellDims> {
        (1..=4u8).flat_map(|a| (1..=4u8).map(move |b| CellDims::new(a, b).expect("in range")))
    }
}

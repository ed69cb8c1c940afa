//! The design type and its validation against the cell it names.

use super::error::DesignError;
use crate::cell::{CellDims, End, UnitCell};
use crate::math::Real;
use crate::tiling::{canonical_params, is_canonical, Family, Tiling, TilingError};
use serde::{Deserialize, Serialize};

/// What sits on one unique edge of the cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointChoice {
    /// No joint: the edge is cut through.
    None,
    /// A pin joint at the edge's endpoint A.
    A,
    /// A pin joint at the edge's endpoint B.
    B,
    /// Joints at both endpoints: the two tiles are welded (never part of an explored design,
    /// but useful for analysis).
    Both,
}

impl JointChoice {
    /// The spec character: `-`, `a`, `b` or `x`.
    pub fn to_char(self) -> char {
        match self {
            JointChoice::None => '-',
            JointChoice::A => 'a',
            JointChoice::B => 'b',
            JointChoice::Both => 'x',
        }
    }

    /// Reads a spec character (case-insensitive; `0` also means no joint).
    pub fn from_char(c: char) -> Option<JointChoice> {
        match c.to_ascii_lowercase() {
            '-' | '0' => Some(JointChoice::None),
            'a' => Some(JointChoice::A),
            'b' => Some(JointChoice::B),
            'x' => Some(JointChoice::Both),
            _ => None,
        }
    }

    /// The edge ends that carry a pin joint.
    pub fn ends(self) -> &'static [End] {
        match self {
            JointChoice::None => &[],
            JointChoice::A => &[End::A],
            JointChoice::B => &[End::B],
            JointChoice::Both => &[End::A, End::B],
        }
    }
}

/// A complete kirigami design: which tiling, which shape, which cell, which joints.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// Tiling family.
    pub family: Family,
    /// Shape parameters (exactly the family's count).
    pub params: Vec<Real>,
    /// Supercell size.
    pub dims: CellDims,
    /// One choice per unique edge of the cell, in the cell's edge order.
    pub joints: Vec<JointChoice>,
}

impl Design {
    /// A design with its shape parameters in canonical form (12 significant digits, see
    /// [`crate::tiling::canonical_param`]): how code that computes a shape makes a design, so
    /// that equal shapes give equal specs.
    pub fn new(
        family: Family,
        params: &[Real],
        dims: CellDims,
        joints: Vec<JointChoice>,
    ) -> Design {
        Design {
            family,
            params: canonical_params(params),
            dims,
            joints,
        }
    }

    /// The same joints at other shape parameters (made canonical).
    pub fn at_params(&self, params: &[Real]) -> Design {
        Design::new(self.family, params, self.dims, self.joints.clone())
    }

    /// True when the shape parameters are in canonical form.
    pub fn is_canonical(&self) -> bool {
        is_canonical(&self.params)
    }

    /// Reads a design given as a name (`rotating-squares`), a JSON object, or a spec string.
    pub fn resolve(text: &str) -> Result<Design, DesignError> {
        let t = text.trim();
        if let Some(d) = super::named::named_design(t) {
            return Ok(d);
        }
        if t.starts_with('{') {
            return Design::from_json(t);
        }
        t.parse()
    }

    /// The validated tiling of this design.
    pub fn tiling(&self) -> Result<Tiling, TilingError> {
        Tiling::new(self.family, &self.params)
    }

    /// Builds the cell and checks that the joints fit it.
    pub fn cell(&self) -> Result<UnitCell, DesignError> {
        let cell = UnitCell::new(&self.tiling()?, self.dims)?;
        if self.joints.len() != cell.edges.len() {
            return Err(DesignError::JointCount {
                given: self.joints.len(),
                family: self.family,
                dims: self.dims,
                edges: cell.edges.len(),
            });
        }
        Ok(cell)
    }

    /// Number of pin joints.
    pub fn joint_count(&self) -> usize {
        self.joints.iter().map(|j| j.ends().len()).sum()
    }
}

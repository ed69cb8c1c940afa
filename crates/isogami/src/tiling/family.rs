//! The 81 realizable isohedral families and their static facts.

use super::error::TilingError;
use crate::math::Real;
use serde::Serialize;
use std::fmt;
use std::str::FromStr;

/// One of the 81 realizable isohedral tiling types, named by Kaplan's number (IH1…IH93).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Family(u8);

/// Symmetry class of a tiling edge (Kaplan): J any shape, U mirror-symmetric, S
/// 180°-symmetric, I both.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum EdgeShapeKind {
    /// No symmetry.
    J,
    /// Symmetric under reflection across the edge's perpendicular bisector.
    U,
    /// Symmetric under a half turn about the edge midpoint.
    S,
    /// Both U and S.
    I,
}

/// The shape class of one prototile edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct PrototileEdge {
    /// Symmetry class.
    pub kind: EdgeShapeKind,
    /// Edges with the same id carry the same shape.
    pub shape_id: usize,
    /// True when this edge uses its shape reversed.
    pub reversed: bool,
}

/// Static facts about a family, at its default parameters.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FamilyInfo {
    /// Family name, e.g. "IH28".
    pub name: String,
    /// Kaplan's number.
    pub number: u8,
    /// Number of shape parameters v0…v5.
    pub param_count: usize,
    /// Default parameters (Kaplan's).
    pub default_params: Vec<Real>,
    /// Prototile vertex count (tiling vertices).
    pub vertex_count: usize,
    /// Tiles (aspects) in the minimal translational cell.
    pub aspect_count: usize,
    /// Shape class of every prototile edge, in order.
    pub edges: Vec<PrototileEdge>,
    /// What each shape parameter does to the tile (for slider labels), in order.
    pub param_effects: Vec<super::describe::ParamEffect>,
}

impl Family {
    /// All 81 families in Kaplan's order.
    pub fn all() -> impl Iterator<Item = Family> {
        tactile::data::TILING_TYPES.iter().map(|&n| Family(n as u8))
    }

    /// The family with Kaplan number `n`, if it is one of the 81 realizable types.
    pub fn from_number(n: u32) -> Result<Family, TilingError> {
        Self::all()
            .find(|f| u32::from(f.0) == n)
            .ok_or_else(|| TilingError::UnknownFamily {
                input: format!("IH{n}"),
            })
    }

    /// Kaplan's number.
    pub fn number(self) -> u8 {
        self.0
    }

    /// Name such as "IH28".
    pub fn name(self) -> String {
        format!("IH{}", self.0)
    }

    pub(crate) fn tactile(self) -> tactile::IsohedralTiling {
        let index = tactile::data::TILING_TYPES
            .iter()
            .position(|&n| n == usize::from(self.0))
            .expect("Family holds only realizable numbers");
        tactile::IsohedralTiling::new(tactile::data::get_tiling_type(index))
    }

    /// Number of shape parameters.
    pub fn param_count(self) -> usize {
        self.tactile().num_params()
    }

    /// Kaplan's default parameters.
    pub fn default_params(self) -> Vec<Real> {
        let t = self.tactile();
        let mut p = [0.0; 6];
        t.parameters(&mut p);
        p[..t.num_params()].to_vec()
    }

    /// Static facts for listings.
    pub fn info(self) -> FamilyInfo {
        let t = self.tactile();
        let edges = t
            .shapes()
            .map(|s| PrototileEdge {
                kind: match s.shape() {
                    tactile::EdgeShape::J => EdgeShapeKind::J,
                    tactile::EdgeShape::U => EdgeShapeKind::U,
                    tactile::EdgeShape::S => EdgeShapeKind::S,
                    tactile::EdgeShape::I => EdgeShapeKind::I,
                },
                shape_id: s.id(),
                reversed: s.reversed(),
            })
            .collect();
        FamilyInfo {
            name: self.name(),
            number: self.0,
            param_count: t.num_params(),
            default_params: self.default_params(),
            vertex_count: t.num_vertices(),
            aspect_count: t.num_aspects(),
            edges,
            param_effects: super::describe::param_effects(self),
        }
    }
}

impl fmt::Display for Family {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "IH{}", self.0)
    }
}

impl FromStr for Family {
    type Err = TilingError;

    /// Accepts "IH28", "ih28", "IH028" or "28".
    fn from_str(s: &str) -> Result<Family, TilingError> {
        let unknown = || TilingError::UnknownFamily {
            input: crate::topology::quote_input(s),
        };
        let t = s.trim();
        let digits = t
            .strip_prefix("IH")
            .or_else(|| t.strip_prefix("ih"))
            .or_else(|| t.strip_prefix("Ih"))
            .unwrap_or(t);
        if digits.is_empty() || digits.len() > 3 || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(unknown());
        }
        let n: u32 = digits.parse().map_err(|_| unknown())?;
        Family::from_number(n).map_err(|_| unknown())
    }
}

impl serde::Serialize for Family {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(&self.name())
    }
}

impl<'de> serde::Deserialize<'de> for Family {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Family, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eighty_one_families() {
        assert_eq!(Family::all().count(), 81);
        assert_eq!("IH28".parse::<Family>().unwrap().number(), 28);
        assert_eq!("ih7".parse::<Family>().unwrap().number(), 7);
        assert!("IH19".parse::<Family>().is_err()); // not realizable
        assert!("IH94".parse::<Family>().is_err());
        assert!("IH".parse::<Family>().is_err());
        assert!("IH-1".parse::<Family>().is_err());
        assert!("IH99999999999".parse::<Family>().is_err());
    }
}

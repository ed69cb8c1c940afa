//! Material presets: sensible hinge width, kerf and sheet thickness for the materials kirigami
//! sheets are commonly cut from. The numbers are the defaults seen in public kirigami tools
//! (card and felt for laser cutting; PLA for printed sheets), not measurements: every value
//! can be overridden.

use crate::math::Real;
use serde::Serialize;

/// A material preset.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Material {
    /// Card, 0.3 mm: kerf 0.1 mm, 1.0 mm hinge necks.
    Card,
    /// Felt, 2 mm: kerf 0.2 mm, 1.5 mm hinge necks.
    Felt,
    /// PLA sheet, 2 mm: 0.15 mm gap (printing clearance), 0.8 mm hinges (minimum feature).
    Pla,
}

/// The numbers a preset sets.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MaterialNumbers {
    /// Width of a hinge bridge (mm).
    pub hinge_mm: Real,
    /// Width of the cut (mm).
    pub kerf_mm: Real,
    /// Sheet thickness (mm), recorded in the file's metadata.
    pub thickness_mm: Real,
}

impl Material {
    /// All presets, in the order the CLI lists them.
    pub const ALL: [Material; 3] = [Material::Card, Material::Felt, Material::Pla];

    /// The preset's name as typed on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Material::Card => "card",
            Material::Felt => "felt",
            Material::Pla => "pla",
        }
    }

    /// The preset named `name` (`card`, `felt`, `pla`).
    pub fn from_name(name: &str) -> Option<Material> {
        Material::ALL.into_iter().find(|m| m.name() == name)
    }

    /// Hinge, kerf and thickness of the preset.
    pub fn numbers(self) -> MaterialNumbers {
        let (hinge_mm, kerf_mm, thickness_mm) = match self {
            Material::Card => (1.0, 0.1, 0.3),
            Material::Felt => (1.5, 0.2, 2.0),
            Material::Pla => (0.8, 0.15, 2.0),
        };
        MaterialNumbers {
            hinge_mm,
            kerf_mm,
            thickness_mm,
        }
    }
}

impl std::fmt::Display for Material {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_numbers_are_positive() {
        for m in Material::ALL {
            assert_eq!(Material::from_name(m.name()), Some(m));
            let n = m.numbers();
            assert!(n.hinge_mm > n.kerf_mm && n.kerf_mm > 0.0 && n.thickness_mm > 0.0);
        }
        assert_eq!(Material::from_name("wood"), None);
        // The card preset is the thinnest sheet with the narrowest cut.
        assert!(Material::Card.numbers().thickness_mm < Material::Felt.numbers().thickness_mm);
    }
}

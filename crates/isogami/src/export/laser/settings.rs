//! Laser export settings: hinge width, kerf, sheet thickness, colours, hairline width,
//! margin and labels, with their defaults and validation.

use super::error::LaserError;
use super::material::Material;
use crate::math::Real;
use serde::Serialize;

/// Colours of the three groups of a laser SVG (`#rrggbb`). Laser drivers map colours to
/// operations, and the mapping differs between tools, so every colour can be changed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LaserColours {
    /// Through cuts (default `#000000`).
    pub cut: String,
    /// Score lines (default `#0000ff`).
    pub score: String,
    /// Engraving: tile labels (default `#ff0000`).
    pub engrave: String,
}

impl Default for LaserColours {
    fn default() -> Self {
        LaserColours {
            cut: "#000000".into(),
            score: "#0000ff".into(),
            engrave: "#ff0000".into(),
        }
    }
}

/// Everything a laser sheet is laid out and written with. Lengths in millimetres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LaserSettings {
    /// Width of the bridge of uncut material at each joint (default 1.5).
    pub hinge_mm: Real,
    /// Width of the material the beam removes (default 0.2). Cut paths are compensated by
    /// half of it (see [`super::cuts`]).
    pub kerf_mm: Real,
    /// Sheet thickness, recorded in the metadata (default 2).
    pub thickness_mm: Real,
    /// Material preset the numbers came from, if any (metadata only).
    pub material: Option<Material>,
    /// Empty margin around the outline (default 5).
    pub margin_mm: Real,
    /// Stroke width of every line in the SVG: a hairline (default 0.1).
    pub stroke_mm: Real,
    /// Group colours.
    pub colours: LaserColours,
    /// Engrave each tile's index at its centre.
    pub labels: bool,
}

impl Default for LaserSettings {
    fn default() -> Self {
        LaserSettings {
            hinge_mm: 1.5,
            kerf_mm: 0.2,
            thickness_mm: 2.0,
            material: None,
            margin_mm: 5.0,
            stroke_mm: 0.1,
            colours: LaserColours::default(),
            labels: false,
        }
    }
}

impl LaserSettings {
    /// Defaults with the hinge, kerf and thickness of `material`.
    pub fn for_material(material: Material) -> Self {
        let n = material.numbers();
        LaserSettings {
            hinge_mm: n.hinge_mm,
            kerf_mm: n.kerf_mm,
            thickness_mm: n.thickness_mm,
            material: Some(material),
            ..LaserSettings::default()
        }
    }

    /// Refuses non-finite values, sizes that are zero or negative (the margin may be zero)
    /// and colours that are not `#rrggbb`.
    pub fn validate(&self) -> Result<(), LaserError> {
        let sizes = [
            ("hinge_mm", self.hinge_mm, false),
            ("kerf_mm", self.kerf_mm, false),
            ("thickness_mm", self.thickness_mm, false),
            ("margin_mm", self.margin_mm, true),
            ("stroke_mm", self.stroke_mm, false),
        ];
        for (name, value, zero_ok) in sizes {
            if !value.is_finite() {
                return Err(LaserError::NotFinite { name, value });
            }
            if value < 0.0 || (value == 0.0 && !zero_ok) {
                return Err(LaserError::NotPositive { name, value });
            }
        }
        let colours = [
            ("cut colour", &self.colours.cut),
            ("score colour", &self.colours.score),
            ("engrave colour", &self.colours.engrave),
        ];
        for (name, value) in colours {
            if !is_hex_colour(value) {
                return Err(LaserError::BadColour {
                    name,
                    value: value.clone(),
                });
            }
        }
        Ok(())
    }
}

/// True for `#rrggbb` (six hex digits).
fn is_hex_colour(s: &str) -> bool {
    s.len() == 7 && s.starts_with('#') && s[1..].chars().all(|c| c.is_ascii_hexdigit())
}

/// The red, green and blue bytes of a validated `#rrggbb` colour (black if malformed).
pub(super) fn rgb(s: &str) -> [u8; 3] {
    let byte = |i: usize| {
        s.get(i..i + 2)
            .and_then(|h| u8::from_str_radix(h, 16).ok())
            .unwrap_or(0)
    };
    [byte(1), byte(3), byte(5)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_validate_and_bad_values_name_themselves() {
        assert!(LaserSettings::default().validate().is_ok());
        for m in Material::ALL {
            assert!(LaserSettings::for_material(m).validate().is_ok());
        }
        let mut s = LaserSettings {
            hinge_mm: 0.0,
            ..LaserSettings::default()
        };
        assert!(matches!(
            s.validate(),
            Err(LaserError::NotPositive {
                name: "hinge_mm",
                ..
            })
        ));
        s.hinge_mm = 1.0;
        s.kerf_mm = -0.1;
        assert!(matches!(
            s.validate(),
            Err(LaserError::NotPositive {
                name: "kerf_mm",
                ..
            })
        ));
        s.kerf_mm = Real::NAN;
        assert!(matches!(
            s.validate(),
            Err(LaserError::NotFinite {
                name: "kerf_mm",
                ..
            })
        ));
        s.kerf_mm = 0.2;
        s.colours.cut = "black".into();
        let e = s.validate().unwrap_err();
        assert!(e.to_string().contains("\"black\""), "{e}");
        s.colours.cut = "#00ff0g".into();
        assert!(s.validate().is_err());
        assert_eq!(rgb("#0a10ff"), [10, 16, 255]);
    }
}

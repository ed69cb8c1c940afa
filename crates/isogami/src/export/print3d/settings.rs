//! 3D-print settings: sheet thickness, clearance gap, lamella hinge width and thickness, and
//! the printer's nozzle (extrusion) width, with defaults for FDM printing in PLA and their
//! validation.
//!
//! Defaults, for a 0.4 mm nozzle and 0.2 mm layers (typical FDM PLA):
//!
//! * `thickness_mm` 2.0: ten layers; the printed-PLA sheet of public kirigami tools.
//! * `gap_mm` 0.4: one extrusion width of clearance between neighbouring tiles, the printed
//!   PLA gap of those tools; narrower slots tend to close up with oozing plastic.
//! * `hinge_mm` 0.8: two extrusion widths (the usual minimum printable feature); a hinge
//!   narrower than one extrusion width may not be sliced at all, so it is refused.
//! * `lamella_mm` 0.4: two layers at the bottom face, thin enough to flex, two layers so a
//!   single weak layer line does not break it (the paper's prototypes used thin lamellae).
//! * `nozzle_mm` 0.4: the common nozzle.

use super::error::PrintError;
use crate::math::Real;
use serde::Serialize;

/// How a sheet is built for printing. Lengths in millimetres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PrintSettings {
    /// Height of the tiles (default 2.0).
    pub thickness_mm: Real,
    /// Clearance between neighbouring tiles (default 0.4); the outline of the patch keeps
    /// its size.
    pub gap_mm: Real,
    /// Width of the lamella hinge at each joint, along the edge (default 0.8).
    pub hinge_mm: Real,
    /// Thickness of the lamella, at the bottom face (default 0.4).
    pub lamella_mm: Real,
    /// The printer's nozzle (extrusion) width: the narrowest hinge accepted (default 0.4).
    pub nozzle_mm: Real,
}

impl Default for PrintSettings {
    fn default() -> Self {
        PrintSettings {
            thickness_mm: 2.0,
            gap_mm: 0.4,
            hinge_mm: 0.8,
            lamella_mm: 0.4,
            nozzle_mm: 0.4,
        }
    }
}

impl PrintSettings {
    /// Refuses sizes that are not finite or not above zero, a hinge or a gap narrower than
    /// the nozzle and a lamella not thinner than the tiles. (A hinge too wide for its edge and a
    /// gap that swallows a tile depend on the patch: [`super::print_sheet`] refuses them.)
    pub fn validate(&self) -> Result<(), PrintError> {
        let sizes = [
            ("thickness_mm", self.thickness_mm),
            ("gap_mm", self.gap_mm),
            ("hinge_mm", self.hinge_mm),
            ("lamella_mm", self.lamella_mm),
            ("nozzle_mm", self.nozzle_mm),
        ];
        for (name, value) in sizes {
            if !value.is_finite() {
                return Err(PrintError::NotFinite { name, value });
            }
            if value <= 0.0 {
                return Err(PrintError::NotPositive { name, value });
            }
        }
        if self.hinge_mm < self.nozzle_mm {
            return Err(PrintError::HingeBelowNozzle {
                hinge_mm: self.hinge_mm,
                nozzle_mm: self.nozzle_mm,
            });
        }
        if self.gap_mm < self.nozzle_mm {
            return Err(PrintError::GapBelowNozzle {
                gap_mm: self.gap_mm,
                nozzle_mm: self.nozzle_mm,
            });
        }
        if self.lamella_mm >= self.thickness_mm {
            return Err(PrintError::LamellaTooThick {
                lamella_mm: self.lamella_mm,
                thickness_mm: self.thickness_mm,
            });
        }
        Ok(())
    }

    /// The settings as metadata lines (name, value in mm).
    pub fn meta(&self) -> [(&'static str, Real); 5] {
        [
            ("thickness_mm", self.thickness_mm),
            ("gap_mm", self.gap_mm),
            ("hinge_mm", self.hinge_mm),
            ("lamella_mm", self.lamella_mm),
            ("nozzle_mm", self.nozzle_mm),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_printable() {
        let s = PrintSettings::default();
        assert!(s.validate().is_ok());
        assert!(s.hinge_mm >= s.nozzle_mm && s.lamella_mm < s.thickness_mm);
    }

    #[test]
    fn each_bad_value_is_named_in_one_line() {
        let base = PrintSettings::default();
        let cases: [(PrintSettings, &str); 9] = [
            (
                // Narrower than the nozzle: the slot fills (issue 23 item 13).
                PrintSettings {
                    gap_mm: 0.2,
                    ..base
                },
                "gap_mm 0.2 is below the nozzle",
            ),
            (
                PrintSettings {
                    thickness_mm: 0.0,
                    ..base
                },
                "thickness_mm",
            ),
            (
                PrintSettings {
                    gap_mm: -0.1,
                    ..base
                },
                "gap_mm",
            ),
            (
                PrintSettings {
                    hinge_mm: Real::NAN,
                    ..base
                },
                "hinge_mm",
            ),
            (
                PrintSettings {
                    lamella_mm: Real::INFINITY,
                    ..base
                },
                "lamella_mm",
            ),
            (
                PrintSettings {
                    nozzle_mm: -1.0,
                    ..base
                },
                "nozzle_mm",
            ),
            (
                PrintSettings {
                    hinge_mm: 0.3,
                    ..base
                },
                "nozzle",
            ),
            (
                PrintSettings {
                    lamella_mm: 2.0,
                    ..base
                },
                "thinner than",
            ),
            (
                PrintSettings {
                    lamella_mm: 3.0,
                    thickness_mm: 1.0,
                    ..base
                },
                "lamella",
            ),
        ];
        for (s, needle) in cases {
            let e = s.validate().unwrap_err().to_string();
            assert!(e.contains(needle) && !e.contains('\n'), "{e}");
        }
        // A hinge exactly one extrusion wide is accepted.
        let edge = PrintSettings {
            hinge_mm: 0.4,
            ..base
        };
        assert!(edge.validate().is_ok());
        let e = PrintSettings {
            hinge_mm: 0.3,
            ..base
        }
        .validate()
        .unwrap_err();
        assert!(matches!(e, PrintError::HingeBelowNozzle { .. }));
    }
}

//! The 3D-print flags of `isogami export` (formats stl and 3mf): gap, lamella and nozzle
//! widths, plus the hinge width and thickness shared with the laser flags
//! ([`super::laser_args`]); checked by the library before anything is deployed or written.

use isogami::export::print3d::PrintSettings;

/// 3D-print flags.
#[derive(Debug, clap::Args)]
pub struct PrintArgs {
    /// Clearance between neighbouring printed tiles (stl/3mf), mm [default: 0.4]; the patch
    /// outline keeps its size.
    #[arg(long, allow_hyphen_values = true)]
    gap_mm: Option<f64>,
    /// Thickness of the lamella hinges at the bottom face (stl/3mf), mm [default: 0.4]; must
    /// be thinner than --thickness-mm.
    #[arg(long, allow_hyphen_values = true)]
    lamella_mm: Option<f64>,
    /// The printer's nozzle (extrusion) width (stl/3mf), mm [default: 0.4]: a hinge narrower
    /// than it is refused.
    #[arg(long, allow_hyphen_values = true)]
    nozzle_mm: Option<f64>,
}

impl PrintArgs {
    /// The validated settings: defaults, then every flag given (`hinge_mm` and
    /// `thickness_mm` come from the shared flags).
    pub fn settings(
        &self,
        hinge_mm: Option<f64>,
        thickness_mm: Option<f64>,
    ) -> Result<PrintSettings, String> {
        let mut s = PrintSettings::default();
        for (slot, v) in [
            (&mut s.hinge_mm, hinge_mm),
            (&mut s.thickness_mm, thickness_mm),
            (&mut s.gap_mm, self.gap_mm),
            (&mut s.lamella_mm, self.lamella_mm),
            (&mut s.nozzle_mm, self.nozzle_mm),
        ] {
            if let Some(v) = v {
                *slot = v;
            }
        }
        s.validate().map_err(|e| e.to_string())?;
        Ok(s)
    }
}

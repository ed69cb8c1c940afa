//! 3D-printable sheets of a patch: tiles extruded to the sheet thickness with a clearance gap
//! between neighbours, joined at every joint by a thin lamella hinge at the bottom face (the
//! paper's printed prototypes, §5.2), united into one closed manifold solid and written as
//! binary STL or 3MF.
//!
//! | concern | module |
//! |---|---|
//! | settings, defaults (FDM PLA) and validation | [`settings`] |
//! | why a sheet is refused | [`error`] |
//! | tile and hinge footprints (gap, hinge placement) | [`layout`] |
//! | a lamella slab across its joint's gap, closed or opened | `band` |
//! | the plan's last check: slabs a gap from everything else | `clearance` |
//! | per-edge polygon inset (the gap) | [`offset`] |
//! | every two tiles a gap apart (notches, opened contacts) | [`separate`] |
//! | the smallest patch that fits, for refusals | [`smallest`] |
//! | extrusion and the mesh boolean (manifold-rust) | [`solid`] |
//! | the mesh, its volume and bounds | [`mesh`] |
//! | binary STL | [`stl`] |
//! | 3MF package | [`threemf`] |
//!
//! [`print_sheet`] builds the solid of an export [`Patch`] at its state; [`PrintSheet::stl`]
//! and [`PrintSheet::threemf`] write it. Nothing here does I/O.

mod band;
mod clearance;
pub mod error;
pub mod layout;
pub mod mesh;
pub mod offset;
pub mod separate;
pub mod settings;
pub mod smallest;
pub mod solid;
pub mod stl;
pub mod threemf;

pub use error::PrintError;
pub use layout::{print_layout, HingeSlab, PrintLayout};
pub use mesh::PrintMesh;
pub use settings::PrintSettings;
pub use solid::print_solid;

use super::laser::fmt_mm;
use super::Patch;
use crate::stop::{KeepGoing, NEVER};
use threemf::ModelMeta;

/// A printable sheet: its footprints, the united mesh and what it was made from.
#[derive(Debug, Clone)]
pub struct PrintSheet {
    /// Tile and hinge footprints.
    pub layout: PrintLayout,
    /// The closed solid, mm.
    pub mesh: PrintMesh,
    /// Settings it was made with.
    pub settings: PrintSettings,
    /// The design's spec string.
    pub design: String,
    /// Metadata lines (name, value): design, patch, scale, state, settings, counts.
    pub meta: Vec<(String, String)>,
}

/// The printable sheet of `patch` at its state with `settings`.
pub fn print_sheet(patch: &Patch, settings: &PrintSettings) -> Result<PrintSheet, PrintError> {
    print_sheet_until(patch, settings, NEVER)
}

/// [`print_sheet`] polling `keep_going` between its stages (layout, the search for the
/// smallest size that fits after a refusal, every tile's solid, the union):
/// [`PrintError::Cancelled`] once it says stop.
pub fn print_sheet_until(
    patch: &Patch,
    settings: &PrintSettings,
    keep_going: KeepGoing<'_>,
) -> Result<PrintSheet, PrintError> {
    settings.validate()?;
    let layout = print_layout(patch, settings)
        .map_err(|e| smallest::with_smallest(e, patch, settings, keep_going))?;
    let mesh = print_solid(&layout, settings, keep_going)?;
    let mut meta: Vec<(String, String)> = vec![
        ("spec".into(), patch.design.clone()),
        (
            "patch".into(),
            format!("{}x{} cells", patch.rows, patch.cols),
        ),
        ("units".into(), "mm".into()),
        ("edge_mm".into(), fmt_mm(patch.edge_mm)),
        (
            "size_mm".into(),
            format!(
                "{} x {}",
                fmt_mm(patch.size_mm[0]),
                fmt_mm(patch.size_mm[1])
            ),
        ),
        ("t".into(), format!("{:.4}", patch.t)),
    ];
    for (name, value) in settings.meta() {
        meta.push((name.into(), fmt_mm(value)));
    }
    meta.push((
        "tiles".into(),
        format!(
            "{} of {} (left off: {} not held by joints)",
            layout.tiles.len(),
            patch.tiles.len(),
            layout.dropped
        ),
    ));
    meta.push(("hinges".into(), layout.hinges.len().to_string()));
    meta.push((
        "hinge_layout".into(),
        "lamella slabs at the bottom face across the gap, one per joint, hinge_mm along the \
         edge; gap_mm between neighbouring tiles, the outline keeps its size"
            .into(),
    ));
    Ok(PrintSheet {
        layout,
        mesh,
        settings: *settings,
        design: patch.design.clone(),
        meta,
    })
}

impl PrintSheet {
    /// The metadata as one line, `name: value; ...`.
    pub fn description(&self) -> String {
        self.meta
            .iter()
            .map(|(k, v)| format!("{k}: {v}"))
            .collect::<Vec<_>>()
            .join("; ")
    }

    /// Binary STL (mm) with the design in its header.
    pub fn stl(&self) -> Vec<u8> {
        stl::stl_bytes(&self.mesh, &self.design)
    }

    /// The 3MF package; `creator` is the Designer (e.g. `isogami 0.1.0`).
    pub fn threemf(&self, creator: &str) -> Result<Vec<u8>, PrintError> {
        let meta = ModelMeta {
            title: format!("isogami sheet {}", self.design),
            designer: creator.to_string(),
            application: format!("isogami {}", env!("CARGO_PKG_VERSION")),
            description: self.description(),
        };
        threemf::threemf_bytes(&self.mesh, &meta)
    }
}

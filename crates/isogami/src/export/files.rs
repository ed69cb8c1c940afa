//! The one export entry point every front end calls: a design, a patch request, a format and
//! its options in; the file contents out (bytes, not yet written anywhere).
//!
//! [`export_design`] checks the request and the options before anything is deployed, builds
//! the patch ([`patch_at_with`](super::patch::patch_at_with)) and writes the format ([`export_files`]). Front ends only parse
//! their arguments into these types and store the bytes (the CLI atomically, the server as a
//! download, Python as `bytes`). [`export_graded`] does the same for a graded sheet.

use super::error::ExportError;
use super::fold::fold_text;
use super::format::Format;
use super::kirigami_sim::{kirigami_sim_files, KIRIGAMI_SIM_FILES};
use super::laser::{laser_dxf, laser_sheet, laser_svg, LaserSettings};
use super::obj::obj_text;
use super::patch::{graded_patch, patch_at_with, GradedPatchRequest, Patch, PatchRequest};
use super::print3d::{print_sheet_until, PrintSettings};
use super::tile_table::{tile_csv, tile_table};
use crate::deploy::Progress;
use crate::graded::{GradedSheet, PathCheck};
use crate::stop::{watched, KeepGoing, NEVER};
use crate::topology::Design;

/// Settings of the formats beyond the patch: the laser layout, the 3D-print solid, and the
/// creator string written into the files' metadata.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportOptions {
    /// Laser layout (SVG, DXF); ignored by the other formats.
    pub laser: LaserSettings,
    /// 3D-print solid (STL, 3MF); ignored by the other formats.
    pub print: PrintSettings,
    /// Who made the file (metadata), e.g. `isogami 0.1.0`.
    pub creator: String,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            laser: LaserSettings::default(),
            print: PrintSettings::default(),
            creator: concat!("isogami ", env!("CARGO_PKG_VERSION")).to_string(),
        }
    }
}

impl ExportOptions {
    /// Checks the settings `format` uses (a bad laser or print value is refused even before
    /// the deployment runs).
    pub fn validate(&self, format: Format) -> Result<(), ExportError> {
        if format.uses_laser_settings() {
            self.laser.validate()?;
        }
        if format.uses_print_settings() {
            self.print.validate()?;
        }
        Ok(())
    }
}

/// What an export produced: one file, or named files that belong in one folder.
#[derive(Debug, Clone, PartialEq)]
pub enum ExportFiles {
    /// A single file's contents.
    One(Vec<u8>),
    /// Files by name (no paths), in a fixed order.
    Folder(Vec<(&'static str, Vec<u8>)>),
}

/// The files of `format` for a patch.
pub fn export_files(
    format: Format,
    patch: &Patch,
    options: &ExportOptions,
) -> Result<ExportFiles, ExportError> {
    export_files_until(format, patch, options, NEVER)
}

/// [`export_files`] polling `keep_going` while the print formats lay out and build their
/// solid (the other formats are written from the patch at once): a cancelled error once it
/// says stop.
pub fn export_files_until(
    format: Format,
    patch: &Patch,
    options: &ExportOptions,
    keep_going: KeepGoing<'_>,
) -> Result<ExportFiles, ExportError> {
    let one = |text: String| ExportFiles::One(text.into_bytes());
    let sheet = || laser_sheet(patch, options.laser.clone());
    Ok(match format {
        Format::Svg => one(laser_svg(&sheet()?)),
        Format::Dxf => one(laser_dxf(&sheet()?)),
        Format::Fold => one(fold_text(patch, &options.creator)?),
        Format::Obj => one(obj_text(patch, &options.creator)),
        Format::TilesCsv => one(tile_csv(&tile_table(patch))),
        Format::TilesJson => one(serde_json::to_string_pretty(&tile_table(patch)).map_err(
            |e| ExportError::Encode {
                format: "tile table JSON",
                reason: e.to_string(),
            },
        )? + "\n"),
        Format::Stl => {
            ExportFiles::One(print_sheet_until(patch, &options.print, keep_going)?.stl())
        }
        Format::ThreeMf => ExportFiles::One(
            print_sheet_until(patch, &options.print, keep_going)?.threemf(&options.creator)?,
        ),
        Format::KirigamiSim => ExportFiles::Folder(
            KIRIGAMI_SIM_FILES
                .into_iter()
                .zip(kirigami_sim_files(patch).map(String::into_bytes))
                .collect(),
        ),
    })
}

/// Checks `request` and `options`, deploys `design` (reporting to `progress`, which may stop
/// it, and is asked on while the sheet is completed and a print's solid is built), places
/// the patch and writes `format`. Returns the patch too, for a summary of what was written.
pub fn export_design(
    design: &Design,
    request: &PatchRequest,
    format: Format,
    options: &ExportOptions,
    progress: Progress<'_>,
) -> Result<(Patch, ExportFiles), ExportError> {
    request.validate()?;
    options.validate(format)?;
    let mut states = 0;
    let patch = patch_at_with(design, request, &mut |n| {
        states = n;
        progress(n)
    })?;
    let files = watched(progress, states, |keep_going| {
        export_files_until(format, &patch, options, keep_going)
    })?;
    Ok((patch, files))
}

/// Checks `request` and `options`, places a graded sheet (with its path check's states when
/// given; see [`graded_patch`]) and writes `format`, polling `keep_going` while a print's
/// solid is built. Returns the patch too, for a summary of what was written.
pub fn export_graded(
    sheet: &GradedSheet,
    path: Option<&PathCheck>,
    request: &GradedPatchRequest,
    format: Format,
    options: &ExportOptions,
    keep_going: KeepGoing<'_>,
) -> Result<(Patch, ExportFiles), ExportError> {
    request.validate()?;
    options.validate(format)?;
    let patch = graded_patch(sheet, path, request)?;
    let files = export_files_until(format, &patch, options, keep_going)?;
    Ok((patch, files))
}

//! Fabrication and interchange export: a finite R×C patch of a design's sheet in millimetres,
//! and one module per file format written from it.
//!
//! [`patch_at`] deploys a design, picks a state and places every tile of the patch in mm
//! ([`Patch`]: tile polygons at the state and closed, joints with the vertex on each tile,
//! the closed outline, a series of states for animated formats). Every format module turns a
//! [`Patch`] into text and never writes files; the front ends write (atomically).
//!
//! | format | module | output |
//! |---|---|---|
//! | patch geometry | [`patch`] | [`Patch`] (plain data) |
//! | FOLD 1.1 (JSON), every state a frame | [`fold`] | text; [`fold::read_fold`] reads it back |
//! | OBJ (one object per tile) | [`obj`] | text |
//! | tile table (CSV, JSON) | [`tile_table`] | rows; CSV text |
//! | kirigami_sim's text files | [`kirigami_sim`] | four texts |
//! | laser cutting: SVG, DXF (closed sheet, bridges, kerf) | [`laser`] | texts |
//! | 3D printing: STL, 3MF (one solid, lamella hinges) | [`print3d`] | bytes |
//!
//! A graded sheet (issue 25) is written the same way: [`graded_patch`] makes its patch
//! (closed sheet, path states, optimised opened state), [`read_graded`] reads the JSON
//! `isogami graded` writes, and [`export_graded`] is its entry point.
//!
//! The library does no I/O: each format returns a `String` (or bytes), the CLI writes it.
//! Front ends call one entry point, [`export_design`] (or [`export_graded`] for a graded
//! sheet, [`export_files`] for a patch they already have), with a [`Format`] parsed from its
//! name; they never dispatch on formats.

mod error;
mod files;
pub mod fold;
mod format;
pub mod kirigami_sim;
pub mod laser;
pub mod obj;
mod outline;
pub mod patch;
pub(crate) mod piece;
pub mod print3d;
pub mod tile_table;

pub use error::ExportError;
pub use files::{
    export_design, export_files, export_files_until, export_graded, ExportFiles, ExportOptions,
};
pub use format::{Format, SettingsGroup};
pub use patch::{
    graded_patch, patch_at, patch_at_with, read_graded, GradedInput, GradedMobility,
    GradedPatchRequest, Patch, PatchJoint, PatchRequest, PatchState, PatchTile, Scale, State,
    MAX_PATCH, MAX_PATCH_FRAMES, MAX_SIZE_MM, MIN_SIZE_MM,
};

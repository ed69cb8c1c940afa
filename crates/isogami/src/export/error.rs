//! The export error: bad patch requests, unreadable files of our own formats, and the
//! pipeline's errors wrapped unchanged. Every message is one line.

use crate::math::Real;
use thiserror::Error;

/// Why an export could not be made.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ExportError {
    /// A format name that is not one of ours.
    #[error("unknown export format '{given}': expected one of {known}")]
    UnknownFormat {
        /// The name given.
        given: String,
        /// The known names, comma separated.
        known: String,
    },
    /// A patch with no rows or no columns.
    #[error("patch {rows}x{cols}: rows and columns must be at least 1")]
    EmptyPatch {
        /// Rows asked for.
        rows: usize,
        /// Columns asked for.
        cols: usize,
    },
    /// A patch over the size limit.
    #[error("patch {rows}x{cols}: at most {max} rows and {max} columns")]
    PatchTooLarge {
        /// Rows asked for.
        rows: usize,
        /// Columns asked for.
        cols: usize,
        /// The limit ([`super::MAX_PATCH`]).
        max: usize,
    },
    /// A region in mm with the patch scaled by its width (the width is what the region's
    /// sheet comes out as).
    #[error(
        "a region in mm needs the tiles' edge length (--edge-mm), not the patch width: the \
         width is what the region's sheet comes out as"
    )]
    RegionNeedsEdge,
    /// A size in mm outside [`super::MIN_SIZE_MM`]..=[`super::MAX_SIZE_MM`] (zero, negative,
    /// not finite, below a micrometre or above a kilometre).
    #[error(
        "{what} {value} mm: must be a number from {} to {} mm",
        super::MIN_SIZE_MM,
        super::MAX_SIZE_MM
    )]
    BadSize {
        /// Which size (`edge length`, `patch width`, ...).
        what: &'static str,
        /// The value given.
        value: Real,
    },
    /// A state t outside the trajectory [0, 1].
    #[error("state t = {t}: must be a number in [0, 1] (0 closed, 1 the contact limit)")]
    StatePastTrajectory {
        /// The t asked for.
        t: Real,
    },
    /// A frame count outside its range.
    #[error("{count} frames: must be in 2..={max}")]
    FrameCount {
        /// Frames asked for.
        count: usize,
        /// The limit ([`super::MAX_PATCH_FRAMES`]).
        max: usize,
    },
    /// The patch has no extent to scale (a width of zero at the asked state).
    #[error("the patch has zero {what} at the asked state: cannot scale it")]
    Degenerate {
        /// Which extent.
        what: &'static str,
    },
    /// A file of one of our formats that our reader cannot read.
    #[error("{format}: {reason}")]
    Read {
        /// The format (`FOLD`, ...).
        format: &'static str,
        /// What is wrong, with the place.
        reason: String,
    },
    /// A file could not be encoded.
    #[error("cannot write {format}: {reason}")]
    Encode {
        /// The format.
        format: &'static str,
        /// Why.
        reason: String,
    },
    /// A laser sheet cannot be laid out (hinge or kerf too wide, bad settings).
    #[error(transparent)]
    Laser(#[from] super::laser::LaserError),
    /// A printable sheet cannot be made (bad print settings, hinge or gap too wide).
    #[error(transparent)]
    Print(#[from] super::print3d::PrintError),
    /// The pipeline failed (design, deployment, settings).
    #[error(transparent)]
    Library(#[from] crate::Error),
}

impl ExportError {
    /// True when the caller's progress callback or stop check stopped the export.
    pub fn is_cancelled(&self) -> bool {
        match self {
            ExportError::Library(e) => e.is_cancelled(),
            ExportError::Print(e) => matches!(e, super::print3d::PrintError::Cancelled),
            _ => false,
        }
    }
}

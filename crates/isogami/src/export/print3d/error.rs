//! Why a printable sheet cannot be made: typed, one-line messages naming the offending
//! setting, tile or joint.

use crate::math::Real;
use thiserror::Error;

/// A 3D-print export refused.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum PrintError {
    /// A size that must be positive is zero or negative.
    #[error("{name} must be above zero, got {value} mm")]
    NotPositive {
        /// Setting name, e.g. "gap_mm".
        name: &'static str,
        /// The value given.
        value: Real,
    },
    /// A value is NaN or infinite.
    #[error("{name} must be a finite number, got {value}")]
    NotFinite {
        /// Setting name.
        name: &'static str,
        /// The value given.
        value: Real,
    },
    /// The hinge is narrower than one extrusion: a slicer would drop it.
    #[error(
        "hinge_mm {hinge_mm} is below the nozzle (extrusion) width {nozzle_mm} mm: a slicer \
         may not print it; use a hinge of at least {nozzle_mm} mm"
    )]
    HingeBelowNozzle {
        /// The hinge width asked.
        hinge_mm: Real,
        /// The nozzle width.
        nozzle_mm: Real,
    },
    /// The gap is narrower than one extrusion: the slot fills with plastic and the tiles fuse.
    #[error(
        "gap_mm {gap_mm} is below the nozzle (extrusion) width {nozzle_mm} mm: the slot would \
         fill and fuse the tiles; use a gap of at least {nozzle_mm} mm"
    )]
    GapBelowNozzle {
        /// The gap asked.
        gap_mm: Real,
        /// The nozzle width.
        nozzle_mm: Real,
    },
    /// The lamella is as thick as the tiles or thicker.
    #[error(
        "lamella_mm {lamella_mm} must be thinner than the tiles (thickness_mm {thickness_mm})"
    )]
    LamellaTooThick {
        /// The lamella thickness asked.
        lamella_mm: Real,
        /// The tile thickness.
        thickness_mm: Real,
    },
    /// The gap is so wide that a tile loses an edge or vanishes.
    #[error("gap_mm {gap_mm} is too wide for tile {tile}: {problem}")]
    GapTooWide {
        /// The gap asked.
        gap_mm: Real,
        /// The first tile it destroys.
        tile: usize,
        /// What happens to the tile.
        problem: String,
    },
    /// The hinge (with the clearance it keeps from the other tiles) does not fit on the edge
    /// of its joint.
    #[error(
        "hinge {hinge_mm} mm does not fit on the {edge_mm:.3} mm edge between tiles {tiles:?}: \
         it needs {needed_mm:.3} mm with the gap clearances"
    )]
    HingeTooWide {
        /// The hinge width asked.
        hinge_mm: Real,
        /// Length of the joint's edge.
        edge_mm: Real,
        /// Length the hinge needs on it.
        needed_mm: Real,
        /// The joint's two tiles.
        tiles: [usize; 2],
    },
    /// The patch is too small for its hinges: the edge of some joint (scaled with the patch)
    /// is shorter than its slab needs with the gap clearances, and those needs do not scale
    /// (at an opened state they grow with the joint's opening). Names the smallest `edge_mm`
    /// at which every slab fits.
    #[error(
        "hinge {hinge_mm} mm does not fit at edge_mm {edge_mm}: the {len_mm:.3} mm edge between \
         tiles {tiles:?} needs {needed_mm:.3} mm with the gap clearances; the smallest edge_mm \
         that fits is {min_edge_mm} (or use a narrower hinge or gap)"
    )]
    PatchTooSmall {
        /// The hinge width asked.
        hinge_mm: Real,
        /// The patch's mean edge length asked.
        edge_mm: Real,
        /// The smallest mean edge length at which every slab fits (rounded up to 0.001).
        min_edge_mm: Real,
        /// Length of the edge that needs the most room for its length.
        len_mm: Real,
        /// Length its slab needs.
        needed_mm: Real,
        /// The joint's two tiles (ids in the patch).
        tiles: [usize; 2],
    },
    /// A hinge comes closer than the gap to a tile it does not join, or to another hinge.
    #[error(
        "the hinge between tiles {tiles:?} comes within the gap of {other} ({})",
        match min_edge_mm {
            Some(e) => format!("the smallest edge_mm that fits is {e}, or use a narrower hinge or gap"),
            None => "no larger patch fixes it; try a narrower hinge or gap".to_string(),
        }
    )]
    HingeClash {
        /// The joint's two tiles.
        tiles: [usize; 2],
        /// What it touches: "tile 7" or "the hinge between tiles [3, 4]".
        other: String,
        /// The smallest mean edge length at which the sheet fits, when one was found.
        min_edge_mm: Option<Real>,
    },
    /// The patch's geometry is unusable (tiles that do not form a tiling, a joint off its
    /// edge).
    #[error("the patch cannot be printed: {reason}")]
    BadPatch {
        /// What is wrong.
        reason: String,
    },
    /// The mesh boolean did not give one closed manifold solid.
    #[error("the printed sheet is not one closed manifold solid: {reason}")]
    NotOneSolid {
        /// The library's status, or the number of bodies.
        reason: String,
    },
    /// The file could not be encoded.
    #[error("cannot write the 3MF package: {reason}")]
    Encode {
        /// Why.
        reason: String,
    },
    /// The caller's check stopped the work (see [`crate::stop`]).
    #[error("cancelled")]
    Cancelled,
}

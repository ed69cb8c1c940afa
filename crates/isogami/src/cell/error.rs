//! What can be wrong with a supercell size or with the geometry of a built cell.

use crate::math::Real;
use std::fmt;
use thiserror::Error;

/// A cell that cannot be built or does not tile the plane.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum CellError {
    /// A malformed "AxB" string.
    #[error("bad cell '{input}': expected AxB with 1 <= A, B <= 4, e.g. 2x1")]
    BadCell {
        /// The text as given, escaped and shortened for a one-line message.
        input: String,
    },
    /// A supercell size outside 1..=4.
    #[error("bad cell '{a}x{b}': expected AxB with 1 <= A, B <= 4, e.g. 2x1")]
    Size {
        /// Repetitions along t1.
        a: u8,
        /// Repetitions along t2.
        b: u8,
    },
    /// A cell whose geometry does not tile the plane (a bug or an extreme parameter).
    #[error("cell geometry check failed: {0}")]
    Geometry(GeometryProblem),
}

/// What the cell geometry check found.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum GeometryProblem {
    /// A tile edge without exactly one partner edge.
    PartnerCount {
        /// Tile index.
        tile: usize,
        /// Edge of that tile.
        edge: usize,
        /// Partners found.
        partners: usize,
    },
    /// The two sides of a unique edge of the family's fixed adjacency do not meet at this
    /// shape (the shape is not a tiling of the family's type).
    EdgesApart {
        /// Tile index.
        tile: usize,
        /// Edge of that tile.
        edge: usize,
        /// The partner tile and its edge.
        partner: (usize, usize),
    },
    /// Two tile edges matched to different unique edges.
    InconsistentMatch {
        /// First tile and its edge.
        a: (usize, usize),
        /// Second tile and its edge.
        b: (usize, usize),
    },
    /// The tiles do not cover the cell exactly.
    AreaMismatch {
        /// Sum of the tiles' signed areas.
        tiles: Real,
        /// Area of the cell.
        cell: Real,
    },
    /// A tile that is not counter-clockwise.
    Clockwise {
        /// Tile index.
        tile: usize,
    },
    /// Two tiles of the sheet overlap.
    Overlap {
        /// Tile of the centre cell.
        a: usize,
        /// Tile of the cell at `offset`.
        b: usize,
        /// Cell offset of tile `b` (multiples of u, w).
        offset: [i32; 2],
    },
}

impl fmt::Display for GeometryProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            GeometryProblem::PartnerCount {
                tile,
                edge,
                partners,
            } => write!(
                f,
                "edge {edge} of tile {tile} has {partners} partner edges (expected exactly one)"
            ),
            GeometryProblem::EdgesApart {
                tile,
                edge,
                partner,
            } => write!(
                f,
                "edge {edge} of tile {tile} does not meet its partner, edge {} of tile {}, at \
                 this shape",
                partner.1, partner.0
            ),
            GeometryProblem::InconsistentMatch { a, b } => write!(
                f,
                "edge {} of tile {} and edge {} of tile {} are matched inconsistently",
                a.1, a.0, b.1, b.0
            ),
            GeometryProblem::AreaMismatch { tiles, cell } => {
                write!(f, "tile areas sum to {tiles} but the cell has area {cell}")
            }
            GeometryProblem::Clockwise { tile } => {
                write!(f, "tile {tile} is not counter-clockwise")
            }
            GeometryProblem::Overlap { a, b, offset } => write!(
                f,
                "tile {a} overlaps tile {b} of cell ({}, {})",
                offset[0], offset[1]
            ),
        }
    }
}

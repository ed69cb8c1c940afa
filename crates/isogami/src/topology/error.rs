//! What can be wrong with a design given as a spec string, as JSON, or as a joint list.

use crate::cell::{CellDims, CellError};
use crate::tiling::{Family, TilingError};
use thiserror::Error;

/// A design that cannot be read or does not fit its cell.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum DesignError {
    /// A spec string without exactly four ':'-separated fields.
    #[error("bad design spec: expected FAMILY:PARAMS:CELL:JOINTS (4 fields separated by ':'), got {fields} field(s) in '{input}'")]
    FieldCount {
        /// Fields found.
        fields: usize,
        /// The spec as given, escaped and shortened for a one-line message.
        input: String,
    },
    /// A shape parameter that is not a number.
    #[error("bad design spec: shape parameter v{index} '{input}' is not a number")]
    ParamNotNumber {
        /// Index of the parameter.
        index: usize,
        /// The text as given, escaped and shortened.
        input: String,
    },
    /// A joint character other than '-', 'a', 'b', 'x'.
    #[error("bad design spec: joint character {index} is '{}'; use '-', 'a', 'b' or 'x'", .found.escape_debug())]
    JointChar {
        /// Position in the joint string.
        index: usize,
        /// The character found.
        found: char,
    },
    /// Design JSON that does not parse or does not have the design's fields.
    #[error("bad design spec: design JSON: {detail}")]
    Json {
        /// The JSON reader's description (line and column included).
        detail: String,
    },
    /// A joint list whose length is not the cell's unique edge count.
    #[error("bad design spec: {given} joint choices given but a {family} {dims} cell has {edges} unique edges")]
    JointCount {
        /// Joint choices given.
        given: usize,
        /// The design's family.
        family: Family,
        /// The design's cell.
        dims: CellDims,
        /// Unique edges of the cell.
        edges: usize,
    },
    /// A joint that names an edge the cell does not have.
    #[error(
        "joint on edge {index} is out of range: the cell has {edges} unique edges (0..{edges})"
    )]
    JointIndex {
        /// The edge index given.
        index: usize,
        /// Number of unique edges of the cell.
        edges: usize,
    },
    /// A JSON joint list naming the same edge twice.
    #[error("bad design spec: edge {edge} is listed twice")]
    DuplicateEdge {
        /// The edge index.
        edge: usize,
    },
    /// The family or its shape parameters.
    #[error(transparent)]
    Tiling(#[from] TilingError),
    /// The cell size or geometry.
    #[error(transparent)]
    Cell(#[from] CellError),
}

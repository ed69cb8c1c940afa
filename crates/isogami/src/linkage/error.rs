//! What can be wrong with the input of the linkage analysis.

use thiserror::Error;

/// A cell and joint list the linkage analysis cannot work on.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum LinkageError {
    /// A joint list whose length is not the cell's unique edge count.
    #[error("bad design spec: linkage analysis: {given} joint choices for a cell with {edges} unique edges")]
    JointCount {
        /// Joint choices given.
        given: usize,
        /// Unique edges of the cell.
        edges: usize,
    },
    /// An edge record naming a tile or tile edge the cell does not have.
    #[error(
        "cell geometry check failed: edge {edge} names a tile or tile edge the cell does not have"
    )]
    EdgeRecord {
        /// The unique edge index.
        edge: usize,
    },
}

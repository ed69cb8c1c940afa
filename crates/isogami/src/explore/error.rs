//! What can stop the topology enumeration of one family and cell.

use crate::cell::{CellDims, CellError};
use crate::kinematics::KinematicsError;
use crate::tiling::Family;
use thiserror::Error;

/// A family and cell whose topologies cannot be enumerated.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ExploreError {
    /// More unique edges than the enumeration takes.
    #[error("bad design spec: {family} {dims} has {edges} unique edges; topology enumeration takes at most {limit}")]
    TooManyEdges {
        /// The family.
        family: Family,
        /// The cell.
        dims: CellDims,
        /// Its unique edges.
        edges: usize,
        /// Most edges enumerated.
        limit: usize,
    },
    /// The cell cannot be built.
    #[error(transparent)]
    Cell(#[from] CellError),
    /// The mechanism cannot be assembled.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
}

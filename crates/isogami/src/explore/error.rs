//! What can stop the topology enumeration of one family and cell, or the planning of a run.

use crate::cell::{CellDims, CellError};
use crate::kinematics::KinematicsError;
use crate::tiling::Family;
use thiserror::Error;

/// A family and cell whose topologies cannot be enumerated, or a bad shard of a plan.
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
    /// A shard that is not `I/N` with `0 <= I < N <= MAX_SHARDS`.
    #[error("shard '{text}': expected I/N with 0 <= I < N <= {max}, e.g. 0/4", max = super::plan::MAX_SHARDS)]
    Shard {
        /// The shard as given.
        text: String,
    },
}

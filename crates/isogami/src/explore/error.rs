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
    /// Requested cells with more unique edges than the run's cap (`max_edges`): a plan never
    /// drops a requested cell silently.
    #[error(
        "{family}/{dims} has {edges} unique edges, more than the edge cap max_edges = \
         {max_edges}{}; raise the cap to {needed} or leave these cells out",
        others_text(*others)
    )]
    CellsOverCap {
        /// The first such cell's family (plan order).
        family: Family,
        /// Its cell.
        dims: CellDims,
        /// Its unique edges.
        edges: usize,
        /// The cap.
        max_edges: usize,
        /// How many more requested (family, cell) pairs are over the cap.
        others: usize,
        /// The cap that would take every requested cell.
        needed: usize,
    },
    /// A requested cell repeated more often than the run allows (`max_dims`).
    #[error("cell {dims} is larger than the run allows (at most {max_dims} repeats along either tiling vector, max_dims)")]
    CellOverDims {
        /// The cell.
        dims: CellDims,
        /// The run's largest repetition.
        max_dims: u8,
    },
    /// The cell cannot be built.
    #[error(transparent)]
    Cell(#[from] CellError),
    /// The mechanism cannot be assembled.
    #[error(transparent)]
    Kinematics(#[from] KinematicsError),
    /// A shard that is not `I/N` with `0 <= I < N <= MAX_SHARDS`.
    /// A unit split into parts that is not 1..=MAX_PARTS parts, or a part index not below the
    /// part count.
    #[error("unit parts '{text}': expected N parts with 1 <= N <= {max} (part I/N with I < N)", max = super::plan::MAX_PARTS)]
    Parts {
        /// What was given.
        text: String,
    },
    /// Parts that cannot be joined into one unit: of different units or part counts, a part
    /// missing or given twice, or enumerations that disagree on the unit's whole-mask counts.
    #[error("cannot join unit parts: {detail}")]
    PartsMismatch {
        /// What does not fit.
        detail: String,
    },
    #[error("shard '{text}': expected I/N with 0 <= I < N <= {max}, e.g. 0/4", max = super::plan::MAX_SHARDS)]
    Shard {
        /// The shard as given.
        text: String,
    },
}

fn others_text(others: usize) -> String {
    match others {
        0 => String::new(),
        1 => " (and 1 more requested cell)".to_string(),
        n => format!(" (and {n} more requested cells)"),
    }
}

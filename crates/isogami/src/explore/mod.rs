//! Design-space exploration (paper §4.1): topology enumeration with hierarchical filters.
//!
//! For one family (default shape parameters) and one cell:
//!
//! 1. [`reduced`] — the reduced space of 2^m joint masks (joint or not per unique edge) and the
//!    four cheap checks, evaluated on the periodic sheet: degree ≥ 2 over distinct
//!    (tile, offset) neighbours, path-connected cell, cycle offsets of rank 2, no jointed
//!    triangle of sheet tiles.
//! 2. [`expand`] — each surviving mask's 2^k endpoint choices, depth-first with incremental
//!    rank and safe prunes; dof = 1 certified by a rigorous bound or decided by
//!    `mobility::analyze` at the leaves (one mask per symmetry orbit of masks).
//! 3. [`separate`] — the motion must open some cut and leave no jointed pair rigidly attached
//!    (first-order relative normal velocity; the rule is an option).
//! 4. [`dedup`] — one design per symmetry orbit of the sheet, no repeats of smaller cells,
//!    one design per motion.
//! 5. [`pipeline`] — the stages strung together with counts and timings per stage, and the
//!    list of cells (a×b up to 4×4 with at most 16 unique edges) to explore per family.
//! 6. [`motion_classes`] — after the run: topologies of different cells and families whose
//!    motions match, grouped (distinct motions across the whole database).
//! 7. [`plan`] — the run's deterministic list of work units (family × cell) and the slice of
//!    it that shard I of N takes.
//!
//! Plain data in and out, deterministic (parallel work never changes a result), no I/O.
//! Deployment of the kept
//! designs, the expansion threshold and shape sampling (§4.2) are later stages.

pub mod dedup;
mod error;
pub mod expand;
pub mod motion_classes;
pub mod pipeline;
pub mod plan;
pub mod reduced;
pub mod separate;

pub use dedup::{cell_twins, duplicates_across, TwinCandidate};
pub use dedup::{
    motion_invariant, sheet_symmetries, MotionIndex, MotionInvariant, Symmetry, SymmetryGroup,
};
pub use error::ExploreError;
pub use expand::{ExpandStats, Expander, Leaf};
pub use motion_classes::{motion_classes, topology_motion};
pub use pipeline::{
    cells_to_explore, enumerate_topologies, enumerate_topology_part, expanded_mask_count,
    DesignDetails, StageTimings, TopologyOptions, TopologyReport,
};
pub use plan::{ExplorePlan, Shard, UnitPart, UnitSize, WorkItem, WorkUnit, MAX_PARTS, MAX_SHARDS};
pub use reduced::{MaskVerdict, ReducedGraph, ReducedResult, MAX_REDUCED_EDGES};
pub use separate::{closing_rates, edge_rates, separation, EdgeRate, Separation, SeparationRule};

//! Finite sheets: what a person cuts, prints or simulates is a patch of the periodic sheet,
//! and a patch is a different mechanism. Its boundary is free, so tiles held by one pin spin
//! and open linkage loops flop.
//!
//! - [`region`]: which tiles a requested region (R×C cells, or a rectangle, disc or polygon
//!   in mm) holds;
//! - [`sheet`]: the finite sheet — tiles named by (cell, tile) and the joints between two of
//!   them, found by integer arithmetic;
//! - [`kernel`]: its first-order motions, the kernel of the sparse H = JᵀJ with a free
//!   boundary (sparse Cholesky and subspace iteration);
//! - [`mobility`]: degrees of freedom and the floppy parts — every motion but the periodic
//!   one, in a local basis, with the tiles that move in each;
//! - [`complete`]: boundary completion to a sheet whose one motion is the periodic one;
//! - [`counting`]: regions where counting tiles and pins alone proves there is none;
//! - [`deploy`]: a one-DOF sheet opening with contact among its own tiles (the periodic
//!   deployment with the sheet's contact pairs), its measures and checks;
//! - [`singular`]: singular (bifurcation) states along a path, periodic or finite;
//! - [`pull`]: any sheet, floppy or not, as a mechanism of its own pulled apart by two
//!   tiles, and how far its tiles leave the periodic motion.
//!
//! Counts are made at a generic opened state of the periodic motion: the closed state is a
//! singular configuration (a closed rotating-squares patch has many first-order modes that
//! no finite motion follows), so front ends report it separately.

pub mod complete;
pub mod counting;
pub mod deploy;
mod error;
pub mod kernel;
pub mod mobility;
pub mod pull;
pub mod region;
pub mod sheet;
pub mod singular;

pub use complete::{
    complete, complete_counted, refusal_by_count, Completion, CompletionReport, Context,
};
pub use deploy::{
    check_states, periodic_agreement, sheet_pairs, sheet_polygons, state_check, ClosedSheet,
    PeriodicAgreement, SheetMeasures, StateCheck,
};
pub use error::FiniteError;
pub use kernel::{sheet_kernel, SheetKernel};
pub use mobility::{periodic_velocity, sheet_mobility, FloppyMode, SheetMobility, MOVER_FRACTION};
pub use pull::{
    default_grips, motion_deviation, sheet_mechanism, MotionDeviation, SheetMechanism,
    LEAVE_TOLERANCE,
};
pub use region::{Region, MAX_REGION_CELLS};
pub use sheet::{FiniteSheet, SheetJoint, SheetTile};
pub use singular::{periodic_singular_states, sheet_singular_states, SingularState};

//! Removing duplicate designs of one cell (paper §4.1, third eigen-analysis check), in three
//! steps, the first two keeping the lexicographically smallest joint string (= smallest spec,
//! since family, parameters and cell are shared), the third the design with the most pin
//! joints (ties: the smallest spec). One file per thing removed:
//!
//! 1. [`symmetry`] — designs that are images of each other under a symmetry of the sheet are
//!    one; each orbit is represented by its smallest joint string.
//! 2. [`repeats`] — a design on an a×b cell that repeats a design of a smaller explored cell
//!    (joints and motion both periodic under a sub-translation) is dropped.
//! 3. [`motion`] — designs whose first-order motions agree (an invariant independent of tile
//!    order, fixed tile, sign, scale and isometry) are one.
//!
//! [`orbits`] strings steps 2 and 3 together over the orbit representatives that the
//! expansion found (step 1 is the keying itself); [`lattice`] is the shared lattice helper.
//! [`across`] then finds the duplicates the per-cell steps cannot see, across cells and
//! families, by the same motion invariant; [`twins`] finds, among the designs a catalogue
//! stores, the same design on two cells of its family (same shape, same path).
//!
//! Not covered: designs on different cells (e.g. a 2×1 design and its 90°-rotated 1×2 twin, or
//! a 2×2 design invariant only under t1 + t2), symmetries of the isohedral type that the
//! default shape does not have, and invariants that tie within noise but sort differently
//! (sort keys are rounded to 1e-8; such a miss keeps a duplicate, never drops a design).
//! Plain data in and out; no I/O.

pub mod across;
mod lattice;
pub mod motion;
pub mod orbits;
pub mod repeats;
pub mod symmetry;
pub mod twins;

pub use across::duplicates_across;
pub use motion::{motion_invariant, MotionIndex, MotionInvariant, MOTION_TOL};
pub use orbits::{dedup_orbits, DedupResult, Kept};
pub use repeats::{is_repeat, repeat_translations, RepeatTest};
pub use symmetry::{joint_string, sheet_symmetries, Symmetry, SymmetryGroup};
pub use twins::{cell_twins, TwinCandidate, PATH_TOL};

//! What can go wrong when measuring a frame: inputs that do not fit or are not finite, and
//! lattices without a deformation gradient or polar decomposition.

use crate::math::{Real, Vec2};
use thiserror::Error;

/// A frame that cannot be measured.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MeasureError {
    /// Closed and current tile angle lists of different lengths.
    #[error(
        "numerical failure: frame measures: {closed} closed tile angles but {current} current ones"
    )]
    AngleCount {
        /// Closed angles given.
        closed: usize,
        /// Current angles given.
        current: usize,
    },
    /// A non-finite deployment parameter.
    #[error("numerical failure: frame measures at t = {t}")]
    NonFiniteT {
        /// The parameter.
        t: Real,
    },
    /// A tile whose rotation is not finite.
    #[error("numerical failure: frame measures: tile {tile} has a non-finite angle")]
    NonFiniteAngle {
        /// Tile index.
        tile: usize,
    },
    /// States whose length does not fit the mechanism.
    #[error("numerical failure: frame measures: states of length {closed} and {current} for a mechanism with {unknowns} unknowns")]
    StateLength {
        /// Length of the closed state.
        closed: usize,
        /// Length of the current state.
        current: usize,
        /// Unknowns of the mechanism.
        unknowns: usize,
    },
    /// Tiling vectors with a non-finite entry.
    #[error("numerical failure: deformation gradient of non-finite tiling vectors (u0 {u0:?}, w0 {w0:?}, u {u:?}, w {w:?})")]
    NonFiniteLattice {
        /// Closed u.
        u0: Vec2,
        /// Closed w.
        w0: Vec2,
        /// Current u.
        u: Vec2,
        /// Current w.
        w: Vec2,
    },
    /// Closed tiling vectors that are (nearly) parallel.
    #[error("numerical failure: closed tiling vectors u0 = ({}, {}) and w0 = ({}, {}) are parallel: no deformation gradient", .u0.x, .u0.y, .w0.x, .w0.y)]
    ParallelLattice {
        /// Closed u.
        u0: Vec2,
        /// Closed w.
        w0: Vec2,
    },
    /// A deformation gradient with a non-finite entry (column-major).
    #[error("numerical failure: polar decomposition of a non-finite deformation gradient {f:?}")]
    NonFiniteGradient {
        /// F, column-major.
        f: [Real; 4],
    },
    /// det F ≤ 0: an inverted or collapsed lattice.
    #[error("numerical failure: deformation gradient has det F = {det:e} <= 0 (inverted or collapsed lattice): no polar decomposition")]
    Inverted {
        /// det F.
        det: Real,
    },
}

//! Why a finite sheet could not be made, analysed or completed.

use crate::settings_error::SettingsError;
use thiserror::Error;

/// A finite-sheet failure, naming the offending values.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum FiniteError {
    /// A setting is out of range.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// The region holds no tile of the sheet.
    #[error("the region holds no tile of the sheet")]
    EmptySheet,
    /// A region's size or shape is unusable.
    #[error("bad region: {0}")]
    BadRegion(String),
    /// A setting of the request is out of range.
    #[error("{0}")]
    BadRequest(String),
    /// A pose or a matrix entry is NaN or infinite.
    #[error("the sheet's state is not finite")]
    NonFinite,
    /// The sparse Cholesky factorisation of H + σI failed.
    #[error("the sparse factorisation of the sheet's constraints failed")]
    Factorisation,
    /// The dense eigen-solver did not converge.
    #[error("the eigen-solver did not converge on the sheet's constraints")]
    Eigen,
    /// A frame of a finite deployment failed its check (two of the sheet's collision
    /// polygons overlap).
    #[error("frame at step {step} of the finite deployment fails its check: {problem}")]
    FrameCheck {
        /// Step index.
        step: usize,
        /// What is wrong.
        problem: String,
    },
    /// No sheet with one degree of freedom moving like the periodic sheet exists in the
    /// region.
    #[error("no one-DOF sheet in this region: {reason}")]
    NoOneDofSheet {
        /// Why not.
        reason: String,
    },
    /// The caller's check stopped the work (see [`crate::stop`]).
    #[error("cancelled")]
    Cancelled,
}

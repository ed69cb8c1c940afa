//! Why a graded sheet could not be made, read or optimised.

use thiserror::Error;

/// A graded-sheet failure, naming the offending values.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum GradedError {
    /// The region is unusable.
    #[error("bad region: {0}")]
    BadRegion(String),
    /// The target cannot be used.
    #[error("bad target: {0}")]
    BadTarget(String),
    /// The target is beyond what the design's sheet can reach (too thin for its tiles, a
    /// field opening past the design's periodic sheet).
    #[error("unreachable target: {0}")]
    Unreachable(String),
    /// A setting is out of range.
    #[error("bad setting: {0}")]
    BadSetting(String),
    /// A sheet read from a file is inconsistent.
    #[error("bad graded sheet: {0}")]
    BadSheet(String),
    /// The design does not open (no deployment to start from).
    #[error("the design cannot be graded: {0}")]
    Design(String),
    /// The sparse factorisation of the normal equations failed.
    #[error("the sparse factorisation of the graded sheet's equations failed")]
    Factorisation,
    /// A residual or a step is NaN or infinite.
    #[error("the optimisation produced a non-finite value")]
    NonFinite,
    /// The caller's check stopped the work (see [`crate::stop`]).
    #[error("cancelled")]
    Cancelled,
}

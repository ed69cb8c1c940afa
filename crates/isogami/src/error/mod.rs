//! The library's error union. Every stage has its own error enum, in its own module, carrying
//! the offending values as typed fields; [`Error`] is the union the entry points of
//! [`api`](crate::api) return and the front ends print. Every message is a single line.

// The settings error lives on the ground floor (`crate::settings_error`), below every stage
// that validates settings; re-exported here for the library's users.
pub use crate::settings_error::{Requirement, SettingValue, SettingsError};

use thiserror::Error;

/// Everything that can go wrong in the pipeline: one variant per stage, each wrapping that
/// stage's error unchanged (its message is the stage error's message).
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// Family name, shape parameters.
    #[error(transparent)]
    Tiling(#[from] crate::tiling::TilingError),
    /// Supercell size, cell geometry.
    #[error(transparent)]
    Cell(#[from] crate::cell::CellError),
    /// Design spec string or JSON, joint list.
    #[error(transparent)]
    Design(#[from] crate::topology::DesignError),
    /// Assembling the mechanism.
    #[error(transparent)]
    Kinematics(#[from] crate::kinematics::KinematicsError),
    /// Mobility analysis.
    #[error(transparent)]
    Mobility(#[from] crate::mobility::MobilityError),
    /// Collision model.
    #[error(transparent)]
    Contact(#[from] crate::contact::ContactError),
    /// Deployment (including cancellation by the caller).
    #[error(transparent)]
    Deploy(#[from] crate::deploy::DeployError),
    /// Frame measures.
    #[error(transparent)]
    Measure(#[from] crate::measure::MeasureError),
    /// Linkage analysis.
    #[error(transparent)]
    Linkage(#[from] crate::linkage::LinkageError),
    /// Topology enumeration.
    #[error(transparent)]
    Explore(#[from] crate::explore::ExploreError),
    /// Inverse design: target, request, stop.
    #[error(transparent)]
    Inverse(#[from] crate::inverse::InverseError),
    /// Shape-aware mobility: classification, moving along the special set.
    #[error(transparent)]
    Shape(#[from] crate::shape_space::ShapeError),
    /// Finite sheets: region, mobility, completion.
    #[error(transparent)]
    Finite(#[from] crate::finite::FiniteError),
    /// Graded sheets: region, target, optimisation.
    #[error(transparent)]
    Graded(#[from] crate::graded::GradedError),
    /// A setting outside its range.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// A file the user named that cannot be read (missing, not a regular file, too large).
    #[error(transparent)]
    Input(#[from] crate::input::InputError),
}

impl Error {
    /// True when the caller's progress callback stopped the run.
    pub fn is_cancelled(&self) -> bool {
        matches!(
            self,
            Error::Deploy(crate::deploy::DeployError::Cancelled)
                | Error::Inverse(crate::inverse::InverseError::Cancelled)
                | Error::Finite(crate::finite::FiniteError::Cancelled)
                | Error::Graded(crate::graded::GradedError::Cancelled)
        )
    }
}

/// Result alias for the library's entry points.
pub type Result<T> = std::result::Result<T, Error>;

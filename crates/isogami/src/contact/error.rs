//! What can go wrong when building or querying a contact model.

use super::inset::InsetProblem;
use crate::math::Real;
use crate::settings_error::SettingsError;
use thiserror::Error;

/// A contact model that cannot be built, or a query it cannot answer.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ContactError {
    /// Kerf, barrier distance or stiffness outside its range.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// A mechanism whose tile shapes or closed state do not fit its tile count.
    #[error("cell geometry check failed: mechanism has {shapes} tile shapes and a closed state of length {rest} for {tiles} tiles")]
    MechanismShape {
        /// Tile shapes.
        shapes: usize,
        /// Length of the closed state.
        rest: usize,
        /// Tiles of the layout.
        tiles: usize,
    },
    /// A mechanism whose closed state has a NaN or infinite entry.
    #[error("numerical failure: mechanism's closed state holds NaN or infinity")]
    NonFiniteRest,
    /// A contact model used with other contact settings than it was built with.
    #[error(
        "invalid setting: contact model built with other contact settings than the deployment's"
    )]
    SettingsMismatch,
    /// A tile whose collision polygon cannot be made: the kerf is too wide for it.
    #[error("cell geometry check failed: tile {tile}: collision polygon inset by kerf/2 = {inset}: {problem} (try a smaller kerf)")]
    Inset {
        /// Tile index.
        tile: usize,
        /// The inset distance, kerf / 2 (units of L).
        inset: Real,
        /// Why the inset fails.
        problem: InsetProblem,
    },
    /// A model used with a mechanism of another tile count.
    #[error("numerical failure: contact model built for {model} tiles used with a mechanism of {mechanism}")]
    MechanismMismatch {
        /// Tiles the model was built for.
        model: usize,
        /// Tiles of the mechanism given.
        mechanism: usize,
    },
    /// A state of the wrong length.
    #[error(
        "numerical failure: state of length {len} for a mechanism with {expected} coordinates"
    )]
    StateLength {
        /// Length given.
        len: usize,
        /// Coordinates of the mechanism.
        expected: usize,
    },
    /// A state with a NaN or infinite entry.
    #[error("numerical failure: state holds NaN or infinity")]
    NonFiniteState,
}

//! Shape-aware mobility (beyond the paper, which screens every topology at its default
//! shape): how a design's one degree of freedom depends on the tile shape.
//!
//! - [`classify`]: generic (one DOF on an open set of shapes) or special (one DOF only on a
//!   sub-manifold), from the DOF at quasi-random nearby shapes; for a special design, its
//!   first-order shape constraints from the pairing of self-stresses and the motion
//!   (`kernel.rs`).
//! - [`follow`]: move one shape parameter to a value and adjust the others so the design
//!   keeps one DOF (continuation along the special set with a Gauss–Newton corrector,
//!   `correct.rs`), so a shape slider can move along a mechanism's family instead of
//!   breaking it.
//! - [`rank_drop`]: search the shapes of a topology that is rigid at its default shape for
//!   one where it gains exactly one DOF; [`search_neighbours`] runs it on the rigid
//!   neighbours of known designs (one joint added or moved) and assesses what it finds.
//!
//! Everything works on the closed state's reduced constraint Jacobian J(p)
//! (`jacobian.rs`) in scaled shape coordinates; the DOF is counted with the mobility
//! analysis's own relative threshold.

mod classify;
mod correct;
mod error;
mod follow;
mod jacobian;
mod kernel;
mod range;
mod rank_drop;
mod search;

pub(crate) use classify::halton_point;
pub use classify::{classify, ShapeClass, ShapeMobility};
pub use error::ShapeError;
pub use follow::{follow, Followed};
pub use jacobian::param_scales;
pub use range::{builds, param_ranges, well_shaped, ParamRange, RANGE_TOL, WINDOW};
pub use rank_drop::{rank_drop, RankDrop};
pub use search::{neighbours, search_neighbours, Finding, SearchReport};

use crate::math::Real;
use crate::mobility::MobilitySettings;
use crate::settings_error::{Requirement, SettingsError};

/// Settings of the shape-space analyses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeSettings {
    /// Half-width of the box of nearby shapes [`classify`] samples, and the largest
    /// continuation step of [`follow`], in units of each parameter's scale.
    pub radius: Real,
    /// Nearby shapes [`classify`] tries.
    pub samples: usize,
    /// Half-width of the box [`rank_drop`] searches (the exploration's sampling span).
    pub search_span: Real,
    /// Nelder–Mead starts of [`rank_drop`] (the default shape first).
    pub search_starts: usize,
    /// Nelder–Mead iterations per start.
    pub search_iterations: usize,
    /// The DOF count's threshold.
    pub mobility: MobilitySettings,
}

impl Default for ShapeSettings {
    fn default() -> Self {
        ShapeSettings {
            radius: 0.02,
            samples: 8,
            search_span: 0.3,
            search_starts: 4,
            search_iterations: 300,
            mobility: MobilitySettings::default(),
        }
    }
}

impl ShapeSettings {
    /// Checks every setting.
    pub fn validate(&self) -> Result<(), ShapeError> {
        let bad = |what: &'static str, value: Real, requirement: Requirement| {
            Err(ShapeError::Library(
                SettingsError::new(what, value, requirement).to_string(),
            ))
        };
        if !(self.radius.is_finite() && self.radius > 0.0 && self.radius <= 0.5) {
            return bad(
                "shape radius",
                self.radius,
                Requirement::Within {
                    low: 0.0,
                    high: 0.5,
                    open_low: true,
                    open_high: false,
                },
            );
        }
        if !(self.search_span.is_finite() && self.search_span > 0.0 && self.search_span <= 1.0) {
            return bad(
                "search span",
                self.search_span,
                Requirement::Within {
                    low: 0.0,
                    high: 1.0,
                    open_low: true,
                    open_high: false,
                },
            );
        }
        if !(1..=1000).contains(&self.samples) {
            return bad(
                "shape samples",
                self.samples as Real,
                Requirement::CountIn { low: 1, high: 1000 },
            );
        }
        self.mobility
            .validate()
            .map_err(|e| ShapeError::Library(e.to_string()))
    }
}

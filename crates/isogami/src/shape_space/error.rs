//! Errors of shape-aware mobility. Every message is one line.

use crate::math::Real;
use thiserror::Error;

/// What went wrong analysing or moving a design over its shape space.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ShapeError {
    /// The design does not have exactly one degree of freedom at its own shape.
    #[error("shape space: the design has {dof} degrees of freedom at its shape, not 1")]
    NotOneDof {
        /// Degrees of freedom found.
        dof: usize,
    },
    /// A parameter index outside the family's parameters.
    #[error("shape space: parameter {index} does not exist (the family has {count})")]
    NoSuchParameter {
        /// Index asked for.
        index: usize,
        /// Parameters of the family.
        count: usize,
    },
    /// A target value that is not a finite number.
    #[error("shape space: parameter value {value} is not a finite number")]
    NotFinite {
        /// The value given.
        value: Real,
    },
    /// The parameter cannot change while the design keeps one degree of freedom: every
    /// first-order shape constraint fixes it.
    #[error("shape space: parameter {index} is fixed by the shape constraints that keep one degree of freedom")]
    Pinned {
        /// The parameter.
        index: usize,
    },
    /// The path along the shape constraints left the well-shaped tiles.
    #[error("shape space: following the constraints to parameter {index} = {value} leaves the well-shaped tiles ({problem})")]
    LeavesShapes {
        /// The parameter moved.
        index: usize,
        /// Where it was going.
        value: Real,
        /// What is wrong with the tile there.
        problem: String,
    },
    /// The corrector could not return to the set of shapes with one degree of freedom.
    #[error("shape space: could not stay on the shapes with one degree of freedom near parameter {index} = {value} (residual {residual:.1e})")]
    Lost {
        /// The parameter moved.
        index: usize,
        /// Where the step was going.
        value: Real,
        /// Smallest eigenvalue ratio reached.
        residual: Real,
    },
    /// The library failed building a nearby design (a shape that gives no tiling, a
    /// mechanism that cannot be assembled, an eigen-solver without convergence).
    #[error("shape space: {0}")]
    Library(String),
}

impl From<crate::Error> for ShapeError {
    fn from(e: crate::Error) -> Self {
        ShapeError::Library(e.to_string())
    }
}

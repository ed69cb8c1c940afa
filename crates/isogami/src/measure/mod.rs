//! Expansion measures of a deploying sheet (paper §4.3).
//!
//! What it is for: turning states of a deployment into the numbers a user filters and sorts
//! designs by. The macroscopic deformation gradient F maps the closed-state tiling vectors to
//! the current ones, [u w] = F [ū w̄]; its polar decomposition F = RU gives the right stretch
//! tensor U, whose directional expansion ε(θ) = dᵀ(U − I)d (d = (cos θ, sin θ)) has the
//! principal expansions (eigenvalues of U − I) as extremes. Per frame we also report the area
//! ratio det F and tile rotations; over a whole trajectory, a [`BehaviourClass`].
//!
//! What it must not do: no I/O, no rendering, no solving. Every function is a pure function of
//! the numbers it is given; invalid input (non-finite values, a degenerate closed lattice, an
//! inverted lattice with det F ≤ 0) is an [`MeasureError`], never
//! a NaN in the output.

mod classify;
mod error;
mod frame;
mod strain;

pub use classify::{
    classify, classify_expansions, classify_with, BehaviourClass, BehaviourFigures, Classification,
    ClassifyTolerances, OPEN_FRACTION,
};
pub use error::MeasureError;
pub use frame::FrameMeasures;
pub use strain::{
    area_ratio, deformation_gradient, directional_expansion, effective_poisson_ratio,
    expansion_profile, polar, principal_direction, principal_expansions, ISOTROPIC_STRETCH_TOL,
};

//! Isohedral tiling families (IH1…IH93, Kaplan's numbering) and validated tilings.
//!
//! Wraps the `tactile` crate's tables: prototile vertices, aspect transforms, translation
//! vectors and edge shapes, converted at the boundary to this crate's types. Never uses the
//! crate's `fill_region` iterator (it can loop forever on degenerate boxes); cells are built
//! from aspects and translation vectors in `cell`. No I/O.

mod canonical;
mod describe;
mod error;
mod family;
mod sampling;
mod shape;

pub use canonical::{canonical_param, canonical_params, is_canonical, CANONICAL_DIGITS};
pub use describe::{param_effects, ParamEffect};
pub use error::{Culprit, ShapeProblem, TilingError};
pub use family::{EdgeShapeKind, Family, FamilyInfo, PrototileEdge};
pub use sampling::{
    param_ranges, shape_grid, shape_quality_problem, MIN_ANGLE_DEG, MIN_EDGE_RATIO, MIN_ROUNDNESS,
};
pub use shape::{Affine, Tiling};

//! isogami: rigid-deployable kirigami sheets from isohedral tilings.
//!
//! The pipeline, one module per stage, data flowing one way:
//! [`tiling`] (family + shape parameters) → [`cell`] (unit cell / supercell, tiles, unique
//! edges with cell offsets, tiling vectors) → [`topology`] (a joint choice per edge, design
//! specs) → [`kinematics`] (rigid tiles + pin joints + periodic lattice: residuals,
//! Jacobian, Hessian) → [`mobility`] (spectrum of H = JᵀJ, degrees of freedom, motion).
//! [`render`] turns results into SVG text; [`export`] lays out a patch of the sheet in mm
//! and writes it in fabrication and interchange formats (as text). The library does no I/O: front ends read and write.
//!
//! Front ends call the entry points of [`api`]: one function per job (resolve a design,
//! analyse, deploy, linkages, compare), plain data in and out. [`inverse`] goes the other
//! way: from a target behaviour to designs that have it.

pub mod api;
pub mod catalog;
pub mod cell;
pub mod contact;
pub mod deploy;
mod disjoint_sets;
pub mod error;
pub mod explore;
pub mod export;
pub mod finite;
pub mod geometry;
pub mod graded;
pub mod input;
pub mod inverse;
pub mod kinematics;
pub mod linkage;
pub mod math;
pub mod measure;
pub mod mobility;
pub mod render;
pub mod settings_error;
pub mod shape_space;
pub mod stop;
#[cfg(test)]
mod test_rng;
pub mod tiling;
pub mod topology;

pub use error::{Error, Result};

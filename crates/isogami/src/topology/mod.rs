//! Joint topologies: a joint choice per unique edge of a cell, and whole designs (family,
//! shape parameters, supercell, joints) with a compact spec string that round-trips exactly,
//! a JSON form, and a few named classic designs. Parsing only; no geometry beyond building the
//! cell a design names.

mod design;
mod error;
mod json;
mod legacy;
mod named;
mod spec;

pub use design::{Design, JointChoice};
pub use error::DesignError;
pub use json::{DesignJson, JointJson};
pub use legacy::{MigratedSpec, SpecLabels};
pub use named::{named_design, NAMED_DESIGNS, SAMPLE_OPENING_DESIGNS};
pub(crate) use spec::truncate as quote_input;

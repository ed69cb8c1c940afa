//! Fabrication exports of a patch of tiles in millimetres.
//!
//! [`laser`]: laser-cutting sheets (SVG and DXF) with hinge bridges and kerf compensation.

pub mod laser;

//! The integration tests of `isogami`, one test binary: every file here is a module (one
//! link instead of one per file; `cargo test -p isogami --test it MODULE::` runs one).

mod behaviour_stability;
mod catalog;
mod catalog_finite;
mod catalog_parts;
mod cells;
mod common;
mod compare;
mod contact;
mod deploy;
mod deploy_summaries;
mod edge_labels;
mod explore_parallel;
mod explore_screen;
mod explore_topology;
mod export;
mod finite_deploy;
mod finite_scale;
mod finite_sheets;
mod inverse;
#[cfg(feature = "render")] // rasterises with resvg
mod laser_export;
mod lattice_contact;
mod linkage;
mod margins;
#[cfg(feature = "render")] // plots with plotters
mod measures_render;
mod mobility;
mod motion_classes;
mod opening_sign;
mod prop_inputs;
mod shape_space;
mod specs;

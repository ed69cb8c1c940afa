//! The integration tests of `isogami-web`, one test binary: every file here is a module (one
//! link instead of one per file; `cargo test -p isogami-web --test it MODULE::` runs one).

mod api_catalogue;
mod api_design;
mod api_export;
mod api_graded;
mod api_inverse;
mod api_limits;
mod api_motions;
mod api_safety;
mod api_server;
mod api_shape;
mod api_sheet;
mod common;
mod site;

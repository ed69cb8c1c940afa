//! The integration tests of `isogami-cli`, one test binary: every file here is a module (one
//! link instead of one per file; `cargo test -p isogami-cli --test it MODULE::` runs one).

mod cli;
mod cli_errors;
mod cli_output;
mod cli_props;
mod common;
mod compare_cli;
mod db_concurrency;
mod db_safety;
mod explore;
mod explore_cap;
mod export_cli;
mod export_laser_cli;
mod export_print_cli;
mod graded_cli;
mod graded_export;
mod graded_svg_cli;
mod hostile_inputs_cli;
mod inverse_checks;
mod inverse_cli;
mod serve_cli;
mod shape_cli;
mod sheet_cli;
mod unit_parts;

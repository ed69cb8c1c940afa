//! One module per subcommand.

pub mod analyze;
pub mod cell;
pub mod compare;
pub mod db;
pub mod db_designs;
pub mod deploy;
pub mod explore;
pub mod export;
pub mod families;
pub mod graded;
pub mod inverse;
pub mod laser_args;
pub mod linkages;
pub(crate) mod margins_text;
pub mod migrate_spec;
pub mod print_args;
pub mod serve;
pub mod shape;
pub mod sheet;

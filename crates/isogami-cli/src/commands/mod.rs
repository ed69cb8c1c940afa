//! One module per subcommand.

pub mod analyze;
pub mod cell;
pub mod compare;
pub mod deploy;
pub mod families;

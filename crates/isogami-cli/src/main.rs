//! `isogami`: the command line. Parses arguments, calls the library, prints or writes the
//! results. No pipeline logic lives here.
//!
//! Exit codes: 0 on success (and for `--help`, `--version`), 2 on any error, reported as one
//! line on stderr (`error: …`), usage errors with a hint naming the help to read.

#[macro_use]
mod output;
mod commands;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Rigid-deployable kirigami sheets from isohedral tilings.
#[derive(Debug, Parser)]
#[command(name = "isogami", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// List the 81 isohedral tiling families.
    Families(commands::families::Args),
    /// Build a unit cell or supercell and show its tiles, edges and tiling vectors.
    Cell(commands::cell::Args),
    /// Mobility analysis of a design: degrees of freedom, spectrum, first-order motion.
    Analyze(commands::analyze::Args),
    /// Deploy a design from its closed state to the contact limit.
    Deploy(commands::deploy::Args),
    /// Compare rigid modes with the spring and NCM baselines (paper Fig. 4).
    Compare(commands::compare::Args),
    /// Linkage analysis of a design: signature, linkages, tile degrees, SVG.
    Linkages(commands::linkages::Args),
    /// Explore the design space into the design database (resumable, shardable).
    Explore(commands::explore::Args),
    /// Export a patch of a design in mm: laser SVG/DXF, 3D-print STL/3MF, FOLD, OBJ, tile
    /// tables, kirigami_sim.
    Export(Box<commands::export::Args>),
    /// Inverse design: screen the database for a target behaviour and refine the best
    /// designs' tile shapes.
    Inverse(commands::inverse::Args),
    /// Shape-aware mobility: generic or special, the shape constraints that keep one DOF,
    /// moving a parameter along them, rank-dropping shapes of rigid designs.
    Shape(commands::shape::Args),
    /// A finite region of a design: degrees of freedom with a free boundary, the floppy
    /// tiles, and its completion to a sheet that opens with the design's one motion.
    Sheet(commands::sheet::Args),
    /// A graded sheet: a finite sheet whose tiles each get their own shape so that it opens
    /// into a target outline (disc, ellipse, polygon), checked to open along one motion.
    Graded(commands::graded::Args),
    /// Carry specs into today's edge labels: read as written today (printed back unchanged,
    /// canonical) or, with --legacy, as written before issue 21 (shape-dependent labels; the
    /// same physical joints in today's labels). Ambiguous texts are named on stderr.
    MigrateSpec(commands::migrate_spec::Args),
    /// Serve the material browser over the design database (runs the quick exploration
    /// first when the database does not exist).
    Serve(commands::serve::ServeArgs),
    /// Write the catalogue as a static site.
    Site(commands::serve::SiteArgs),
    /// Merge shard databases into one.
    Merge(commands::db::MergeArgs),
    /// Inspect a design database.
    Db {
        #[command(subcommand)]
        command: commands::db::DbCommand,
    },
}

fn main() -> ExitCode {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    let cli = match Cli::try_parse_from(&args) {
        Ok(cli) => cli,
        Err(e) => return output::usage::report(&e, &args),
    };
    let result = match cli.command {
        Command::Families(a) => commands::families::run(a),
        Command::Cell(a) => commands::cell::run(a),
        Command::Analyze(a) => commands::analyze::run(a),
        Command::Deploy(a) => commands::deploy::run(a),
        Command::Compare(a) => commands::compare::run(a),
        Command::Explore(a) => commands::explore::run(a),
        Command::Linkages(a) => commands::linkages::run(a),
        Command::Export(a) => commands::export::run(*a),
        Command::Inverse(a) => commands::inverse::run(a),
        Command::Shape(a) => commands::shape::run(a),
        Command::Sheet(a) => commands::sheet::run(a),
        Command::Graded(a) => commands::graded::run(a),
        Command::MigrateSpec(a) => commands::migrate_spec::run(a),
        Command::Serve(a) => commands::serve::serve(a),
        Command::Site(a) => commands::serve::site(a),
        Command::Merge(a) => commands::db::merge(a),
        Command::Db { command } => commands::db::run(command),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!(
                "error: {}",
                isogami::input::clip_echo(&output::usage::one_line(&e))
            );
            ExitCode::from(2)
        }
    }
}

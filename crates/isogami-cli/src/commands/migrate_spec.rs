//! `isogami migrate-spec`: specs written before issue 21 in the current edge labels.

use crate::output::{emit, print_json, CliResult};
use isogami::topology::Design;
use serde::Serialize;

/// Arguments of `migrate-spec`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Specs as isogami wrote them before issue 21 (edge labels then depended on the exact
    /// shape; the same physical joints may have other labels now).
    #[arg(required = true)]
    specs: Vec<String>,
    /// Print JSON: a list of {old, new, changed}.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Migrated {
    old: String,
    new: String,
    /// True when the joint string or the number form changed.
    changed: bool,
}

/// Prints each old spec's current spec (the same physical joints, canonical numbers), one per
/// line; the first spec that cannot be read stops it with its error.
pub fn run(args: Args) -> CliResult {
    let mut out = Vec::with_capacity(args.specs.len());
    for old in &args.specs {
        let design = Design::from_legacy_spec(old).map_err(|e| format!("'{old}': {e}"))?;
        let new = design.to_string();
        out.push(Migrated {
            changed: new != old.trim(),
            old: old.trim().to_string(),
            new,
        });
    }
    if args.json {
        return print_json(&out);
    }
    emit(
        &out.iter()
            .map(|m| format!("{}\n", m.new))
            .collect::<String>(),
    )
}

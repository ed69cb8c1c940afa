//! `isogami migrate-spec`: specs carried into today's edge labels, reading each in the labels
//! it was written in (today's unless `--legacy`), and saying when a text is ambiguous.

use crate::output::{emit, print_json, CliResult};
use isogami::topology::{Design, SpecLabels};
use serde::Serialize;

/// Arguments of `migrate-spec`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Specs (or names, or design JSON).
    #[arg(required = true)]
    specs: Vec<String>,
    /// The specs were written by isogami before issue 21, whose edge labels depended on the
    /// exact shape: translate their joints (the same physical joints in today's labels).
    /// Without it the specs are read as written today and printed back canonical, unchanged
    /// (a spec carries no mark of its labels; a note on stderr names the other reading when
    /// the text is ambiguous).
    #[arg(long)]
    legacy: bool,
    /// Print JSON: a list of {old, new, changed, other_reading}.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Migrated {
    old: String,
    new: String,
    /// True when the joint string or the number form changed.
    changed: bool,
    /// The design the text names in the other labels, when that is another one.
    #[serde(skip_serializing_if = "Option::is_none")]
    other_reading: Option<String>,
}

/// Prints each spec's current spec (the same physical joints, canonical numbers), one per line;
/// the first spec that cannot be read stops it with its error.
pub fn run(args: Args) -> CliResult {
    let labels = if args.legacy {
        SpecLabels::BeforeRelabelling
    } else {
        SpecLabels::Current
    };
    let mut out = Vec::with_capacity(args.specs.len());
    for old in &args.specs {
        let m = Design::migrate_spec(old, labels).map_err(|e| format!("'{old}': {e}"))?;
        let new = m.design.to_string();
        out.push(Migrated {
            changed: new != old.trim(),
            old: old.trim().to_string(),
            new,
            other_reading: m.other_reading.map(|d| d.to_string()),
        });
    }
    if !args.json {
        for m in &out {
            if let Some(other) = &m.other_reading {
                let (read, other_labels) = if args.legacy {
                    ("the labels of isogami before issue 21", "today's labels")
                } else {
                    (
                        "today's labels",
                        "the labels of isogami before issue 21 (--legacy)",
                    )
                };
                eprintln!(
                    "note: '{}' read in {read}; in {other_labels} it names another design, {other}",
                    m.old
                );
            }
        }
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

//! `isogami compare`: the baseline comparison of paper §5 / Fig. 4.

use crate::output::{emit, print_json, CliResult};
use isogami::contact::ContactSettings;
use isogami::deploy::{compare_methods, DeploySettings, MethodResult};
use isogami::kinematics::Mechanism;
use isogami::topology::Design;

/// Designs compared when none are given: rotating squares and two designs whose motion
/// turns away from its initial eigenvector.
fn default_designs() -> &'static [&'static str] {
    &isogami::topology::SAMPLE_OPENING_DESIGNS[..3]
}

/// Arguments of `compare`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Designs to compare (repeatable); default: a built-in set of turning designs.
    #[arg(long, allow_hyphen_values = true)]
    design: Vec<String>,
    /// Cut width relative to the mean edge length.
    #[arg(long, default_value_t = ContactSettings::default().kerf, allow_hyphen_values = true)]
    kerf: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

#[derive(serde::Serialize)]
struct Row {
    design: String,
    results: Vec<MethodResult>,
}

/// Runs rigid modes, NCM and springs on each design and prints the final t of each, measured
/// along the rigid-modes trajectory (1 = its contact limit).
pub fn run(args: Args) -> CliResult {
    let settings = DeploySettings {
        contact: ContactSettings::with_kerf(args.kerf),
        ..DeploySettings::default()
    };
    settings.validate().map_err(|e| e.to_string())?;
    let specs: Vec<String> = if args.design.is_empty() {
        default_designs().iter().map(|s| s.to_string()).collect()
    } else {
        args.design.clone()
    };
    let mut rows = Vec::new();
    for spec in &specs {
        let design = Design::resolve(spec).map_err(|e| e.to_string())?;
        let cell = design.cell().map_err(|e| e.to_string())?;
        let mech = Mechanism::new(&cell, &design.joints).map_err(|e| e.to_string())?;
        let results = compare_methods(&mech, &settings).map_err(|e| format!("{spec}: {e}"))?;
        rows.push(Row {
            design: design.to_string(),
            results,
        });
    }
    if args.json {
        return print_json(&rows);
    }
    let mut o = String::new();
    outln!(
        o,
        "final t of each method along the rigid-modes trajectory (1 = contact limit)"
    );
    for row in &rows {
        outln!(o, "{}", row.design);
        for r in &row.results {
            outln!(
                o,
                "  {:<12} t = {:.3}  ({}, {} states, {:.1} ms)",
                r.method.to_string(),
                r.final_t,
                r.end_reason,
                r.steps,
                r.millis
            );
        }
    }
    emit(&o)
}

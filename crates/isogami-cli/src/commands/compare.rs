//! `isogami compare`: the baseline comparison of paper §5 / Fig. 4. The library runs and
//! measures; this command only prints the table or the JSON.

use crate::output::{emit, print_json, CliResult};
use isogami::api::{compare, resolve_design};
use isogami::contact::ContactSettings;
use isogami::deploy::{DeploySettings, COMPARISON_DESIGNS};

/// Arguments of `compare`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Designs to compare (repeatable); default: a built-in set on which the methods differ.
    #[arg(long, allow_hyphen_values = true)]
    design: Vec<String>,
    /// Cut width relative to the mean edge length.
    #[arg(long, default_value_t = ContactSettings::default().kerf, allow_hyphen_values = true)]
    kerf: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Runs rigid modes, NCM and springs on each design and prints, per method, how far it got
/// along the rigid-modes path and how much it opened.
pub fn run(args: Args) -> CliResult {
    let settings = DeploySettings {
        contact: ContactSettings::with_kerf(args.kerf),
        ..DeploySettings::default()
    };
    settings.validate().map_err(|e| e.to_string())?;
    let specs: Vec<String> = if args.design.is_empty() {
        COMPARISON_DESIGNS.iter().map(|s| s.to_string()).collect()
    } else {
        args.design.clone()
    };
    // Resolve every design before running any, so a typo fails at once.
    let designs = specs
        .iter()
        .map(|spec| resolve_design(spec).map_err(|e| e.to_string()))
        .collect::<Result<Vec<_>, _>>()?;
    let mut rows = Vec::new();
    for (spec, design) in specs.iter().zip(&designs) {
        rows.push(compare(design, &settings).map_err(|e| format!("{spec}: {e}"))?);
    }
    if args.json {
        return print_json(&rows);
    }
    let mut o = String::new();
    outln!(
        o,
        "t      last state along the rigid-modes path (1 = its contact limit)"
    );
    outln!(
        o,
        "off    its distance from that path (state space: edge lengths and radians)"
    );
    outln!(
        o,
        "area   largest det F, the t where it was reached, and det F at the end"
    );
    outln!(
        o,
        "e      largest and smallest principal expansion; rot: largest tile rotation (deg)"
    );
    outln!(
        o,
        "peak   whether the rigid-modes path's largest area was reached (within 1 %)"
    );
    for row in &rows {
        outln!(o, "");
        outln!(o, "{}  ({} DOF)", row.design, row.dof);
        outln!(
            o,
            "  {:<12} {:>5} {:>6} {:>8} {:>6} {:>8} {:>7} {:>7} {:>6} {:>5}  {:<20} {:>6} {:>8}",
            "method",
            "t",
            "off",
            "area",
            "at t",
            "last",
            "e max",
            "e min",
            "rot",
            "peak",
            "end",
            "states",
            "ms"
        );
        for r in &row.results {
            outln!(
                o,
                "  {:<12} {:>5.3} {:>6.3} {:>8.3} {:>6.3} {:>8.3} {:>7.3} {:>7.3} {:>6.1} {:>5}  {:<20} {:>6} {:>8.1}",
                r.method.to_string(),
                r.final_t,
                r.path_distance,
                r.max_area_ratio,
                r.max_area_t,
                r.final_area_ratio,
                r.max_expansion,
                r.min_expansion,
                r.max_tile_rotation.to_degrees(),
                if r.reached_peak_area { "yes" } else { "no" },
                r.end_reason.to_string(),
                r.steps,
                r.millis
            );
        }
    }
    emit(&o)
}

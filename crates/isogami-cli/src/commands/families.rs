//! `isogami families`.

use crate::output::{emit, print_json, CliResult};
use isogami::tiling::Family;

/// Arguments of `families`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// Lists every family with its parameter count, defaults, vertex and aspect counts and edge
/// shapes.
pub fn run(args: Args) -> CliResult {
    let infos: Vec<_> = Family::all().map(|f| f.info()).collect();
    if args.json {
        return print_json(&infos);
    }
    let mut o = String::new();
    outln!(
        o,
        "{:<6} {:>6} {:>8} {:>7}  {:<28} default parameters",
        "family",
        "params",
        "vertices",
        "aspects",
        "edge shapes"
    );
    for i in &infos {
        let shapes: Vec<String> = i
            .edges
            .iter()
            .map(|e| {
                format!(
                    "{:?}{}{}",
                    e.kind,
                    e.shape_id,
                    if e.reversed { "'" } else { "" }
                )
            })
            .collect();
        let params: Vec<String> = i.default_params.iter().map(|p| format!("{p:.6}")).collect();
        outln!(
            o,
            "{:<6} {:>6} {:>8} {:>7}  {:<28} [{}]",
            i.name,
            i.param_count,
            i.vertex_count,
            i.aspect_count,
            shapes.join(" "),
            params.join(", ")
        );
    }
    outln!(
        o,
        "{} families. Edge shapes: kind + shape id (' = reversed).",
        infos.len()
    );
    emit(&o)
}

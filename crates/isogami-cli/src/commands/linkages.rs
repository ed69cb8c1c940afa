//! `isogami linkages`.

use crate::output::{emit, print_json, write_atomic, CliResult};
use isogami::api::{linkages, resolve_design};
use isogami::linkage::{FaceIssue, Node};
use isogami::render::linkage_svg;
use std::path::PathBuf;

/// Arguments of `linkages`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The design: a name (rotating-squares), a spec string, or design JSON.
    #[arg(long, allow_hyphen_values = true)]
    design: String,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write an SVG of the 3×3 patch with the linkages coloured by bar count.
    #[arg(long)]
    svg: Option<PathBuf>,
}

/// Prints the linkage signature, the linkages and the tile degrees of a design.
pub fn run(args: Args) -> CliResult {
    let design = resolve_design(&args.design).map_err(|e| e.to_string())?;
    let a = linkages(&design).map_err(|e| e.to_string())?;
    let cell = design.cell().map_err(|e| e.to_string())?;
    if let Some(path) = &args.svg {
        write_atomic(path, linkage_svg(&cell, &design.joints, &a).as_bytes())?;
    }
    if args.json {
        return print_json(&a);
    }
    let mut o = String::new();
    outln!(o, "design      {design}");
    outln!(o, "signature   {}", a.signature);
    let degrees: Vec<String> = a
        .degree_histogram
        .iter()
        .map(|(d, n)| format!("{n} of degree {d}"))
        .collect();
    outln!(o, "tiles       {}", degrees.join(", "));
    for l in &a.linkages {
        outln!(o, "{:>2}-bar      {}", l.bars, nodes_text(&l.nodes, " – "));
    }
    for f in &a.other_faces {
        let why = match f.issue {
            FaceIssue::RepeatedTile => "not a linkage (boundary repeats a tile)",
            FaceIssue::Chord => "not a linkage (boundary has a chord)",
            FaceIssue::SinglePoint => "not a linkage (tiles share one pin)",
            FaceIssue::Unbounded => "unbounded face",
        };
        outln!(o, "{why}: {}", nodes_text(&f.nodes, " "));
    }
    if let Some(p) = &args.svg {
        outln!(o, "wrote {}", p.display());
    }
    emit(&o)
}

/// Tiles as T<index>@(k_u,k_w).
fn nodes_text(nodes: &[Node], sep: &str) -> String {
    nodes
        .iter()
        .map(|n| format!("T{}@({},{})", n.0, n.1[0], n.1[1]))
        .collect::<Vec<_>>()
        .join(sep)
}

//! `isogami sheet`: a finite region of a design, its degrees of freedom with a free boundary
//! and its completion to a sheet that opens with the design's one motion.

use crate::output::{emit, print_json, CliResult};
use isogami::api::{finite_sheet, resolve_design, SheetRequest};
use isogami::finite::{FiniteSheet, Region, SheetMobility};

/// Arguments of `sheet`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The design: a name, a spec string FAMILY:PARAMS:CELL:JOINTS, or design JSON.
    #[arg(long, allow_hyphen_values = true)]
    design: String,
    /// The region: RxC cells (e.g. 6x6), or in mm rect:W,H, disc:R, polygon:x,y;x,y;…
    /// (centred on cell [0, 0]).
    #[arg(long, default_value = "6x6")]
    region: Region,
    /// Mean edge length in mm (the scale of a region in mm).
    #[arg(long, default_value_t = 20.0)]
    edge_mm: f64,
    /// The periodic state the degrees of freedom are counted at: the accepted state nearest
    /// this t in (0, 1] (the closed state, a singular configuration, is counted separately).
    #[arg(long, default_value_t = 0.3)]
    t: f64,
    /// Smallest share of the region's area, in percent, that the completed sheet must keep
    /// (below it the completion is refused; 0 accepts any one-DOF sheet, even one loop).
    #[arg(long, default_value_t = 50.0)]
    min_cover: f64,
    /// Only the raw region: no completion.
    #[arg(long)]
    raw: bool,
    /// Print JSON (the sheets' tiles as cell and tile index, the mobility, the completion).
    #[arg(long)]
    json: bool,
}

/// Runs the finite-sheet analysis of one design.
pub fn run(args: Args) -> CliResult {
    let design = resolve_design(&args.design).map_err(|e| e.to_string())?;
    let request = SheetRequest {
        region: args.region.clone(),
        edge_mm: args.edge_mm,
        t: args.t,
        complete: !args.raw,
        min_covered: args.min_cover / 100.0,
        ..SheetRequest::default()
    };
    let out = finite_sheet(&design, &request, &mut |_| true).map_err(|e| e.to_string())?;
    if args.json {
        return print_json(&out);
    }
    let mut o = String::new();
    outln!(o, "design      {}", out.design);
    outln!(
        o,
        "region      {}: {} tiles, {} pins (counted at t = {:.3} of the periodic motion)",
        out.region,
        out.raw.len(),
        out.raw.joints.len(),
        out.t
    );
    outln!(
        o,
        "raw         {}; closed state {} DOF",
        dof_words(&out.raw_mobility),
        out.raw_closed_dof
    );
    describe_floppy(&mut o, &out.raw, &out.raw_mobility);
    if let Some(c) = &out.completion {
        let r = &c.report;
        outln!(
            o,
            "completed   {}; closed state {} DOF",
            dof_words(&c.mobility),
            out.completed_closed_dof.unwrap_or(0)
        );
        outln!(
            o,
            "            {} of {} requested tiles kept ({:.1} % of their area), {} removed, {} added{}",
            r.kept,
            r.requested,
            100.0 * r.covered_fraction,
            r.removed.len(),
            r.added.len(),
            if r.grown {
                " (grown by the surrounding ring, then pruned)"
            } else {
                " (pruned)"
            }
        );
    }
    emit(&o)
}

/// "1 DOF ✓" or "N DOF: M extra modes, K loose tiles".
fn dof_words(m: &SheetMobility) -> String {
    let pieces = if m.pieces > 1 {
        format!(", {} pieces", m.pieces)
    } else {
        String::new()
    };
    if m.dof == 1 && m.floppy.is_empty() && m.follows_periodic {
        format!("1 DOF, the periodic motion{pieces}")
    } else {
        format!(
            "{} DOF: {} extra modes, {} tiles held by fewer than two pins{}",
            m.dof,
            m.floppy.len(),
            m.loose_tiles.len(),
            pieces
        )
    }
}

/// One line per extra mode (at most ten), naming its moving tiles as cell/tile.
fn describe_floppy(o: &mut String, sheet: &FiniteSheet, m: &SheetMobility) {
    for (k, mode) in m.floppy.iter().take(10).enumerate() {
        let names: Vec<String> = mode
            .tiles
            .iter()
            .take(8)
            .map(|&t| {
                let s = sheet.tiles[t];
                format!("[{},{}]#{}", s.cell[0], s.cell[1], s.tile)
            })
            .collect();
        let more = mode.tiles.len().saturating_sub(8);
        outln!(
            o,
            "  mode {:<3}  {} tiles move: {}{}",
            k + 1,
            mode.tiles.len(),
            names.join(" "),
            if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            }
        );
    }
    if m.floppy.len() > 10 {
        outln!(o, "  … and {} more modes", m.floppy.len() - 10);
    }
}

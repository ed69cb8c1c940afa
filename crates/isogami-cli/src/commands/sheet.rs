//! `isogami sheet`: a finite region of a design, its degrees of freedom with a free boundary
//! and its completion to a sheet that opens with the design's one motion.

use crate::output::{emit, print_json, CliResult};
use isogami::api::{
    deploy_sheet, finite_sheet, pull_sheet, resolve_design, SheetAnalysis, SheetDeployRequest,
    SheetDeployment, SheetPull, SheetPullRequest, SheetRequest,
};
use isogami::finite::{FiniteError, FiniteSheet, Region, SheetMobility, SingularState};

/// Arguments of `sheet`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("motion").args(["deploy", "pull"])))]
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
    /// Deploy the (completed) sheet with contact among its own tiles to its contact limit,
    /// and compare it with the periodic sheet. A raw region deploys only when it is one-DOF.
    #[arg(long)]
    deploy: bool,
    /// Pull the sheet apart by two of its tiles, as a tester would (one held, the other
    /// pulled away along the direction the design opens most), with contact among its own
    /// tiles, and say how far its tiles leave the periodic motion. Works on a floppy raw
    /// region (with --raw): its extra modes show.
    #[arg(long, conflicts_with = "deploy")]
    pull: bool,
    /// With --pull: the held and the pulled tile, as indices into the sheet's tiles
    /// (the JSON's order) [default: the ends of the sheet along its opening direction].
    #[arg(long, value_parser = parse_grips, requires = "pull")]
    grips: Option<[usize; 2]>,
    /// Frames of tile poses in the JSON of --deploy and --pull (at least 2).
    #[arg(long, default_value_t = 24, requires = "motion")]
    frames: usize,
    /// Print JSON (the sheets' tiles as cell and tile index, the mobility, the completion).
    #[arg(long)]
    json: bool,
}

/// Runs the finite-sheet analysis of one design. With --json, a refused completion (or a
/// sheet that cannot deploy or be pulled) still prints the raw region's analysis before the
/// refusal's one line; the text report refuses at once (counting alone refuses an isostatic
/// cell's region before any factorisation), and --raw shows the region.
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
    // Why the motion asked for did not run, when the sheet has no one-DOF form.
    let mut refused: Option<String> = None;
    let deployment = if args.deploy {
        let request = SheetDeployRequest {
            sheet: request.clone(),
            frames: args.frames,
            ..SheetDeployRequest::default()
        };
        match deploy_sheet(&design, &request, &mut |_| true) {
            Ok(d) => Some(d),
            Err(e) => refusal(e, args.json, &mut refused)?,
        }
    } else {
        None
    };
    let pull = if args.pull {
        let request = SheetPullRequest {
            sheet: request.clone(),
            grips: args.grips,
            frames: args.frames,
        };
        match pull_sheet(&design, &request, &mut |_| true) {
            Ok(p) => Some(p),
            Err(e) => refusal(e, args.json, &mut refused)?,
        }
    } else {
        None
    };
    let out: SheetAnalysis = match (&deployment, &pull) {
        (Some(d), _) if args.json => return print_json(d),
        (_, Some(p)) if args.json => return print_json(p),
        (Some(d), _) => d.analysis.clone(),
        (_, Some(p)) => p.analysis.clone(),
        _ => {
            let request = SheetRequest {
                keep_raw_on_refusal: args.json,
                ..request
            };
            finite_sheet(&design, &request, &mut |_| true).map_err(|e| e.to_string())?
        }
    };
    let refused = refused.or_else(|| out.refusal.clone());
    if args.json {
        print_json(&out)?;
        return refused.map_or(Ok(()), Err);
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
    if let Some(d) = &deployment {
        describe_deployment(&mut o, d);
    }
    if let Some(p) = &pull {
        describe_pull(&mut o, p);
    }
    emit(&o)?;
    refused.map_or(Ok(()), Err)
}

/// No result, with the reason kept, when `e` says the sheet has no one-DOF form and the raw
/// analysis is to be printed (`keep`); else `e`.
fn refusal<T>(
    e: isogami::Error,
    keep: bool,
    refused: &mut Option<String>,
) -> Result<Option<T>, String> {
    match e {
        isogami::Error::Finite(FiniteError::NoOneDofSheet { .. }) if keep => {
            *refused = Some(e.to_string());
            Ok(None)
        }
        e => Err(e.to_string()),
    }
}

/// `A,B`: two tile indices.
fn parse_grips(text: &str) -> Result<[usize; 2], String> {
    let bad = || format!("'{text}': expected two tile indices A,B");
    let (a, b) = text.split_once(',').ok_or_else(bad)?;
    let a = a.trim().parse().map_err(|_| bad())?;
    let b = b.trim().parse().map_err(|_| bad())?;
    Ok([a, b])
}

/// What the pull did, against the periodic motion.
fn describe_pull(o: &mut String, p: &SheetPull) {
    let sheet = p.analysis.sheet();
    let name = |t: usize| {
        let s = sheet.tiles[t];
        format!("{t} ([{},{}]#{})", s.cell[0], s.cell[1], s.tile)
    };
    outln!(
        o,
        "pulled      held tile {}, pulled tile {}: {} after {} states, grips ×{:.4} apart, hull area ×{:.4} (largest ×{:.4})",
        name(p.grips[0]),
        name(p.grips[1]),
        p.end_reason,
        p.steps,
        p.extension,
        p.end.hull_area_ratio,
        p.max_hull_area_ratio
    );
    if p.leaving.is_empty() {
        outln!(
            o,
            "            every tile follows the periodic motion (to {:.1e} L)",
            p.max_deviation
        );
    } else {
        outln!(
            o,
            "            {} of {} tiles leave the periodic motion (by up to {:.3} L)",
            p.leaving.len(),
            sheet.len(),
            p.max_deviation
        );
    }
    if let Some(l) = &p.leaves {
        let why = if p.dof > 1 {
            format!("through its {} extra modes", p.dof - 1)
        } else if l.dof > 1 {
            format!(
                "at a branch point of its motion ({} DOF there): a one-DOF sheet has a second motion at such a state",
                l.dof
            )
        } else {
            "where no branch point was found at the states checked".into()
        };
        outln!(
            o,
            "            leaves between t = {:.3} and {:.3} of the periodic motion, {why}",
            l.after_periodic_t,
            l.before_periodic_t
        );
    }
}

/// What the finite deployment did, against the periodic sheet.
fn describe_deployment(o: &mut String, d: &SheetDeployment) {
    let p = &d.periodic;
    outln!(
        o,
        "deployed    {} after {} states: hull area ×{:.4} (largest ×{:.4}), stretches {:.4} × {:.4}",
        d.end_reason,
        d.steps,
        d.end.hull_area_ratio,
        d.max_hull_area_ratio,
        d.end.stretches[0],
        d.end.stretches[1]
    );
    outln!(
        o,
        "periodic    {} after {} states: these tiles at hull area ×{:.4}",
        p.end_reason,
        p.steps,
        p.measures.hull_area_ratio
    );
    let a = &d.agreement;
    outln!(
        o,
        "            same poses as the periodic sheet to {:.1e} L, {:.1e} rad over {} states (to t = {:.3} of the periodic motion)",
        a.max_position_deviation,
        a.max_angle_deviation,
        a.compared_steps,
        a.until_periodic_t
    );
    let checked_bad: Vec<String> = d
        .checks
        .iter()
        .filter(|c| c.dof != 1 || !c.follows_periodic)
        .map(|c| format!("t = {:.3}: {} DOF", c.t, c.dof))
        .collect();
    if checked_bad.is_empty() {
        outln!(
            o,
            "            one DOF at each of {} states checked",
            d.checks.len()
        );
    } else {
        outln!(
            o,
            "warning: the sheet is not one-DOF everywhere along the way ({}); it may leave this path",
            checked_bad.join(", ")
        );
    }
    for (what, states) in [("sheet", &d.singular), ("periodic", &d.periodic_singular)] {
        for s in states.iter() {
            outln!(o, "{}", singular_warning(what, s));
        }
    }
}

/// The warning line of a singular state of the `what` path ("sheet", "periodic").
pub(crate) fn singular_warning(what: &str, s: &SingularState) -> String {
    format!(
        "warning: the {what} path is singular at t = {:.4} ({} extra first-order motion{}, \
         lowest eigenvalue {:.1e} against {:.1e} along the path): a sheet pulled through it \
         can branch off the periodic motion there; stop short of it or guide the sheet",
        s.t,
        s.extra_motions,
        if s.extra_motions == 1 { "" } else { "s" },
        s.lowest,
        s.typical
    )
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

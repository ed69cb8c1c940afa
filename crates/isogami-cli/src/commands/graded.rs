//! `isogami graded`: a finite sheet of a design whose tiles each get their own shape so that
//! it opens into a target outline, written as JSON, with the check that its closed tiling
//! really opens into it along one motion.

use crate::output::{emit, json_text, write_atomic, CliResult, Outputs};
use indicatif::{ProgressBar, ProgressStyle};
use isogami::api::{graded_sheet, GradedRun};
use isogami::graded::{self, outline_from_svg, GradedRequest, PathCheck, Target, MAX_SVG_BYTES};
use isogami::input::read_text;
use isogami::stop::NEVER;
use std::path::{Path, PathBuf};

/// Arguments of `graded`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The design: a name, a spec string FAMILY:PARAMS:CELL:JOINTS, or design JSON.
    #[arg(long, allow_hyphen_values = true)]
    design: String,
    /// The region: RxC cells of the design (e.g. 3x3).
    #[arg(long, default_value = "3x3", value_parser = parse_cells)]
    region: (usize, usize),
    /// The outline the opened sheet should have: disc, ellipse:A,B (semi-axes along x and y,
    /// their ratio counts), polygon:x,y;x,y;… (star-shaped about its centroid) or @FILE.svg
    /// (the one closed shape drawn in an SVG file: path, polygon, rect, circle or ellipse,
    /// transforms applied, as seen on screen). Scaled to the area the design's own sheet
    /// covers when open. Or field:FROM,TO[,DEGREES]: instead of an outline, a ramp of area
    /// ratio across the sheet (FROM at one end, TO at the other, along DEGREES from +x), met
    /// cell by cell.
    #[arg(long, default_value = "disc", value_parser = parse_target)]
    target: Target,
    /// The opened state as the periodic deployment's t in (0, 1] [default: the periodic
    /// state of largest area].
    #[arg(long)]
    t: Option<f64>,
    /// States the pins must close in, the opened one included (more: shapes that move all
    /// the way; 1: the opened state alone, which leaves most sheets rigid).
    #[arg(long, default_value_t = GradedRequest::default().states)]
    states: usize,
    /// Iterations of the optimisation (sheets of over a few hundred tiles come nearer their
    /// target with more: 1,600 rotating squares 5.3 % from a disc at 200, 2.6 % at 400).
    #[arg(long, default_value_t = GradedRequest::default().solve.max_iterations)]
    iterations: usize,
    /// Largest error that meets the target, a fraction: the outline's Hausdorff distance to
    /// the target over the target's equivalent radius, or a field's largest relative cell
    /// error [default: 0.05].
    #[arg(long)]
    tolerance: Option<f64>,
    /// Edge length in millimetres at which the verdict says its sizes (overlap depth, pin
    /// gap).
    #[arg(long, default_value_t = graded::verdict::NOMINAL_EDGE_MM)]
    edge_mm: f64,
    /// Write the sheet (to --out, and print it) even when it does not open along one motion
    /// or misses its target; without it such a sheet is an error (exit code 2) and no file
    /// is written.
    #[arg(long)]
    allow_failed: bool,
    /// Only the sheet graded towards the target: when it does not open, no search for the
    /// nearest sheet that does (the target blended with the design's own outline).
    #[arg(long)]
    no_fallback: bool,
    /// Write the graded sheet and its report as JSON to this file.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print the JSON (sheet, report, path check) on standard output.
    #[arg(long)]
    json: bool,
}

fn parse_cells(text: &str) -> Result<(usize, usize), String> {
    let (r, c) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("region {text:?} is not RxC (e.g. 3x3)"))?;
    let number = |s: &str| {
        s.trim()
            .parse::<usize>()
            .map_err(|_| format!("region {text:?} is not RxC (e.g. 3x3)"))
    };
    Ok((number(r)?, number(c)?))
}

/// A target outline's text, or `@PATH`: the outline of the SVG file at PATH (clap's message
/// names the value, so the errors do not repeat the path).
fn parse_target(text: &str) -> Result<Target, String> {
    let Some(path) = text.strip_prefix('@') else {
        return graded::parse_target(text).map_err(|e| e.to_string());
    };
    let svg = read_text(Path::new(path), MAX_SVG_BYTES).map_err(|e| e.to_string())?;
    outline_from_svg(&svg)
        .map(Target::Outline)
        .map_err(|e| e.to_string())
}

/// Grades one design towards one outline.
pub fn run(args: Args) -> CliResult {
    // The destination before the work: a large sheet takes minutes.
    if let Some(path) = &args.out {
        let mut outputs = Outputs::new();
        outputs.file(path, Vec::new());
        outputs.check()?;
    }
    let mut request = GradedRequest {
        design: args.design.clone(),
        rows: args.region.0,
        cols: args.region.1,
        t: args.t,
        states: args.states,
        tolerance: args.tolerance,
        fall_back: !args.no_fallback,
        ..GradedRequest::default()
    }
    .with_target(args.target.clone());
    if !(args.edge_mm.is_finite() && args.edge_mm > 0.0) {
        return Err(format!(
            "--edge-mm {} must be a positive length",
            args.edge_mm
        ));
    }
    if args.iterations == 0 {
        return Err("--iterations must be at least 1".into());
    }
    request.solve.max_iterations = args.iterations;
    let bar = ProgressBar::new(request.solve.max_iterations as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} grading: iteration {pos}, cost {msg}, {elapsed}")
            .expect("valid template"),
    );
    let run = graded_sheet(
        &request,
        &mut |p| {
            bar.set_position(p.iteration as u64);
            bar.set_message(format!("{:.3e}", p.cost));
            true
        },
        NEVER,
    )
    .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    if !(run.verdict.passed() || args.allow_failed) {
        emit(&summary(&run, &args, false))?;
        return Err(format!(
            "the graded sheet {} (--allow-failed writes it anyway)",
            if run.verdict.opens {
                "misses its target"
            } else {
                "does not open along one motion"
            }
        ));
    }
    let text = json_text(&run)?;
    if let Some(path) = &args.out {
        write_atomic(path, (text.clone() + "\n").as_bytes())?;
    }
    if args.json {
        return emit(&(text + "\n"));
    }
    emit(&summary(&run, &args, true))
}

/// The human summary (`written`: the file was written).
fn summary(run: &GradedRun, args: &Args, written: bool) -> String {
    let r = &run.report;
    let p = &run.path;
    let mut o = String::new();
    let dof: Vec<String> = p
        .states
        .iter()
        .filter(|s| s.opening > 0.0)
        .map(|s| s.dof.map_or("?".into(), |d| d.to_string()))
        .collect();
    o += &format!("design      {}\n", run.sheet.design);
    o += &format!(
        "sheet       {} tiles, {} pins, {} nodes; {} states\n",
        r.tiles,
        run.sheet.joints.len(),
        run.sheet.nodes.len(),
        run.sheet.path.len() + 1
    );
    let v = &run.verdict;
    o += &match (r.max_field_error, &run.fit) {
        (Some(e), _) => format!(
            "fit         area ratio within {e:.4} of the field in each of {} cells ({:.2} % at most); the whole sheet opens ×{:.3}{}\n",
            r.field_cells,
            100.0 * v.error,
            v.sheet_opening,
            v.periodic_opening
                .map_or(String::new(), |p| format!(" (the design's periodic sheet: ×{p:.3} at most)"))
        ),
        (None, Some(f)) => format!(
            "fit         outline {:.2} % from the target at most (Hausdorff, both ways), {:.2} % on average, {:.2} % inside and {:.2} % outside at most; tips within {:.2} % (median {:.2} %)\n",
            100.0 * f.hausdorff,
            100.0 * f.mean,
            100.0 * f.inside,
            100.0 * f.outside,
            100.0 * r.max_outline_error,
            100.0 * r.median_outline_error,
        ),
        (None, None) => "fit         no outline measured\n".into(),
    };
    o += &format!(
        "shapes      smallest angle {:.1}°, corners keep ≥ {:.0} % of their sine, edges ≥ {:.0} % of their length, tiles ≥ {:.0} % of their area\n",
        r.min_angle_degrees,
        100.0 * r.min_corner_fraction,
        100.0 * r.min_edge_fraction,
        100.0 * r.min_area_fraction
    );
    o += &format!(
        "solve       {} iterations, cost {:.3e} → {:.3e}, pins closed to {:.1e} L, {:.1} s\n",
        r.iterations, r.cost[0], r.cost[1], r.joint_gap, r.seconds
    );
    o += &format!(
        "motion      {}: {} states from open to closed, DOF {}, {}, {}, closed-state spread {:.1e} rad\n",
        if p.reached {
            "opens along one motion"
        } else {
            "does NOT open along one motion"
        },
        p.states.len(),
        dof.join(" "),
        pins_line(p),
        overlaps_line(p),
        p.closed_spread
    );
    o += &format!("verdict     {}\n", v.line(args.edge_mm));
    if let (Some(path), true) = (&args.out, written) {
        o += &format!("written     {}\n", path.display());
    }
    o
}

/// The path's widest pin gap and, when it is over the tolerance, where.
fn pins_line(p: &PathCheck) -> String {
    match p.widest_gap() {
        Some(s) if !s.pins_closed() => format!(
            "pins closed to {:.1e} L (widest at {:.0} % open)",
            s.joint_gap,
            100.0 * s.opening
        ),
        Some(s) => format!("pins closed to {:.1e} L", s.joint_gap),
        None => "no states".into(),
    }
}

/// The states with overlapping tiles, each named with its pair (the first three).
fn overlaps_line(p: &PathCheck) -> String {
    let hits: Vec<String> = p
        .states
        .iter()
        .filter_map(|s| {
            s.overlap
                .map(|(a, b)| format!("{a} and {b} at {:.0} % open", 100.0 * s.opening))
        })
        .collect();
    match hits.len() {
        0 => "no overlapping tiles".into(),
        n if n <= 3 => format!("overlapping tiles {}", hits.join(", ")),
        n => format!(
            "overlapping tiles {} and in {} more states",
            hits[..3].join(", "),
            n - 3
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(
        opening: f64,
        joint_gap: f64,
        overlap: Option<(usize, usize)>,
    ) -> isogami::graded::PathState {
        isogami::graded::PathState {
            opening,
            joint_gap,
            dof: Some(1),
            smallest: None,
            overlap,
            overlap_depth: if overlap.is_some() { 1e-3 } else { 0.0 },
            poses: Vec::new(),
        }
    }

    /// A failed path says where: the widest pin gap's state when it is over the tolerance,
    /// and every overlapping pair with its state (the 400-tile disc's opened state overlaps:
    /// "2 with overlapping tiles" hid that the sheet as fitted is one of them).
    #[test]
    fn the_motion_line_says_where_the_path_fails() {
        let failed = PathCheck {
            states: vec![
                state(1.0, 8e-7, Some((0, 2))),
                state(0.5, 2e-7, None),
                state(0.0, 8.4e-4, Some((0, 1))),
            ],
            closed_spread: 1.5,
            self_intersecting: Vec::new(),
            reached: false,
            pin_tolerance: graded::deploy::PIN_TOLERANCE,
            dof_from_opening: graded::deploy::DOF_FROM_OPENING,
        };
        assert_eq!(
            pins_line(&failed),
            "pins closed to 8.4e-4 L (widest at 0 % open)"
        );
        assert_eq!(
            overlaps_line(&failed),
            "overlapping tiles 0 and 2 at 100 % open, 0 and 1 at 0 % open"
        );
        let clean = PathCheck {
            states: vec![state(1.0, 8e-7, None), state(0.0, 1e-15, None)],
            closed_spread: 0.0,
            self_intersecting: Vec::new(),
            reached: true,
            pin_tolerance: graded::deploy::PIN_TOLERANCE,
            dof_from_opening: graded::deploy::DOF_FROM_OPENING,
        };
        assert_eq!(pins_line(&clean), "pins closed to 8.0e-7 L");
        assert_eq!(overlaps_line(&clean), "no overlapping tiles");
        let many = PathCheck {
            states: (0..5)
                .map(|k| state(k as f64 / 4.0, 0.0, Some((k, k + 1))))
                .collect(),
            closed_spread: 0.0,
            self_intersecting: Vec::new(),
            reached: false,
            pin_tolerance: graded::deploy::PIN_TOLERANCE,
            dof_from_opening: graded::deploy::DOF_FROM_OPENING,
        };
        assert_eq!(
            overlaps_line(&many),
            "overlapping tiles 0 and 1 at 0 % open, 1 and 2 at 25 % open, 2 and 3 at 50 % open and in 2 more states"
        );
    }

    #[test]
    fn regions_and_targets_parse_or_say_why() {
        assert_eq!(parse_cells("3x4").unwrap(), (3, 4));
        assert!(parse_cells("3").unwrap_err().contains("RxC"));
        assert!(parse_target("ellipse:2,1").is_ok());
        assert!(parse_target("square").unwrap_err().contains("target"));
        assert!(parse_target("@/nonexistent/outline.svg")
            .unwrap_err()
            .contains("/nonexistent/outline.svg: cannot read it: "));
    }
}

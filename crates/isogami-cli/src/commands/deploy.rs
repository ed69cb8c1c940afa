//! `isogami deploy`.

use crate::output::{emit, json_text, print_json, CliResult, Outputs};
use indicatif::{ProgressBar, ProgressStyle};
use isogami::api::{deploy, resolve_design, DeployRequest, FrameSelection};
use isogami::catalog::{margins_report_of_trajectory, CatalogSettings};
use isogami::contact::{ContactModel, ContactSettings};
use isogami::deploy::{DeploySettings, DeploymentReport, Method};
use isogami::explore::TopologyOptions;
use isogami::finite::periodic_singular_states;
use isogami::kinematics::Mechanism;
use isogami::measure::expansion_profile;
use isogami::render::{
    deployment_frame_svgs, expansion_plot_svg, gif_from_svgs, polar_plot_svg, Fonts,
};
use std::path::{Path, PathBuf};

/// Arguments of `deploy`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The design: a name (rotating-squares), a spec string, or design JSON.
    #[arg(long, allow_hyphen_values = true)]
    design: String,
    /// Deployment method.
    #[arg(long, default_value = "rigid-modes", value_parser = ["rigid-modes", "ncm", "springs"])]
    method: String,
    /// Cut width relative to the mean edge length.
    #[arg(long, default_value_t = ContactSettings::default().kerf, allow_hyphen_values = true)]
    kerf: f64,
    /// For a design with several degrees of freedom: open along basis motion K (0-based, as
    /// listed by `analyze`) instead of the fastest-opening combination of all of them.
    #[arg(long, value_name = "K")]
    mode: Option<usize>,
    /// Number of frames to report, exactly: accepted states nearest to evenly spaced t, with
    /// states inserted between them when the deployment has fewer (summaries never depend on it).
    #[arg(long, default_value_t = 60)]
    frame_count: usize,
    /// Report every accepted state instead of evenly spaced frames.
    #[arg(long)]
    all_steps: bool,
    /// Deployment parameters t at which the polar plot shows the profile of U (comma
    /// separated, each in [0, 1]).
    #[arg(long, default_value = "0.25,0.5,0.75,1")]
    polar_t: String,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
    /// Write the JSON report to this file.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write one SVG per frame (3×3 cells) into this directory.
    #[arg(long)]
    frames: Option<PathBuf>,
    /// Write an animated GIF of the deployment.
    #[arg(long)]
    gif: Option<PathBuf>,
    /// Write an SVG plot of min/max expansion versus t; the polar plot goes beside it
    /// (FILE-polar.svg).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Skip the margins the text report ends with (shape tolerance, most open state, finite
    /// sheet), which deploy shapes moved off the design and count a 6×6-cell patch.
    #[arg(long)]
    no_margins: bool,
}

/// Deploys one design and writes what was asked.
pub fn run(args: Args) -> CliResult {
    let method: Method = args
        .method
        .parse()
        .map_err(|e: isogami::error::SettingsError| e.to_string())?;
    let polar_t = parse_polar_t(&args.polar_t)?;
    let mut request = DeployRequest {
        settings: DeploySettings {
            method,
            contact: ContactSettings::with_kerf(args.kerf),
            mode: args.mode,
            ..DeploySettings::default()
        },
        frames: FrameSelection::Evenly(args.frame_count),
    };
    // --frame-count is checked even when --all-steps makes it moot.
    request.validate().map_err(|e| e.to_string())?;
    if args.all_steps {
        request.frames = FrameSelection::AllSteps;
    }
    let design = resolve_design(&args.design).map_err(|e| e.to_string())?;

    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("{spinner} deploying: {pos} states, {elapsed}")
            .expect("valid template"),
    );
    let run = deploy(&design, &request, &mut |n| {
        bar.set_position(n as u64);
        true
    })
    .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    let (mech, contact, frames, report) = (&run.mechanism, &run.contact, &run.frames, &run.report);

    // Every file is made first, then all are written together (or none).
    let mut outputs = Outputs::new();
    if let Some(dir) = &args.frames {
        frame_files(&mut outputs, dir, mech, contact, frames);
    }
    if let Some(path) = &args.gif {
        let svgs = deployment_frame_svgs(mech, contact, frames, 480.0);
        let bytes = gif_from_svgs(&svgs, 480, 6, &Fonts::system()).map_err(|e| e.to_string())?;
        outputs.file(path, bytes);
    }
    if let Some(path) = &args.plot {
        let t: Vec<f64> = frames.iter().map(|f| f.t).collect();
        let lo: Vec<f64> = frames.iter().map(|f| f.measures.min_expansion).collect();
        let hi: Vec<f64> = frames.iter().map(|f| f.measures.max_expansion).collect();
        let svg = expansion_plot_svg(&t, &lo, &hi, &report.design).map_err(|e| e.to_string())?;
        outputs.file(path, svg.into_bytes());
        let profiles: Vec<(String, Vec<(f64, f64)>)> = polar_t
            .iter()
            .map(|&target| {
                let f = frames
                    .iter()
                    .min_by(|a, b| (a.t - target).abs().total_cmp(&(b.t - target).abs()))
                    .expect("at least one frame");
                (
                    format!("t = {:.2}", f.t),
                    expansion_profile(&f.measures.u_matrix(), 180),
                )
            })
            .collect();
        let polar = polar_plot_svg(&profiles).map_err(|e| e.to_string())?;
        outputs.file(&sibling(path, "-polar"), polar.into_bytes());
    }
    if let Some(path) = &args.out {
        outputs.file(path, json_text(report)?.into_bytes());
    }
    outputs.write()?;
    if args.json {
        return print_json(report);
    }
    let mut o = String::new();
    outln!(o, "design       {}", report.design);
    outln!(
        o,
        "method       {}  (kerf {} L)",
        report.method,
        report.kerf
    );
    if report.dof > 1 {
        outln!(
            o,
            "dof          {} (not self-deployable: this is the fastest-opening of many paths)",
            report.dof
        );
    }
    outln!(o, "end          {}", report.end_reason);
    outln!(
        o,
        "steps        {} accepted of {} attempted ({} states with the closed one), arc length {:.4}",
        report.steps - 1,
        report.attempts,
        report.steps,
        report.arc_length
    );
    outln!(o, "behaviour    {}", behaviour_line(report));
    outln!(
        o,
        "expansion    min {:+.4}  max {:+.4}  area ratio up to {:.4}",
        report.min_expansion,
        report.max_expansion,
        report.max_area_ratio
    );
    outln!(
        o,
        "rotation     up to {:.2}°",
        report.max_tile_rotation.to_degrees()
    );
    outln!(
        o,
        "invariants   max joint residual {:.2e} L, min clearance {:.4} L",
        report.max_joint_residual,
        report.min_clearance
    );
    let singular = periodic_singular_states(mech, &run.trajectory, &request.settings)
        .map_err(|e| e.to_string())?;
    if singular.is_empty() {
        outln!(
            o,
            "singular     no state of the periodic path (a finite sheet can branch where its \
             cell does not: `isogami sheet --deploy` checks the sheet you will make)"
        );
    }
    for s in &singular {
        outln!(o, "{}", super::sheet::singular_warning("periodic", s));
    }
    // The margins are measured along the rigid-modes path of a one-DOF design.
    if report.dof == 1 && method == Method::RigidModes && !args.no_margins {
        let settings = CatalogSettings {
            deploy: request.settings,
            topology: TopologyOptions {
                mobility: request.settings.mobility,
                ..TopologyOptions::default()
            },
            ..CatalogSettings::default()
        };
        // The deployment and its files stand on their own: margins that cannot be measured
        // are said, not a failure of the command.
        match margins_report_of_trajectory(&design, mech, &run.trajectory, &settings) {
            Ok(margins) => super::margins_text::margin_lines(&mut o, &margins, 20.0),
            Err(e) => outln!(o, "margins      not measured: {e}"),
        }
    }
    emit(&o)
}

/// The class, the figures it was decided on (in units of the largest expansion) and, for a
/// design at a class boundary, the class on the other side.
fn behaviour_line(report: &DeploymentReport) -> String {
    let Some(class) = report.behaviour else {
        return "none (does not expand)".to_string();
    };
    let Some(f) = report.behaviour_figures else {
        return class.to_string();
    };
    let figures = format!(
        "spread {:.3}, contraction {:+.3} of the largest expansion",
        f.spread, f.contraction
    );
    if report.behaviour_boundary {
        format!(
            "{class}  (boundary case, {:.3} from {}: {figures})",
            f.margin, f.across
        )
    } else {
        format!("{class}  ({figures}; margin {:.3})", f.margin)
    }
}

/// One SVG per frame in the folder `dir` (made when missing).
fn frame_files(
    outputs: &mut Outputs,
    dir: &Path,
    mech: &Mechanism,
    contact: &ContactModel,
    frames: &[isogami::deploy::FrameRecord],
) {
    outputs.folder(dir);
    for (k, svg) in deployment_frame_svgs(mech, contact, frames, 600.0)
        .into_iter()
        .enumerate()
    {
        outputs.file(&dir.join(format!("frame-{k:04}.svg")), svg.into_bytes());
    }
}

/// `path` with `suffix` inserted before the extension.
fn sibling(path: &Path, suffix: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_default();
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    path.with_file_name(format!("{stem}{suffix}{ext}"))
}

/// Parses `--polar-t`: comma-separated values in [0, 1].
fn parse_polar_t(text: &str) -> Result<Vec<f64>, String> {
    let values: Vec<f64> = text
        .split(',')
        .map(|p| {
            let v: f64 = p
                .trim()
                .parse()
                .map_err(|_| format!("--polar-t: '{}' is not a number", p.trim()))?;
            if (0.0..=1.0).contains(&v) {
                Ok(v)
            } else {
                Err(format!("--polar-t: {v} is outside [0, 1]"))
            }
        })
        .collect::<Result<_, _>>()?;
    if values.is_empty() || values.len() > 12 {
        return Err("--polar-t takes 1 to 12 values".into());
    }
    Ok(values)
}

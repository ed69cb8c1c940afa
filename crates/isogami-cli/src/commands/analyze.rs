//! `isogami analyze`.

use crate::output::{emit, print_json, CliResult};
use isogami::api::{analyze, resolve_design, Analysis};
use isogami::catalog::{margins_report, CatalogSettings, MarginsReport};
use isogami::mobility::MobilitySettings;
use serde::Serialize;

/// Arguments of `analyze`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The design: a name (rotating-squares), a spec string FAMILY:PARAMS:CELL:JOINTS, or
    /// design JSON.
    #[arg(long, allow_hyphen_values = true)]
    design: String,
    /// Relative zero tolerance on the eigenvalues of the non-dimensional H.
    #[arg(long, default_value_t = MobilitySettings::default().rel_tol, allow_hyphen_values = true)]
    tol: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Edge length in mm at which the shape tolerance is also given in mm.
    #[arg(long, default_value_t = 20.0, allow_hyphen_values = true)]
    edge_mm: f64,
    /// Skip the margins (shape tolerance, most open state), which deploy the design and
    /// shapes moved off it; only the closed state's mobility is analysed then.
    #[arg(long)]
    no_margins: bool,
}

/// The JSON of `analyze`: the analysis and, for a one-DOF design, its margins.
#[derive(Serialize)]
struct Analyzed<'a> {
    #[serde(flatten)]
    analysis: &'a Analysis,
    #[serde(skip_serializing_if = "Option::is_none")]
    margins: Option<MarginsReport>,
}

/// Runs the mobility analysis of one design.
pub fn run(args: Args) -> CliResult {
    let design = resolve_design(&args.design).map_err(|e| e.to_string())?;
    let out =
        analyze(&design, MobilitySettings { rel_tol: args.tol }).map_err(|e| e.to_string())?;
    let mob = &out.mobility;
    if !(args.edge_mm.is_finite() && args.edge_mm > 0.0) {
        return Err(format!(
            "--edge-mm {}: expected a length in mm above 0",
            args.edge_mm
        ));
    }
    let margins = if mob.dof == 1 && !args.no_margins {
        let settings = CatalogSettings {
            topology: isogami::explore::TopologyOptions {
                mobility: MobilitySettings { rel_tol: args.tol },
                ..Default::default()
            },
            ..CatalogSettings::default()
        };
        Some(margins_report(&design, &settings).map_err(|e| format!("margins: {e}"))?)
    } else {
        None
    };
    if args.json {
        return print_json(&Analyzed {
            analysis: &out,
            margins,
        });
    }
    let mut o = String::new();
    outln!(o, "design      {}", out.design);
    outln!(
        o,
        "cell        {} tiles, {} edges, {} joints",
        out.tiles,
        out.edges,
        out.joints
    );
    outln!(
        o,
        "dof         {}{}",
        mob.dof,
        match mob.dof {
            0 => "  (rigid)",
            1 => "  (self-deployable)",
            _ => "  (under-constrained)",
        }
    );
    let shown: Vec<String> = mob
        .eigenvalues
        .iter()
        .take(6)
        .map(|l| format!("{l:.3e}"))
        .collect();
    outln!(
        o,
        "eigenvalues {} (smallest of {}; zero below {:.1e})",
        shown.join(" "),
        mob.eigenvalues.len(),
        mob.threshold
    );
    match mob.gap_decades {
        Some(g) => outln!(
            o,
            "gap         {g:.1} decades between zero and non-zero eigenvalues"
        ),
        None => outln!(o, "gap         n/a"),
    }
    if let Some(m) = &mob.motion {
        outln!(
            o,
            "motion      (unit vector, lengths in units of L = {:.6}; area rate {:+.4})",
            out.length_scale,
            m.area_rate
        );
        for (i, t) in m.tiles.iter().enumerate() {
            outln!(
                o,
                "  tile {i:>2}   v = ({:+.6}, {:+.6})  omega = {:+.6}",
                t.vx,
                t.vy,
                t.omega
            );
        }
        outln!(
            o,
            "  u̇ = ({:+.6}, {:+.6})  ẇ = ({:+.6}, {:+.6})",
            m.u[0],
            m.u[1],
            m.w[0],
            m.w[1]
        );
    }
    if let Some(m) = &margins {
        super::margins_text::margin_lines(&mut o, m, args.edge_mm);
    }
    emit(&o)
}

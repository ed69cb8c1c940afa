//! `isogami inverse`: from a target behaviour to designs, by screening the design database
//! and refining the best (the library's `inverse::inverse_design`; the store supplies the
//! candidates and saves the results).

use crate::output::{emit, print_json, CliResult};
use indicatif::{ProgressBar, ProgressStyle};
use isogami::input::{read_text, MAX_TARGET_BYTES};
use isogami::inverse::{inverse_design, InverseRequest, InverseResult, Scored, Target};
use isogami_store::{Check, SavedDesign, Store, StoreError, StoreWriter};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Arguments of `inverse`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The target: compact text such as "2*area + isotropic; families=IH28; tiles<=4", JSON
    /// (starting with '{'), or @FILE holding either. Goals: area, area(r), expansion(deg),
    /// expansion(deg,e), uniform, isotropic, zero-poisson, poisson(nu), ratio(r),
    /// lock(min,max[,deg]), lock-f(a,b,c,d), path(t:min:max,...); a goal naming a value is
    /// met within its tolerance (default 0.01, 0.05 for poisson; `~TOL` after the goal sets
    /// it) and the run ends with that verdict. Constraints: families=, cells=, tiles<=/>=/=,
    /// rotation>=DEG, kerf>=K, hinge>=H.
    #[arg(long, allow_hyphen_values = true)]
    target: String,
    /// The design database to screen.
    #[arg(long)]
    db: PathBuf,
    /// How many designs of different topologies to keep and refine.
    #[arg(long, default_value_t = 3)]
    top: usize,
    /// Evaluations (deployments) per refined design; 0 screens only.
    #[arg(long, default_value_t = 80)]
    budget: usize,
    /// How many of the best pre-screened designs to re-deploy (default 16 × top).
    #[arg(long)]
    confirm: Option<usize>,
    /// How many screened designs (two shapes per topology at most) get a first refinement
    /// of a quarter of the budget before the best TOP topologies go on (default 16 × top).
    #[arg(long)]
    triage: Option<usize>,
    /// Fresh shape samples around each of the best topologies before refining.
    #[arg(long, default_value_t = 0)]
    samples: usize,
    /// Kerf the designs are deployed with (units of the mean edge length).
    #[arg(long, allow_hyphen_values = true)]
    kerf: Option<f64>,
    /// Also optimise the kerf during refinement.
    #[arg(long)]
    refine_kerf: bool,
    /// Save the refined designs to the database as user designs.
    #[arg(long)]
    save: bool,
    /// Print the results as JSON.
    #[arg(long)]
    json: bool,
}

fn at(path: &Path, e: StoreError) -> String {
    format!("{}: {e}", path.display())
}

fn read_target(text: &str) -> Result<Target, String> {
    let body = match text.strip_prefix('@') {
        Some(file) => {
            read_text(Path::new(file), MAX_TARGET_BYTES).map_err(|e| format!("--target @{e}"))?
        }
        None => text.to_string(),
    };
    Target::resolve(&body).map_err(|e| e.to_string())
}

fn request_of(args: &Args) -> Result<InverseRequest, String> {
    let mut r = InverseRequest::new(read_target(&args.target)?);
    r.top = args.top;
    r.budget = args.budget;
    r.confirm = args.confirm.unwrap_or(0);
    r.triage = args.triage.unwrap_or(0);
    if args.confirm == Some(0) || args.triage == Some(0) {
        return Err("--confirm and --triage must be at least 1".into());
    }
    r.samples = args.samples;
    if let Some(k) = args.kerf {
        r.kerf = k;
    }
    r.refine_kerf = args.refine_kerf;
    r.validate().map_err(|e| e.to_string())?;
    Ok(r)
}

fn save(db: &Path, result: &InverseResult) -> Result<Vec<SavedDesign>, String> {
    let mut writer = StoreWriter::open(db, None, Check::Quick).map_err(|e| at(db, e))?;
    writer.save_inverse_results(result).map_err(|e| at(db, e))
}

fn row(text: &mut String, label: &str, s: &Scored) {
    let m = &s.measures;
    let poisson = m
        .poisson
        .map_or("-".to_string(), |[a, b]| format!("[{a:.3}, {b:.3}]"));
    outln!(text, "   {label} {}", s.spec);
    outln!(
        text,
        "          objective {:.6}  kerf {}  area {:.4}  expansion [{:.4}, {:.4}]  rotation {:.1}°  nu {poisson}",
        s.objective,
        s.kerf,
        m.max_area_ratio,
        m.min_expansion,
        m.max_expansion,
        m.max_tile_rotation_deg
    );
    outln!(
        text,
        "          end {}: expansions [{:.4}, {:.4}] along {:.1}°",
        m.end_label,
        m.end_expansions[0],
        m.end_expansions[1],
        m.end_angle_deg
    );
}

fn table(result: &InverseResult, saved: &[SavedDesign]) -> String {
    let mut t = String::new();
    outln!(t, "target: {}", result.target);
    outln!(
        t,
        "{} candidates, {} pass the constraints, {} pre-scored, {} re-deployed ({} valid), {} fresh samples, {} triaged; {} deployments in {:.1} s",
        result.candidates,
        result.admitted,
        result.prescored,
        result.confirmed,
        result.confirmed_valid,
        result.sampled,
        result.triaged,
        result.evaluations,
        result.seconds
    );
    for r in &result.results {
        outln!(
            t,
            "#{} {} {} (topology {}): objective {:.6} -> {:.6}, {} ({} evaluations, {} invalid)",
            r.rank,
            r.family,
            r.cell,
            r.topology,
            r.before.objective,
            r.after.objective,
            if r.improved {
                "improved"
            } else {
                "not improved"
            },
            r.evaluations,
            r.invalid_evaluations
        );
        row(&mut t, "before", &r.before);
        row(&mut t, "after ", &r.after);
        outln!(t, "          {}", r.verdict.summary());
    }
    if let Some(best) = result.results.first() {
        outln!(t, "verdict: {}", best.verdict.summary());
    }
    for s in saved {
        outln!(t, "{}: {}", s.spec, s.note);
    }
    t
}

#[derive(Serialize)]
struct JsonOut<'a> {
    #[serde(flatten)]
    result: &'a InverseResult,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    saved: Vec<SavedDesign>,
}

/// Runs inverse design on the database and prints or saves the results.
pub fn run(args: Args) -> CliResult {
    let request = request_of(&args)?;
    let candidates = {
        let store = Store::open_read(&args.db, Check::Quick).map_err(|e| at(&args.db, e))?;
        store
            .inverse_candidates(&request.target.constraints)
            .map_err(|e| at(&args.db, e))?
    };
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{msg:>8} [{bar:30}] {pos}/{len} {elapsed}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    let result = inverse_design(&candidates, &request, &mut |p| {
        bar.set_length(p.total as u64);
        bar.set_position(p.done as u64);
        bar.set_message(p.stage.as_str());
        true
    })
    .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    let saved = if args.save {
        save(&args.db, &result)?
    } else {
        Vec::new()
    };
    if args.json {
        print_json(&JsonOut {
            result: &result,
            saved,
        })
    } else {
        emit(&table(&result, &saved))
    }
}

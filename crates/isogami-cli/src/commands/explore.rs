//! `isogami explore`: arguments, the progress bar and the report. The driver (planning,
//! skipping committed units, the thread pool, one transaction per unit) is
//! `isogami_store::explore_into`.

use crate::output::{emit, print_json, CliResult};
use indicatif::{ProgressBar, ProgressStyle};
use isogami::catalog::CatalogSettings;
use isogami::cell::{CellDims, UnitCell};
use isogami::explore::{ExploreError, Shard, WorkUnit, MAX_PARTS, MAX_REDUCED_EDGES};
use isogami::tiling::{Family, Tiling};
use isogami_store::{explore_into, ExploreEvent, ExploreRequest, MAX_JOBS};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

/// Arguments of `explore`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Families, comma separated (e.g. IH1,IH28), or "all".
    #[arg(long, default_value = "all")]
    families: String,
    /// Supercells, comma separated (e.g. 1x1,2x1); default: every cell with at most
    /// --max-edges unique edges. A listed cell over --max-edges is an error.
    #[arg(long)]
    cells: Option<String>,
    /// Largest number of unique edges of an explored cell, 1..=24 (default 16; 12 with
    /// --quick). A cell given with --cells over it is an error, never skipped. Work grows
    /// about 2^edges: for all families 20 takes about 10 CPU-minutes (5 minutes on 2 cores,
    /// under 1 GB), 24 an estimated 19 CPU-hours (spread it with --shard and --unit-parts).
    #[arg(long)]
    max_edges: Option<usize>,
    /// Keep designs whose largest principal expansion reaches this.
    #[arg(long, default_value_t = CatalogSettings::default().threshold, allow_hyphen_values = true)]
    threshold: f64,
    /// Shape samples per kept topology (the default shape included).
    #[arg(long, default_value_t = CatalogSettings::default().samples)]
    samples: usize,
    /// The design database (SQLite).
    #[arg(long, default_value = "isogami.db")]
    db: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    jobs: Option<usize>,
    /// Run only the I-th of N disjoint slices of the work units (0-based), e.g. 0/4. With
    /// --unit-parts the slices are of the units' parts.
    #[arg(long)]
    shard: Option<String>,
    /// Split every unit's masks into P parts (1..=4096), so that one big unit spreads over
    /// --shard tasks (or over reruns); a unit with fewer masks to expand than P is split into
    /// one part per mask, never into empty parts. A part waits in the database until the unit's other
    /// parts are there (`isogami merge` brings the other shards' parts), then the unit is
    /// joined exactly as if run whole.
    #[arg(long, default_value_t = 1)]
    unit_parts: usize,
    /// A small exploration that finishes in seconds (about 2 s of CPU for all families):
    /// minimal cells with at most 12 edges, four shape samples per topology.
    #[arg(long)]
    quick: bool,
    /// Print the final report as JSON.
    #[arg(long)]
    json: bool,
    /// Print the work units this command would run, in the order they would start (longest
    /// expected first), with each cell's unique edges, symmetry group order, parts and
    /// relative expected cost (3^edges / group), one line per unit however many parts, and
    /// run nothing: no database is opened or made.
    /// `isogami db units` gives the measured figures of a finished run.
    #[arg(long)]
    plan: bool,
    /// The report goes to stderr (serve's first run: its stdout's first line says where it
    /// listens).
    #[arg(skip)]
    report_on_stderr: bool,
}

impl Args {
    /// The quick exploration (`explore --quick --db DB`) with every other flag at its
    /// default and its report on stderr: what `isogami serve` runs when its database does not
    /// exist yet (or its first run was stopped).
    pub fn quick(db: PathBuf) -> Args {
        let defaults = CatalogSettings::default();
        Args {
            families: "all".into(),
            cells: None,
            max_edges: None,
            threshold: defaults.threshold,
            samples: defaults.samples,
            db,
            jobs: None,
            shard: None,
            unit_parts: 1,
            quick: true,
            json: false,
            plan: false,
            report_on_stderr: true,
        }
    }
}

fn parse_shard(text: &str) -> Result<Shard, String> {
    text.parse::<Shard>()
        .map_err(|_| format!("--shard '{text}': expected I/N with 0 <= I < N, e.g. 0/4"))
}

fn parse_families(text: &str) -> Result<Vec<Family>, String> {
    if text.trim() == "all" {
        return Ok(Family::all().collect());
    }
    let mut out: Vec<Family> = text
        .split(',')
        .map(|f| f.trim().parse::<Family>().map_err(|e| e.to_string()))
        .collect::<Result<_, _>>()?;
    out.sort();
    out.dedup();
    Ok(out)
}

fn settings_of(args: &Args) -> Result<CatalogSettings, String> {
    let mut s = CatalogSettings {
        threshold: args.threshold,
        samples: args.samples,
        ..CatalogSettings::default()
    };
    if args.quick {
        s = s.quick();
    }
    if let Some(n) = args.max_edges {
        if n == 0 || n > MAX_REDUCED_EDGES {
            return Err(format!(
                "--max-edges must lie in 1..={MAX_REDUCED_EDGES} (the topology enumeration's \
                 limit), got {n}"
            ));
        }
        s.topology.max_edges = n;
    }
    s.validate().map_err(|e| e.to_string())?;
    Ok(s)
}

/// The request of these arguments (parsed and checked, nothing run).
fn request_of(args: &Args) -> Result<ExploreRequest, String> {
    let settings = settings_of(args)?;
    let families = parse_families(&args.families)?;
    let cells: Option<Vec<CellDims>> = match &args.cells {
        Some(list) => Some(
            list.split(',')
                .map(|c| c.trim().parse::<CellDims>().map_err(|e| e.to_string()))
                .collect::<Result<_, _>>()?,
        ),
        None => None,
    };
    let shard = args.shard.as_deref().map(parse_shard).transpose()?;
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if jobs == 0 || jobs > MAX_JOBS {
        return Err(format!("--jobs must lie in 1..={MAX_JOBS}, got {jobs}"));
    }
    let request = ExploreRequest {
        settings,
        families,
        cells,
        shard,
        jobs,
        parts: args.unit_parts,
    };
    let plan = request.plan().map_err(|e| plan_error(&e, &request))?;
    if args.families.trim() != "all" {
        empty_families(&request, &plan.all)?;
    }
    Ok(request)
}

/// A planning error in the terms of the command line.
fn plan_error(e: &ExploreError, request: &ExploreRequest) -> String {
    let max = request.settings.topology.max_edges;
    match e {
        ExploreError::CellsOverCap {
            family,
            dims,
            edges,
            others,
            needed,
            ..
        } => {
            let more = match others {
                0 => String::new(),
                n => format!(" ({n} more requested cell(s) too)"),
            };
            let fix = if *needed <= MAX_REDUCED_EDGES {
                format!("give --max-edges {needed} or leave the cell out")
            } else {
                format!("leave the cell out (--max-edges is at most {MAX_REDUCED_EDGES})")
            };
            format!(
                "--cells: {family}/{dims} has {edges} unique edges, more than --max-edges \
                 {max}{more}; {fix}"
            )
        }
        ExploreError::CellOverDims { dims, max_dims } => format!(
            "--cells: {dims} is larger than {max_dims}x{max_dims}, the largest cell of {}",
            if request.settings.topology.max_dims == 1 {
                "--quick (minimal cells only)"
            } else {
                "an exploration"
            }
        ),
        ExploreError::Parts { text } => {
            format!("--unit-parts must lie in 1..={MAX_PARTS}, got {text}")
        }
        other => format!("--cells: {other}"),
    }
}

/// An explicitly named family without any cell under the cap is an error, not an empty run.
fn empty_families(request: &ExploreRequest, units: &[WorkUnit]) -> Result<(), String> {
    let max = request.settings.topology.max_edges;
    for &family in &request.families {
        if units.iter().any(|u| u.family == family) {
            continue;
        }
        let edges = UnitCell::new(&Tiling::default_for(family), CellDims::MINIMAL)
            .map(|c| c.edges.len())
            .map_err(|e| format!("{family}: {e}"))?;
        if edges > max {
            return Err(format!(
                "--families: {family}'s minimal cell has {edges} unique edges, more than \
                 --max-edges {max}; give --max-edges {edges} to explore it"
            ));
        }
    }
    Ok(())
}

/// One planned unit as `--plan --json` prints it: a unit split into parts is one entry,
/// with its part count, never one entry per part.
#[derive(serde::Serialize)]
struct PlannedUnit {
    unit: String,
    #[serde(flatten)]
    size: isogami::explore::UnitSize,
    /// Parts the unit is split into (1: run whole).
    parts: usize,
    /// Of those, the parts this run (this shard) takes.
    parts_here: usize,
}

/// `explore --plan`: the units in start order (longest expected first) with their sizes and
/// how many parts each is split into; nothing runs. One line per unit however many parts.
fn print_plan(request: &ExploreRequest, json: bool) -> CliResult {
    let plan = request.plan().map_err(|e| plan_error(&e, request))?;
    let items = plan.items();
    let mut units: Vec<WorkUnit> = Vec::new();
    let mut here: std::collections::HashMap<WorkUnit, usize> = std::collections::HashMap::new();
    for item in &items {
        let n = here.entry(item.unit).or_insert(0);
        if *n == 0 {
            units.push(item.unit);
        }
        *n += 1;
    }
    let mut planned: Vec<PlannedUnit> = units
        .iter()
        .filter_map(|u| {
            u.size().map(|size| PlannedUnit {
                unit: u.id(),
                size,
                parts: plan.parts_of(u),
                parts_here: here.get(u).copied().unwrap_or(0),
            })
        })
        .collect();
    // Longest first, ties in plan order (a stable sort).
    planned.sort_by(|a, b| b.size.expected_cost.total_cmp(&a.size.expected_cost));
    if json {
        return print_json(&planned);
    }
    let total: f64 = planned.iter().map(|p| p.size.expected_cost).sum();
    let mut o = format!(
        "{} work units ({} work items) in start order, longest expected first; expected cost \
         relative to the whole plan (3^edges / symmetry group)\n\n{:<14} {:>5} {:>6} {:>11} {:>9}\n",
        planned.len(),
        items.len(),
        "unit",
        "edges",
        "group",
        "parts",
        "share %"
    );
    for p in &planned {
        let parts = if p.parts_here == p.parts {
            p.parts.to_string()
        } else {
            format!("{} of {}", p.parts_here, p.parts)
        };
        o.push_str(&format!(
            "{:<14} {:>5} {:>6} {:>11} {:>9.3}\n",
            p.unit,
            p.size.edges,
            p.size.symmetry_group,
            parts,
            100.0 * p.size.expected_cost / total.max(f64::MIN_POSITIVE)
        ));
    }
    emit(&o)
}

/// Explores and prints the per-family, per-stage report.
pub fn run(args: Args) -> CliResult {
    let request = request_of(&args)?;
    if args.plan {
        return print_plan(&request, args.json);
    }
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template(
            "{bar:30} {pos}/{len} work units, {elapsed} (eta {eta}) {msg}",
        )
        .expect("valid template"),
    );
    let mut on_event = |event: &ExploreEvent<'_>| match *event {
        ExploreEvent::Started { to_run, .. } => {
            bar.set_length(to_run as u64);
            bar.reset_elapsed();
        }
        ExploreEvent::UnitFinished { unit, .. } => {
            bar.set_message(unit.id());
            bar.inc(1);
        }
    };
    let never = AtomicBool::new(false);
    let outcome = explore_into(&args.db, &request, &mut on_event, &never)
        .map_err(|e| format!("{}: {e}", args.db.display()))?;
    bar.finish_and_clear();
    let failures = &outcome.failures;
    if args.json {
        print_json(&outcome.stats)?;
    } else {
        let mut o = String::new();
        outln!(
            o,
            "{} {} run, {} already in {}, {} failed",
            outcome.committed,
            if request.parts > 1 {
                "unit parts"
            } else {
                "work units"
            },
            outcome.skipped,
            args.db.display(),
            failures.len()
        );
        o.push_str(&crate::commands::db::stats_table(&outcome.stats));
        if args.report_on_stderr {
            crate::output::check_text(&o)?;
            eprint!("{o}");
        } else {
            emit(&o)?;
        }
    }
    for f in failures {
        eprintln!("warning: work unit {}: {}", f.unit, f.message);
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "{} work unit(s) failed; rerun to retry them",
            failures.len()
        ))
    }
}

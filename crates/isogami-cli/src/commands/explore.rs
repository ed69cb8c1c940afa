//! `isogami explore`: runs work units (family × supercell) in parallel and commits each to
//! the design database in its own transaction, skipping units already there.

use crate::output::{emit, print_json, CliResult};
use indicatif::{ProgressBar, ProgressStyle};
use isogami::catalog::{run_unit, CatalogSettings};
use isogami::cell::CellDims;
use isogami::explore::cells_to_explore;
use isogami::tiling::Family;
use isogami_store::{Check, RunInfo, StoreWriter, UnitRecords};
use rayon::prelude::*;
use std::path::PathBuf;
use std::sync::mpsc;
use std::time::Instant;

/// Arguments of `explore`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Families, comma separated (e.g. IH1,IH28), or "all".
    #[arg(long, default_value = "all")]
    families: String,
    /// Supercells, comma separated (e.g. 1x1,2x1); default: every cell with at most 16
    /// unique edges.
    #[arg(long)]
    cells: Option<String>,
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
    /// Run only the I-th of N disjoint slices of the work units (0-based), e.g. 0/4.
    #[arg(long)]
    shard: Option<String>,
    /// A small exploration that finishes in minutes: minimal cells with at most 12 edges,
    /// four shape samples per topology.
    #[arg(long)]
    quick: bool,
    /// Print the final report as JSON.
    #[arg(long)]
    json: bool,
}

impl Args {
    /// The quick exploration (`explore --quick --db DB`) with every other flag at its
    /// default: what `isogami serve` runs when its database does not exist yet.
    pub fn quick(db: PathBuf) -> Args {
        let defaults = CatalogSettings::default();
        Args {
            families: "all".into(),
            cells: None,
            threshold: defaults.threshold,
            samples: defaults.samples,
            db,
            jobs: None,
            shard: None,
            quick: true,
            json: false,
        }
    }
}

/// One unit of work.
#[derive(Debug, Clone, Copy)]
struct Unit {
    family: Family,
    dims: CellDims,
}

impl Unit {
    fn id(&self) -> String {
        format!("{}/{}", self.family, self.dims)
    }
}

fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("--shard '{text}': expected I/N with 0 <= I < N, e.g. 0/4");
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (
        i.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if n == 0 || i >= n || n > 100_000 {
        return Err(bad());
    }
    Ok((i, n))
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
        s.topology.max_dims = 1;
        s.topology.max_edges = 12;
        s.samples = s.samples.min(4);
    }
    s.validate().map_err(|e| e.to_string())?;
    Ok(s)
}

/// The deterministic, ordered list of work units.
fn units_of(args: &Args, settings: &CatalogSettings) -> Result<Vec<Unit>, String> {
    let families = parse_families(&args.families)?;
    let wanted: Option<Vec<CellDims>> = match &args.cells {
        Some(list) => Some(
            list.split(',')
                .map(|c| c.trim().parse::<CellDims>().map_err(|e| e.to_string()))
                .collect::<Result<_, _>>()?,
        ),
        None => None,
    };
    let mut units = Vec::new();
    for family in families {
        for (dims, _) in cells_to_explore(family, &settings.topology) {
            if wanted.as_ref().is_none_or(|w| w.contains(&dims)) {
                units.push(Unit { family, dims });
            }
        }
    }
    Ok(units)
}

/// Explores and prints the per-family, per-stage report.
pub fn run(args: Args) -> CliResult {
    let settings = settings_of(&args)?;
    let mut units = units_of(&args, &settings)?;
    if let Some(shard) = &args.shard {
        let (i, n) = parse_shard(shard)?;
        units = units
            .into_iter()
            .enumerate()
            .filter(|(k, _)| k % n == i)
            .map(|(_, u)| u)
            .collect();
    }
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if jobs == 0 || jobs > 1024 {
        return Err(format!("--jobs must lie in 1..=1024, got {jobs}"));
    }
    let fingerprint = settings.fingerprint();
    let run = RunInfo {
        tool_version: env!("CARGO_PKG_VERSION"),
        settings: &fingerprint,
    };
    let mut store = StoreWriter::open(&args.db, Some(run), Check::Full)
        .map_err(|e| format!("{}: {e}", args.db.display()))?;
    let done = store
        .done_units()
        .map_err(|e| format!("{}: {e}", args.db.display()))?;
    let total = units.len();
    let todo: Vec<Unit> = units
        .into_iter()
        .filter(|u| !done.contains(&u.id()))
        .collect();
    let skipped = total - todo.len();

    let bar = ProgressBar::new(todo.len() as u64);
    bar.set_style(
        ProgressStyle::with_template(
            "{bar:30} {pos}/{len} work units, {elapsed} (eta {eta}) {msg}",
        )
        .expect("valid template"),
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs)
        .build()
        .map_err(|e| format!("thread pool: {e}"))?;
    let (tx, rx) = mpsc::channel();
    let mut failures = Vec::new();
    let mut committed = 0usize;
    std::thread::scope(|scope| -> Result<(), String> {
        let todo = &todo;
        scope.spawn(move || {
            pool.install(|| {
                todo.par_iter().for_each_with(tx, |tx, unit| {
                    let start = Instant::now();
                    let outcome = run_unit(unit.family, unit.dims, &settings);
                    let _ = tx.send((*unit, outcome, start.elapsed().as_secs_f64()));
                })
            })
        });
        for (unit, outcome, seconds) in rx {
            bar.set_message(unit.id());
            match outcome {
                Ok(o) => match UnitRecords::from_outcome(&o, seconds) {
                    Ok(records) => {
                        store
                            .commit_unit(&records)
                            .map_err(|e| format!("{}: {e}", args.db.display()))?;
                        committed += 1;
                    }
                    Err(e) => failures.push(format!("{}: {e}", unit.id())),
                },
                Err(e) => failures.push(format!("{}: {e}", unit.id())),
            }
            bar.inc(1);
        }
        Ok(())
    })?;
    bar.finish_and_clear();
    let stats = store
        .stats()
        .map_err(|e| format!("{}: {e}", args.db.display()))?;
    if args.json {
        print_json(&stats)?;
    } else {
        let mut o = String::new();
        outln!(
            o,
            "{committed} work units run, {skipped} already in {}, {} failed",
            args.db.display(),
            failures.len()
        );
        o.push_str(&crate::commands::db::stats_table(&stats));
        emit(&o)?;
    }
    for f in &failures {
        eprintln!("warning: work unit {f}");
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

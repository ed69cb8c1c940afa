//! `isogami merge`, `isogami db stats`, `isogami db units`, `isogami db motions`,
//! `isogami db check-shard` and `isogami db migrate`.

use crate::output::{emit, print_json, CliResult};
use isogami::explore::Shard;
use isogami_store::{check_shard_set, Check, DbStats, Store, StoreError, StoreWriter};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Arguments of `merge`.
#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// The database to merge into (created if missing or empty; otherwise it must be an
    /// isogami database made with the shards' settings).
    #[arg(long)]
    into: PathBuf,
    /// Shard databases to merge.
    #[arg(required = true)]
    shards: Vec<PathBuf>,
    /// Merge shard databases even when some shard of their run is missing or incomplete
    /// (by default such a merge is refused and nothing is written).
    #[arg(long)]
    allow_incomplete: bool,
}

/// Merges shard databases; units already present are skipped. Every shard is opened and
/// fully checked before the target is touched, so a damaged or foreign shard stops the merge
/// with nothing written. Databases made by `explore --shard` must be every shard of one run,
/// each complete, unless `--allow-incomplete`.
pub fn merge(args: MergeArgs) -> CliResult {
    let shards = args
        .shards
        .iter()
        .map(|s| Store::open_read(s, Check::Full).map_err(|e| at(s, e)))
        .collect::<Result<Vec<_>, _>>()?;
    if !args.allow_incomplete {
        let inputs: Vec<(&Path, &Store)> = args
            .shards
            .iter()
            .map(PathBuf::as_path)
            .zip(&shards)
            .collect();
        check_shard_set(&inputs)
            .map_err(|e| format!("checking the shards: {e}"))?
            .map_err(|e| {
                format!("{e} (nothing merged; --allow-incomplete merges what is there)")
            })?;
    }
    let existed = args.into.exists();
    let mut store =
        StoreWriter::open(&args.into, None, Check::Full).map_err(|e| at(&args.into, e))?;
    // One transaction: a refused or failed input leaves the target as it was (a target this
    // merge made is removed again).
    let inputs: Vec<&Store> = shards.iter().collect();
    let reports = match store.merge_all(&inputs) {
        Ok(r) => r,
        Err((k, e)) => {
            drop(store);
            if !existed {
                for suffix in ["", "-wal", "-shm", "-journal"] {
                    let mut p = args.into.clone().into_os_string();
                    p.push(suffix);
                    let _ = std::fs::remove_file(p);
                }
            }
            return Err(format!("{} (nothing merged)", at(&args.shards[k], e)));
        }
    };
    let mut o = String::new();
    for (path, r) in args.shards.iter().zip(&reports) {
        let _ = write!(
            o,
            "{}: {} work units added ({} already present), {} designs",
            path.display(),
            r.units_added,
            r.units_skipped,
            r.designs_added
        );
        if r.parts_added > 0 {
            let _ = write!(
                o,
                ", {} parts of split units ({} units joined)",
                r.parts_added, r.units_joined
            );
        }
        if r.user_designs_added + r.user_designs_skipped > 0 {
            let _ = write!(
                o,
                ", {} user designs ({} already present)",
                r.user_designs_added, r.user_designs_skipped
            );
        }
        o.push('\n');
    }
    emit(&o)
}

/// A store error as the one-line message `PATH: problem`.
fn at(path: &Path, e: StoreError) -> String {
    format!("{}: {e}", path.display())
}

/// Subcommands of `db`.
#[derive(Debug, clap::Subcommand)]
pub enum DbCommand {
    /// Summarise a design database.
    Stats {
        /// The database.
        #[arg(long, default_value = "isogami.db")]
        db: PathBuf,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// List designs as the catalogue does: the browser's filters, sort and lead (buildable
    /// designs first by default), each row with its finite sheet, shape tolerance and whether
    /// it is buildable.
    Designs(super::db_designs::Args),
    /// List every work unit with its wall time, peak memory (the exploring process's resident
    /// memory while it ran) and designs kept, slowest first: the figures for sizing a cluster
    /// run's tasks.
    Units {
        /// The database.
        #[arg(long, default_value = "isogami.db")]
        db: PathBuf,
        /// Only the N slowest.
        #[arg(long, value_name = "N")]
        top: Option<usize>,
        /// Print JSON (a list of {id, seconds, peak_rss_bytes, designs}).
        #[arg(long)]
        json: bool,
    },
    /// List the distinct motions: classes of topologies (in different cells or families) that
    /// move alike, biggest first, each with its topologies, families, cells and an example
    /// design.
    Motions {
        /// The database.
        #[arg(long, default_value = "isogami.db")]
        db: PathBuf,
        /// Also list the motions found only once (by default only shared ones are listed).
        #[arg(long)]
        all: bool,
        /// Print JSON (every class with its variants).
        #[arg(long)]
        json: bool,
    },
    /// Carry an older database into a new file; the old file is only read. Schema version 3
    /// (before the finite-sheet columns): copied, with every explored design's finite 6x6
    /// figures computed from its spec. Schema version 2 (made before issue 21: joint strings
    /// in edge labels that depended on the exact shape): the explored catalogue explored
    /// again with its settings and plan, and every saved user design translated to the
    /// current labels (the same physical joints) and deployed again.
    Migrate {
        /// The old database.
        #[arg(long)]
        db: PathBuf,
        /// The new database (created; an interrupted migration into it resumes).
        #[arg(long)]
        into: PathBuf,
        /// Worker threads (default: all cores).
        #[arg(long)]
        jobs: Option<usize>,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Check that a database made by `explore --shard I/N` holds every work unit of its shard
    /// (exit 0), or say in one line why not (exit 2): missing, not that shard, incomplete.
    CheckShard {
        /// The shard database.
        #[arg(long)]
        db: PathBuf,
        /// The shard it must hold, I/N.
        #[arg(long)]
        shard: String,
        /// Print the shard's status as JSON (before failing, when it is readable).
        #[arg(long)]
        json: bool,
    },
}

/// Runs a `db` subcommand.
pub fn run(cmd: DbCommand) -> CliResult {
    match cmd {
        DbCommand::Stats { db, json } => {
            // Reading only: nothing is created or changed, even for a file that is refused.
            let store = Store::open_read(&db, Check::Full).map_err(|e| at(&db, e))?;
            let stats = store.stats().map_err(|e| at(&db, e))?;
            if json {
                print_json(&stats)
            } else {
                emit(&stats_table(&stats))
            }
        }
        DbCommand::Designs(args) => super::db_designs::run(args),
        DbCommand::Units { db, top, json } => units_table(&db, top, json),
        DbCommand::Motions { db, all, json } => motions_table(&db, all, json),
        DbCommand::CheckShard { db, shard, json } => check_shard(&db, &shard, json),
        DbCommand::Migrate {
            db,
            into,
            jobs,
            json,
        } => migrate(&db, &into, jobs, json),
    }
}

/// `db check-shard`.
fn check_shard(db: &Path, shard: &str, json: bool) -> CliResult {
    let wanted: Shard = shard
        .parse()
        .map_err(|_| format!("--shard '{shard}': expected I/N with 0 <= I < N, e.g. 0/4"))?;
    let store = Store::open_read(db, Check::Full).map_err(|e| at(db, e))?;
    let status = store
        .shard_status()
        .map_err(|e| at(db, e))?
        .ok_or_else(|| {
            format!(
                "{}: not a shard database (made without --shard, or by an older isogami)",
                db.display()
            )
        })?;
    if json {
        print_json(&status)?;
    }
    let r = &status.record;
    if (r.index, r.count) != (wanted.index(), wanted.count()) {
        return Err(format!(
            "{}: holds shard {}/{}, not {wanted}",
            db.display(),
            r.index,
            r.count
        ));
    }
    if !status.complete() {
        return Err(format!(
            "{}: shard {wanted} is incomplete ({})",
            db.display(),
            status.progress()
        ));
    }
    if !json {
        emit(&format!(
            "{}: shard {wanted} complete ({})\n",
            db.display(),
            status.progress()
        ))?;
    }
    Ok(())
}

/// Bytes as MiB with one decimal.
fn mebibytes(bytes: u64) -> String {
    format!("{:.1} MiB", bytes as f64 / f64::from(1u32 << 20))
}

/// `db units`: every work unit's time, peak memory and designs, slowest first.
fn units_table(db: &Path, top: Option<usize>, json: bool) -> CliResult {
    let store = Store::open_read(db, Check::Full).map_err(|e| at(db, e))?;
    let mut units = store.unit_summaries().map_err(|e| at(db, e))?;
    let total = units.len();
    let seconds: f64 = units.iter().map(|u| u.seconds).sum();
    units.truncate(top.unwrap_or(usize::MAX));
    if json {
        return print_json(&units);
    }
    let mut o = format!(
        "{total} work units, {seconds:.1} s of unit time in all (slowest first)\n\n{:<14} {:>10} {:>12} {:>8}\n",
        "unit", "seconds", "peak memory", "designs"
    );
    for u in &units {
        let peak = u.peak_rss_bytes.map_or_else(|| "-".to_string(), mebibytes);
        let _ = writeln!(
            o,
            "{:<14} {:>10.2} {:>12} {:>8}",
            u.id, u.seconds, peak, u.designs
        );
    }
    emit(&o)
}

/// `db motions`: the classes of topologies that move alike.
fn motions_table(db: &Path, all: bool, json: bool) -> CliResult {
    let store = Store::open_read(db, Check::Full).map_err(|e| at(db, e))?;
    let classes = store
        .motion_classes()
        .map_err(|e| at(db, e))?
        .ok_or_else(|| {
            format!(
                "{}: no motion classes yet (made by an older isogami); run `isogami explore` \
                 with the same settings on it once to add them",
                db.display()
            )
        })?;
    if json {
        return print_json(&classes);
    }
    let shared = classes.iter().filter(|c| c.variants.len() > 1).count();
    let mut o = format!(
        "{} topologies, {} distinct motions, {shared} found in several cells or families\n",
        classes.iter().map(|c| c.variants.len()).sum::<usize>(),
        classes.len()
    );
    for (k, c) in classes.iter().enumerate() {
        if c.variants.len() < 2 && !all {
            continue;
        }
        let _ = writeln!(
            o,
            "\nmotion {} ({} topologies, {} families)",
            k + 1,
            c.variants.len(),
            c.families()
        );
        for v in &c.variants {
            let _ = writeln!(
                o,
                "  {:<6} {:<4} {:>3} designs  {}",
                v.family, v.cell, v.designs, v.topology
            );
        }
    }
    emit(&o)
}

/// The per-stage and per-family report.
pub fn stats_table(s: &DbStats) -> String {
    let mut o = String::new();
    let user = if s.user_designs > 0 {
        format!(", {} of them saved by users", s.user_designs)
    } else {
        String::new()
    };
    let twins = if s.cell_twins > 0 {
        format!(
            "; {} more found again on another cell of their family, stored with it",
            s.cell_twins
        )
    } else {
        String::new()
    };
    let _ = writeln!(
        o,
        "{} work units, {} designs{user}{twins} (schema {}, isogami {})",
        s.work_units,
        s.designs,
        s.schema_version,
        s.tool_version.as_deref().unwrap_or("?")
    );
    if let Some(shard) = &s.shard {
        let state = if shard.complete() {
            "complete"
        } else {
            "incomplete"
        };
        let _ = writeln!(o, "{} {state}: {}", shard.record, shard.progress());
    }
    if s.waiting_parts > 0 {
        let _ = writeln!(
            o,
            "{} part(s) of split units wait for their units' other parts (isogami merge the \
             other shards, or rerun the same explore)",
            s.waiting_parts
        );
    }
    if let Some(m) = &s.motions {
        let _ = writeln!(
            o,
            "{} topologies, {} distinct motions ({} found in several cells or families, {} across \
             families); per class: isogami db motions",
            m.topologies, m.motions, m.shared, m.across_families
        );
    }
    if let Some(u) = &s.slowest {
        let _ = write!(o, "slowest unit {} ({:.1} s)", u.id, u.seconds);
        if let Some(m) = &s.peak_memory {
            let bytes = m.peak_rss_bytes.unwrap_or(0);
            let _ = write!(o, "; largest peak memory {} ({})", m.id, mebibytes(bytes));
        }
        let _ = writeln!(o, "; per unit: isogami db units");
    }
    let _ = writeln!(
        o,
        "\n{:<18} {:>12} {:>12} {:>9}",
        "stage", "in", "out", "seconds"
    );
    for st in &s.stages {
        let _ = writeln!(
            o,
            "{:<18} {:>12} {:>12} {:>9.2}",
            st.stage, st.count_in, st.count_out, st.seconds
        );
    }
    let names: Vec<&str> = s.stages.iter().map(|st| st.stage.as_str()).collect();
    let _ = writeln!(
        o,
        "\nper family (masks in, count out of each stage, designs kept, seconds):"
    );
    let _ = write!(o, "{:<6} {:>9}", "family", "masks");
    for n in &names {
        let _ = write!(o, " {:>11}", n.chars().take(11).collect::<String>());
    }
    let _ = writeln!(o, " {:>8} {:>8}", "designs", "seconds");
    let mut families: Vec<_> = s.families.iter().collect();
    // IH2 before IH10.
    families.sort_by_key(|(name, _)| (name.len(), name.to_string()));
    for (fam, f) in families {
        let masks = f.stages.first().map_or(0, |st| st.count_in);
        let _ = write!(o, "{fam:<6} {masks:>9}");
        for n in &names {
            let v = f
                .stages
                .iter()
                .find(|st| &st.stage == n)
                .map_or(0, |st| st.count_out);
            let _ = write!(o, " {v:>11}");
        }
        let seconds: f64 = f.stages.iter().map(|st| st.seconds).sum();
        let _ = writeln!(o, " {:>8} {seconds:>8.2}", f.designs);
    }
    let f = &s.finite;
    if f.measured > 0 {
        let _ = writeln!(
            o,
            "\nfinite 6x6 patches: {} of {} designs measured; {} one DOF as cut; {} complete to \
             a one-DOF sheet ({} keeping the whole region, smallest share {}), {} do not",
            f.measured,
            s.designs,
            f.raw_one_dof,
            f.completed,
            f.fully_covered,
            f.min_covered.map_or("-".into(), |c| format!("{c:.3}")),
            f.measured - f.completed
        );
    }
    let m = &s.margins;
    if m.measured > 0 {
        let _ = writeln!(
            o,
            "margins: {} of {} designs measured; {} keep their opening at ±{} L (±{:.2} mm at 20 mm \
             edges; {} of fixed shape), {} special (open only at their exact shape); {} \
             buildable (that tolerance and a one-DOF sheet); {} close again to under 95 % of \
             their largest area by the end of the path",
            m.measured,
            s.designs,
            m.tolerance_met,
            isogami::catalog::FABRICATION_TOLERANCE,
            isogami::catalog::FABRICATION_TOLERANCE * 20.0,
            m.fixed_shape,
            m.special,
            m.buildable,
            m.closing_again,
        );
    }
    let _ = writeln!(o, "\nbehaviour classes:");
    for (k, v) in &s.by_behaviour {
        let _ = writeln!(o, "  {k:<32} {v}");
    }
    let _ = writeln!(o, "linkage signatures:");
    for (k, v) in &s.by_linkage {
        let _ = writeln!(o, "  {k:<32} {v}");
    }
    o
}

/// `db migrate`.
fn migrate(db: &Path, into: &Path, jobs: Option<usize>, json: bool) -> CliResult {
    if db == into {
        return Err("--into must be a new file, not the database being migrated".into());
    }
    let jobs = jobs.unwrap_or_else(|| {
        std::thread::available_parallelism().map_or(1, |n| n.get().min(isogami_store::MAX_JOBS))
    });
    let bar = indicatif::ProgressBar::new(0);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:30} {pos}/{len} work units re-explored, {elapsed}",
        )
        .expect("valid template"),
    );
    let mut on_event = |event: &isogami_store::ExploreEvent<'_>| match *event {
        isogami_store::ExploreEvent::Started { to_run, .. } => bar.set_length(to_run as u64),
        isogami_store::ExploreEvent::UnitFinished { .. } => bar.inc(1),
    };
    let never = std::sync::atomic::AtomicBool::new(false);
    let outcome = isogami_store::migrate(db, into, jobs, &mut on_event, &never)
        .map_err(|e| format!("migrating {} into {}: {e}", db.display(), into.display()))?;
    bar.finish_and_clear();
    if json {
        return print_json(&outcome);
    }
    let mut o = String::new();
    if let Some(fill) = &outcome.columns {
        let finite = if outcome.from_version < 4 {
            format!(
                "finite 6x6 figures and margins computed for {} explored designs ({} without a \
                 one-DOF sheet",
                fill.computed, fill.no_one_dof_sheet
            )
        } else {
            format!("margins computed for {} explored designs (", fill.computed)
        };
        let _ = writeln!(
            o,
            "{}: schema {} upgraded to {}: {} designs, {finite}{}{} special), {} user designs \
             left without, {} failed",
            into.display(),
            outcome.from_version,
            isogami_store::SCHEMA_VERSION,
            fill.designs,
            if outcome.from_version < 4 { ", " } else { "" },
            fill.special,
            fill.user_designs,
            fill.failed.len()
        );
        for (spec, reason) in &fill.failed {
            let _ = writeln!(o, "  not computed: {spec}: {reason}");
        }
        return emit(&o);
    }
    let Some(explored) = &outcome.explored else {
        return emit(&o);
    };
    let _ = writeln!(
        o,
        "{}: {} work units explored again ({} failed); {} user designs: {} saved, {} already \
         there (merged), {} relabelled, {} not carried over",
        into.display(),
        explored.committed + explored.skipped,
        explored.failures.len(),
        outcome.user_designs,
        outcome.user_saved,
        outcome.user_merged,
        outcome.user_relabelled,
        outcome.user_failed.len()
    );
    for (spec, reason) in &outcome.user_failed {
        let _ = writeln!(o, "  not carried over: {spec}: {reason}");
    }
    o.push_str(&stats_table(&explored.stats));
    emit(&o)
}

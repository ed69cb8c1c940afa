//! `isogami merge` and `isogami db stats`.

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
    let mut store =
        StoreWriter::open(&args.into, None, Check::Full).map_err(|e| at(&args.into, e))?;
    let mut o = String::new();
    for (path, shard) in args.shards.iter().zip(&shards) {
        let r = store.merge_from(shard).map_err(|e| at(path, e))?;
        let _ = write!(
            o,
            "{}: {} work units added ({} already present), {} designs",
            path.display(),
            r.units_added,
            r.units_skipped,
            r.designs_added
        );
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
        DbCommand::CheckShard { db, shard, json } => check_shard(&db, &shard, json),
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

/// The per-stage and per-family report.
pub fn stats_table(s: &DbStats) -> String {
    let mut o = String::new();
    let user = if s.user_designs > 0 {
        format!(", {} of them saved by users", s.user_designs)
    } else {
        String::new()
    };
    let _ = writeln!(
        o,
        "{} work units, {} designs{user} (schema {}, isogami {})",
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

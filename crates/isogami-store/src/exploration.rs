//! Running an exploration into a database: the one driver every front end calls (the CLI's
//! `explore`, and any binding).
//!
//! [`explore_into`] plans the work units ([`ExplorePlan`]), opens the database for writing
//! (creating it if new; its settings must match; a shard's database records which shard it
//! holds, see [`ShardRecord`](crate::ShardRecord)), skips the units it already holds, runs the
//! rest on a pool of `jobs` threads — handed out one at a time, longest expected first
//! ([`WorkItem::longest_first`]), each unit itself parallel on the same pool — and commits each
//! finished unit from the calling thread in its own transaction (one writer). What is stored
//! does not depend on `jobs` (only the commit order and timings do). A unit that fails is reported, not committed, so a rerun
//! retries it. A killed run keeps every unit it had committed.

use crate::error::{StoreError, StoreResult};
use crate::open::{Check, RunInfo, StoreWriter};
use crate::parts::{unit_records, StoredPart};
use crate::peak_memory::PeakMemory;
use crate::shard::record_plan;
use crate::stats::DbStats;
use isogami::catalog::{run_unit_part, CatalogSettings};
use isogami::cell::CellDims;
use isogami::error::{Requirement, SettingsError};
use isogami::explore::{ExploreError, ExplorePlan, Shard, WorkItem};
use isogami::tiling::Family;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

/// The most worker threads a run takes.
pub const MAX_JOBS: usize = 1024;

/// What to explore, and with how many threads. Plain data.
#[derive(Debug, Clone, PartialEq)]
pub struct ExploreRequest {
    /// Settings of every work unit (stored with the database; a resumed run must match).
    pub settings: CatalogSettings,
    /// Families, in the order their units are planned (callers sort them).
    pub families: Vec<Family>,
    /// Only these supercells (of those the settings allow); `None` for all.
    pub cells: Option<Vec<CellDims>>,
    /// Run only this slice of the plan; `None` for all of it.
    pub shard: Option<Shard>,
    /// Worker threads, 1..=[`MAX_JOBS`].
    pub jobs: usize,
    /// Parts every unit's masks are split into (1: whole units). A part waits in the file
    /// until its unit's other parts arrive (from this run, or from other shards by `merge`),
    /// then the unit is joined exactly as if run whole ([`StoredPart`](crate::StoredPart)).
    pub parts: usize,
}

impl ExploreRequest {
    /// The plan this request runs; an error when a requested cell is outside the settings'
    /// limits (`settings.topology.max_edges`, `max_dims`): requested cells are never dropped
    /// silently.
    pub fn plan(&self) -> Result<ExplorePlan, ExploreError> {
        ExplorePlan::new(
            &self.families,
            self.cells.as_deref(),
            &self.settings.topology,
            self.shard,
        )?
        .split(self.parts)
    }
}

/// What [`explore_into`] tells its progress callback, always on the calling thread.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ExploreEvent<'a> {
    /// The database is open: `planned` units in this run's slice, `skipped` of them already
    /// in the database, `to_run` left to run.
    Started {
        /// Units of this run (this shard's slice).
        planned: usize,
        /// Of these, units already committed.
        skipped: usize,
        /// Units left to run.
        to_run: usize,
    },
    /// A work item (a unit, or a part of one) finished (committed when `ok`, else reported as
    /// a failure).
    UnitFinished {
        /// The item.
        unit: &'a WorkItem,
        /// Whether it was committed.
        ok: bool,
        /// Units finished so far in this run, this one included.
        finished: usize,
        /// Units this run had to run.
        to_run: usize,
    },
}

/// A unit that failed, with the library's message.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct UnitFailure {
    /// Unit id, e.g. `IH28/2x1`.
    pub unit: String,
    /// Why (one line).
    pub message: String,
}

/// What a run did.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ExploreOutcome {
    /// Units in this run's slice of the plan.
    pub planned: usize,
    /// Units run and committed now.
    pub committed: usize,
    /// Units already in the database, not run again.
    pub skipped: usize,
    /// Units that failed (not committed; a rerun retries them).
    pub failures: Vec<UnitFailure>,
    /// Units not started because the run was cancelled.
    pub not_run: usize,
    /// Whether the cancellation flag stopped the run early.
    pub cancelled: bool,
    /// The database afterwards.
    pub stats: DbStats,
}

fn check_request(request: &ExploreRequest) -> StoreResult<()> {
    request.settings.validate()?;
    if request.jobs == 0 || request.jobs > MAX_JOBS {
        return Err(SettingsError::new(
            "jobs",
            request.jobs,
            Requirement::CountIn {
                low: 1,
                high: MAX_JOBS as u64,
            },
        )
        .into());
    }
    Ok(())
}

/// Runs `request` into the database at `db`; see the module documentation.
///
/// `progress` is called on the calling thread: once when the database is open, then after
/// every finished unit. Setting `cancel` stops the run between units: units already running
/// finish and are committed, units not started are left for a rerun (counted in
/// [`ExploreOutcome::not_run`]). Returns an error only when the database cannot be opened or
/// written (or the request is invalid); failed units are listed in the outcome.
pub fn explore_into(
    db: &Path,
    request: &ExploreRequest,
    progress: &mut dyn FnMut(&ExploreEvent<'_>),
    cancel: &AtomicBool,
) -> StoreResult<ExploreOutcome> {
    check_request(request)?;
    let plan = request.plan()?;
    let items = plan.items();
    let fingerprint = request.settings.fingerprint();
    let run = RunInfo {
        tool_version: env!("CARGO_PKG_VERSION"),
        settings: &fingerprint,
    };
    let mut store = StoreWriter::open(db, Some(run), Check::Full)?;
    record_plan(&store, &plan)?;
    let done = store.done_units()?;
    let waiting = store.waiting_parts()?;
    let todo: Vec<WorkItem> = items
        .iter()
        .filter(|i| !done.contains(&i.unit.id()) && !waiting.contains(&i.id()))
        .copied()
        .collect();
    let planned = items.len();
    let skipped = planned - todo.len();
    let to_run = todo.len();
    progress(&ExploreEvent::Started {
        planned,
        skipped,
        to_run,
    });

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(request.jobs)
        .build()
        .map_err(|e| StoreError::Io(std::io::Error::other(format!("thread pool: {e}"))))?;
    let settings = &request.settings;
    let (tx, rx) = mpsc::channel();
    let mut failures = Vec::new();
    let mut committed = 0usize;
    let mut finished = 0usize;
    // Set when a commit fails: the workers start nothing more.
    let stop = AtomicBool::new(false);
    // One item at a time, longest expected first: every worker takes the next item when it
    // finishes one, so no worker sits idle while items are left, and the cheap ones fill the
    // end. Inside an item the library works in parallel on the same pool, so a worker with no
    // item left helps the others with theirs.
    let order = WorkItem::longest_first(&todo);
    let next = AtomicUsize::new(0);
    let memory = PeakMemory::default();
    let sampled = AtomicBool::new(false);
    std::thread::scope(|scope| -> StoreResult<()> {
        let (order, next, stop, memory) = (&order, &next, &stop, &memory);
        scope.spawn(|| memory.sample_until(&sampled));
        // The sampler stops however the loop below ends (an early return included).
        let _stop_sampler = SetOnDrop(&sampled);
        scope.spawn(move || {
            pool.broadcast(|_| loop {
                if cancel.load(Ordering::Relaxed) || stop.load(Ordering::Relaxed) {
                    return;
                }
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(item) = order.get(k) else {
                    return;
                };
                let start = Instant::now();
                memory.begin(k);
                let outcome = run_unit_part(item.unit.family, item.unit.dims, item.part, settings);
                let peak = memory.end(k);
                let _ = tx.send((item, outcome, start.elapsed().as_secs_f64(), peak));
            });
            drop(tx);
        });
        for (item, outcome, seconds, peak) in rx {
            let ok = match outcome {
                Ok(outcome) => {
                    let part = StoredPart {
                        outcome,
                        seconds,
                        peak_rss_bytes: peak,
                    };
                    match commit_item(&mut store, part) {
                        Ok(()) => {
                            committed += 1;
                            true
                        }
                        // A part that cannot be joined with its siblings, or a design that
                        // cannot be stored, is this item's failure; anything else is the
                        // database's and stops the run.
                        Err(e @ (StoreError::Plan(_) | StoreError::InvalidRecord { .. })) => {
                            failures.push(UnitFailure {
                                unit: item.id(),
                                message: e.to_string(),
                            });
                            false
                        }
                        Err(e) => {
                            stop.store(true, Ordering::Relaxed);
                            return Err(e);
                        }
                    }
                }
                Err(e) => {
                    failures.push(UnitFailure {
                        unit: item.id(),
                        message: e.to_string(),
                    });
                    false
                }
            };
            finished += 1;
            progress(&ExploreEvent::UnitFinished {
                unit: item,
                ok,
                finished,
                to_run,
            });
        }
        Ok(())
    })?;
    // Twins and classes span the whole file: the twins are looked for on every run (a file
    // made before they were stored gets them; with none to fold nothing is written), the
    // classes recomputed when designs came in or went (or were never made), so a rerun that
    // adds nothing leaves the file as it was.
    let folded = store.refresh_cell_twins()?;
    let unclassed =
        store.design_count()? > 0 && store.motion_counts()?.is_none_or(|c| c.topologies == 0);
    if committed > 0 || folded > 0 || unclassed {
        store.refresh_motion_classes()?;
    }
    let stats = store.stats()?;
    Ok(ExploreOutcome {
        planned,
        committed,
        skipped,
        failures,
        not_run: to_run - finished,
        cancelled: cancel.load(Ordering::Relaxed) && finished < to_run,
        stats,
    })
}

/// Commits a finished item: a whole unit at once, a part through the parts table (which joins
/// its unit when it was the last part).
fn commit_item(store: &mut StoreWriter, part: StoredPart) -> StoreResult<()> {
    if part.outcome.part.count() > 1 {
        store.commit_part(&part)?;
        return Ok(());
    }
    store.commit_unit(&unit_records(vec![part])?)
}

/// Sets its flag when dropped.
struct SetOnDrop<'a>(&'a AtomicBool);

impl Drop for SetOnDrop<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

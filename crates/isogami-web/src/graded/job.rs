//! One graded-sheet job: the run of `api::graded_sheet` on the blocking pool, where it is
//! (iteration, cost, stage), a throttled snapshot of the sheet as it stands (its opened
//! polygons), why it stopped, and its result: the serialised `GradedRun`, the JSON
//! `isogami graded --out` writes. The registry, stopping and the job's life are
//! [`crate::jobs`]'.

use super::body::{outline_view, UNREACHABLE_HINT};
use super::limits::GradedLimits;
use crate::error::ApiError;
use crate::jobs::{Caps, Job, JobError, JobKind, JobRegistry, JobState};
use axum::http::StatusCode;
use isogami::api::{graded_sheet, GradedRun};
use isogami::graded::{AreaField, GradedError, GradedProgress, GradedRequest, GradedSheet};
use serde::Serialize;
use serde_json::Value;
use std::sync::Arc;
use std::time::Instant;

/// The request as run, for the view.
#[derive(Debug, Clone, Serialize)]
pub struct Echo {
    /// The design as given.
    pub design: String,
    /// Cells along w.
    pub rows: usize,
    /// Cells along u.
    pub cols: usize,
    /// The target's text as given (`@NAME` for an uploaded SVG file, as the CLI takes it).
    pub outline: String,
    /// The outline at scale 1, centred on its centroid, counter-clockwise (128 points around
    /// a disc or an ellipse): what the page draws, sized to the sheet, while the run goes
    /// (empty for a field target).
    pub outline_points: Value,
    /// A field target: the ramp of area ratio (null for an outline).
    pub field: Option<AreaField>,
    /// The opened state asked for (null: the state of largest area).
    pub t: Option<f64>,
    /// States the pins must close in.
    pub states: usize,
    /// Most iterations of the fit.
    pub iterations: usize,
    /// The largest error that meets the target asked for (null: the library's default).
    pub tolerance: Option<f64>,
    /// Whether the nearest sheet that opens is given when the one graded towards the target
    /// does not (false: `--no-fallback`).
    pub fall_back: bool,
}

impl Echo {
    /// `request` as it runs, its target given as `outline`.
    pub fn of(request: &GradedRequest, outline: &str) -> Echo {
        Echo {
            design: request.design.clone(),
            rows: request.rows,
            cols: request.cols,
            outline: outline.to_string(),
            outline_points: match request.field {
                Some(_) => Value::Array(Vec::new()),
                None => outline_view(outline, &request.outline)["points"].clone(),
            },
            field: request.field,
            t: request.t,
            states: request.states,
            iterations: request.solve.max_iterations,
            tolerance: request.tolerance,
            fall_back: request.fall_back,
        }
    }
}

/// The library's last progress report.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ProgressView {
    /// Accepted steps so far, over every stage.
    pub iteration: usize,
    /// Most iterations the fit may take.
    pub max_iterations: usize,
    /// Cost (½‖r‖²) after the step, at the stage's weights.
    pub cost: f64,
    /// Stage of the penalty continuation (0-based).
    pub stage: usize,
    /// Stages there are.
    pub stages: usize,
}

/// The sheet as it stood at one iteration: each tile's opened polygon (counter-clockwise,
/// in the sheet's units; its pins not yet closed exactly).
#[derive(Debug, Clone, Serialize)]
pub struct Snapshot {
    /// Snapshots taken so far, this one included (the page redraws when it changes).
    pub count: usize,
    /// The iteration it was taken at.
    pub iteration: usize,
    /// The cost then.
    pub cost: f64,
    /// One polygon per tile.
    pub polygons: Vec<Vec<[f64; 2]>>,
}

impl Snapshot {
    fn of(sheet: &GradedSheet, count: usize, iteration: usize, cost: f64) -> Snapshot {
        Snapshot {
            count,
            iteration,
            cost,
            polygons: (0..sheet.tiles.len())
                .map(|i| sheet.opened_polygon(i).iter().map(|p| [p.x, p.y]).collect())
                .collect(),
        }
    }
}

/// What a poll answers (`GET /api/graded/{id}`).
#[derive(Debug, Clone, Serialize)]
pub struct GradedView {
    /// The job's id.
    pub id: u64,
    /// Where it is.
    pub state: JobState,
    /// A stop was asked for and the run has not ended yet.
    pub stopping: bool,
    /// Seconds since the job started (until it ended).
    pub elapsed: f64,
    /// The request as it runs.
    pub request: Echo,
    /// The library's last progress report (null before the first accepted step).
    pub progress: Option<ProgressView>,
    /// The latest snapshot of the sheet as it stands (throttled; null before the first).
    pub snapshot: Option<Snapshot>,
    /// When done: the graded sheet, its report and path check, as `isogami graded --out`
    /// writes them.
    pub result: Option<Value>,
    /// When failed or stopped: why.
    pub error: Option<JobError>,
}

/// What a graded-sheet run has done so far.
#[derive(Default)]
pub struct Data {
    progress: Option<ProgressView>,
    snapshot: Option<Snapshot>,
    last_snapshot: Option<Instant>,
    run: Option<Arc<GradedRun>>,
    result_json: Option<Value>,
}

/// Graded sheets as a kind of job: at most [`GradedLimits::max_running`] at once.
#[derive(Debug)]
pub enum Graded {}

impl JobKind for Graded {
    type Limits = GradedLimits;
    type Echo = Echo;
    type Data = Data;
    const NOUN: &'static str = "graded-sheet";
    const ENDPOINT: &'static str = "/api/graded";
    const RUN: &'static str = "grading";
    const TIME_LIMIT_HINT: &'static str = "ask for fewer iterations or a smaller region, or run \
        `isogami graded` from the command line";

    fn caps(limits: &GradedLimits) -> Caps {
        Caps {
            max_running: limits.max_running,
            max_run: limits.max_run,
            abandon: limits.abandon,
            keep: limits.keep,
            max_kept: limits.max_kept,
        }
    }

    fn busy(running: &[u64]) -> ApiError {
        let ids: Vec<String> = running.iter().map(u64::to_string).collect();
        ApiError::new(
            StatusCode::CONFLICT,
            "busy",
            format!(
                "{} graded sheet{} already being optimised on this server (job {}), its limit",
                running.len(),
                if running.len() == 1 { " is" } else { "s are" },
                ids.join(", ")
            ),
            format!(
                "wait for one to end, or stop it (DELETE /api/graded/{})",
                running[0]
            ),
        )
    }

    fn explain(e: &isogami::Error) -> JobError {
        // The request's refusals are 400s before a job starts (`body::refusal`); should the
        // library refuse a target later in a run, the job says so in the same words.
        let (kind, hint) = match e {
            isogami::Error::Graded(GradedError::Unreachable(_)) => ("bad_target", UNREACHABLE_HINT),
            _ => (
                "graded_failed",
                "try another design, a smaller region or another outline",
            ),
        };
        ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, kind, e.to_string(), hint).into()
    }
}

/// One graded-sheet run and what it has done.
pub type GradedJob = Job<Graded>;

/// Every graded-sheet job this server remembers.
pub type GradedJobs = JobRegistry<Graded>;

impl Job<Graded> {
    /// The graded run, when done.
    pub fn run_result(&self) -> Option<Arc<GradedRun>> {
        self.with_data(|d| d.run.clone())
    }

    /// The view a poll answers; polling keeps a running job alive.
    pub fn view(&self) -> GradedView {
        self.poll(|s, d| GradedView {
            id: s.id,
            state: s.state,
            stopping: s.stopping,
            elapsed: s.elapsed,
            request: self.echo().clone(),
            progress: d.progress,
            snapshot: d.snapshot.clone(),
            result: d.result_json.clone(),
            error: s.error,
        })
    }

    /// Takes a progress report (a snapshot when the last is old enough); false when the run
    /// must stop.
    fn report(&self, p: &GradedProgress) -> bool {
        let every = self.limits().snapshot_every;
        let due = self.with_data(|d| {
            d.progress = Some(ProgressView {
                iteration: p.iteration,
                max_iterations: p.max_iterations,
                cost: p.cost,
                stage: p.stage,
                stages: p.stages,
            });
            d.last_snapshot.is_none_or(|t| t.elapsed() >= every)
        });
        if due {
            // Cloning the sheet happens outside the lock: polls are not held up by it.
            let sheet = p.sheet();
            let count = self.with_data(|d| d.snapshot.as_ref().map_or(0, |s| s.count)) + 1;
            let snapshot = Snapshot::of(&sheet, count, p.iteration, p.cost);
            self.with_data(|d| {
                d.snapshot = Some(snapshot);
                d.last_snapshot = Some(Instant::now());
            });
        }
        self.keep_going()
    }

    /// Runs the job on this thread. Ends the job however the run ends (a panic too).
    pub fn run(self: &Arc<Self>, request: &GradedRequest) {
        let keep_going = || self.keep_going();
        self.run_with(
            || Ok(graded_sheet(request, &mut |p| self.report(p), &keep_going)?),
            |d, run: GradedRun, json| {
                let count = d.snapshot.as_ref().map_or(0, |s| s.count) + 1;
                let iteration = run.report.iterations;
                d.snapshot = Some(Snapshot::of(
                    &run.sheet,
                    count,
                    iteration,
                    run.report.cost[1],
                ));
                d.result_json = Some(json);
                d.run = Some(Arc::new(run));
            },
        );
    }
}

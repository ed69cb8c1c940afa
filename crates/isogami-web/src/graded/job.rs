//! One graded-sheet job: the run of `api::graded_sheet` on the blocking pool, where it is
//! (iteration, cost, stage), a throttled snapshot of the sheet as it stands (its opened
//! polygons), why it stopped, and its result: the serialised `GradedRun`, the JSON
//! `isogami graded --out` writes.

use super::body::outline_view;
use super::limits::GradedLimits;
use crate::error::ApiError;
use crate::inverse::view::{JobError, JobState};
use axum::http::StatusCode;
use isogami::api::{graded_sheet, GradedRun};
use isogami::graded::{AreaField, GradedProgress, GradedRequest, GradedSheet};
use serde::Serialize;
use serde_json::Value;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
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

struct Inner {
    state: JobState,
    progress: Option<ProgressView>,
    snapshot: Option<Snapshot>,
    last_snapshot: Option<Instant>,
    run: Option<Arc<GradedRun>>,
    result_json: Option<Value>,
    error: Option<JobError>,
    ended: Option<Instant>,
    last_seen: Instant,
    stop_reason: Option<JobError>,
}

/// One graded-sheet run and what it has done.
pub struct GradedJob {
    id: u64,
    echo: Echo,
    started: Instant,
    limits: GradedLimits,
    stop: AtomicBool,
    inner: Mutex<Inner>,
}

impl std::fmt::Debug for GradedJob {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GradedJob").field("id", &self.id).finish()
    }
}

fn stopped(message: String, hint: &str) -> JobError {
    JobError {
        error: message,
        kind: "stopped",
        hint: hint.to_string(),
    }
}

/// A library error that ended a run, in the API's terms.
fn explain(e: &isogami::Error) -> JobError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "graded_failed",
        e.to_string(),
        "try another design, a smaller region or another outline",
    )
    .into()
}

impl GradedJob {
    /// A running job `id` for `request`, whose outline was given as `outline`.
    pub fn new(id: u64, request: &GradedRequest, outline: &str, limits: GradedLimits) -> Self {
        let now = Instant::now();
        GradedJob {
            id,
            echo: Echo {
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
            },
            started: now,
            limits,
            stop: AtomicBool::new(false),
            inner: Mutex::new(Inner {
                state: JobState::Running,
                progress: None,
                snapshot: None,
                last_snapshot: None,
                run: None,
                result_json: None,
                error: None,
                ended: None,
                last_seen: now,
                stop_reason: None,
            }),
        }
    }

    /// Its id.
    pub fn id(&self) -> u64 {
        self.id
    }

    fn lock(&self) -> MutexGuard<'_, Inner> {
        // A panic while holding the lock leaves plain data behind: keep using it.
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Its state.
    pub fn state(&self) -> JobState {
        self.lock().state
    }

    /// When it ended, if it has.
    pub fn ended(&self) -> Option<Instant> {
        self.lock().ended
    }

    /// The graded run, when done.
    pub fn run_result(&self) -> Option<Arc<GradedRun>> {
        self.lock().run.clone()
    }

    /// The request as it runs.
    pub fn echo(&self) -> &Echo {
        &self.echo
    }

    /// Asks the run to stop (it ends as `stopped` at the optimiser's next step or check).
    pub fn request_stop(&self) {
        let mut s = self.lock();
        if s.state == JobState::Running && s.stop_reason.is_none() {
            s.stop_reason = Some(stopped(
                "grading stopped by request".into(),
                "run it again to start over",
            ));
        }
        self.stop.store(true, Ordering::Relaxed);
    }

    /// The view a poll answers; polling keeps a running job alive.
    pub fn view(&self) -> GradedView {
        let mut s = self.lock();
        s.last_seen = Instant::now();
        let end = s.ended.unwrap_or_else(Instant::now);
        GradedView {
            id: self.id,
            state: s.state,
            stopping: s.state == JobState::Running && self.stop.load(Ordering::Relaxed),
            elapsed: end.duration_since(self.started).as_secs_f64(),
            request: self.echo.clone(),
            progress: s.progress,
            snapshot: s.snapshot.clone(),
            result: s.result_json.clone(),
            error: s.error.clone(),
        }
    }

    /// False once the run must stop: asked to, out of time, or nobody polled for too long
    /// (the reason is recorded the first time).
    fn keep_going(&self) -> bool {
        if self.stop.load(Ordering::Relaxed) {
            return false;
        }
        let limits = &self.limits;
        let mut s = self.lock();
        let reason = if self.started.elapsed() > limits.max_run {
            Some(stopped(
                format!(
                    "grading stopped at this server's time limit of {} s",
                    limits.max_run.as_secs_f64()
                ),
                "ask for fewer iterations or a smaller region, or run `isogami graded` from \
                 the command line",
            ))
        } else if s.last_seen.elapsed() > limits.abandon {
            Some(stopped(
                format!(
                    "grading stopped: nobody asked for its progress for {} s",
                    limits.abandon.as_secs_f64()
                ),
                "keep the page open while it runs",
            ))
        } else {
            None
        };
        match reason {
            Some(r) => {
                s.stop_reason = Some(r);
                self.stop.store(true, Ordering::Relaxed);
                false
            }
            None => true,
        }
    }

    /// Takes a progress report (a snapshot when the last is old enough); false when the run
    /// must stop.
    fn report(&self, p: &GradedProgress) -> bool {
        let due = {
            let mut s = self.lock();
            s.progress = Some(ProgressView {
                iteration: p.iteration,
                max_iterations: p.max_iterations,
                cost: p.cost,
                stage: p.stage,
                stages: p.stages,
            });
            s.last_snapshot
                .is_none_or(|t| t.elapsed() >= self.limits.snapshot_every)
        };
        if due {
            // Cloning the sheet happens outside the lock: polls are not held up by it.
            let sheet = p.sheet();
            let count = self.lock().snapshot.as_ref().map_or(0, |s| s.count) + 1;
            let snapshot = Snapshot::of(&sheet, count, p.iteration, p.cost);
            let mut s = self.lock();
            s.snapshot = Some(snapshot);
            s.last_snapshot = Some(Instant::now());
        }
        self.keep_going()
    }

    fn end(&self, state: JobState, error: Option<JobError>) {
        let mut s = self.lock();
        if s.state == JobState::Running {
            s.state = state;
            s.error = error;
            s.ended = Some(Instant::now());
        }
    }

    fn finish(&self, run: GradedRun) {
        match serde_json::to_value(&run) {
            Ok(v) => {
                let mut s = self.lock();
                let count = s.snapshot.as_ref().map_or(0, |s| s.count) + 1;
                let iteration = run.report.iterations;
                s.snapshot = Some(Snapshot::of(
                    &run.sheet,
                    count,
                    iteration,
                    run.report.cost[1],
                ));
                s.result_json = Some(v);
                s.run = Some(Arc::new(run));
                drop(s);
                self.end(JobState::Done, None);
            }
            Err(e) => self.end(
                JobState::Failed,
                Some(ApiError::internal(format!("result JSON: {e}")).into()),
            ),
        }
    }

    /// Runs the job on this thread. Ends the job however the run ends (a panic too).
    pub fn run(self: &Arc<Self>, request: &GradedRequest) {
        struct EndGuard<'a>(&'a GradedJob);
        impl Drop for EndGuard<'_> {
            fn drop(&mut self) {
                self.0.end(
                    JobState::Failed,
                    Some(ApiError::internal("the graded-sheet task failed").into()),
                );
            }
        }
        let _guard = EndGuard(self);
        let keep_going = || self.keep_going();
        match graded_sheet(request, &mut |p| self.report(p), &keep_going) {
            Ok(run) => self.finish(run),
            Err(e) if e.is_cancelled() => {
                let reason = self.lock().stop_reason.clone();
                let reason = reason.unwrap_or_else(|| {
                    stopped("grading stopped".into(), "run it again to start over")
                });
                self.end(JobState::Stopped, Some(reason));
            }
            Err(e) => self.end(JobState::Failed, Some(explain(&e))),
        }
    }
}

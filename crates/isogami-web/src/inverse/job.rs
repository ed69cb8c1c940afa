//! One inverse-design job: the run on the blocking pool, what it has done so far (the
//! library's progress, the evaluations counted across stages, the best objective over
//! evaluations), why it stopped, and its result in the form `isogami inverse --json` prints
//! (the result, plus `saved` once saved).

use super::limits::InverseLimits;
use super::view::{Echo, JobError, JobState, JobView};
use crate::error::ApiError;
use crate::state::AppState;
use axum::http::StatusCode;
use isogami::inverse::InverseResult;
use isogami::inverse::{inverse_design, InverseError, InverseProgress, InverseRequest};
use isogami_store::SavedDesign;
use serde_json::Value;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Instant;

/// Most points of the best-objective history kept (improvements only, so rarely reached).
const MAX_HISTORY: usize = 2000;

struct Inner {
    state: JobState,
    progress: Option<InverseProgress>,
    /// Evaluations of the stages before the current one.
    before_stage: usize,
    evaluations: usize,
    history: Vec<[f64; 2]>,
    result: Option<Arc<InverseResult>>,
    result_json: Option<Value>,
    error: Option<JobError>,
    ended: Option<Instant>,
    last_seen: Instant,
    stop_reason: Option<JobError>,
}

/// One inverse-design run and what it has done.
pub struct Job {
    id: u64,
    echo: Echo,
    started: Instant,
    limits: InverseLimits,
    stop: AtomicBool,
    inner: Mutex<Inner>,
}

impl std::fmt::Debug for Job {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Job").field("id", &self.id).finish()
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
    let hint = match e {
        isogami::Error::Inverse(
            InverseError::NoCandidates
            | InverseError::NoneAdmitted { .. }
            | InverseError::NothingValid { .. },
        ) => "loosen the target's constraints, or explore more families into the database",
        _ => "try another target or smaller numbers",
    };
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "inverse_failed",
        e.to_string(),
        hint,
    )
    .into()
}

impl Job {
    /// A running job `id` for `request`.
    pub fn new(id: u64, request: &InverseRequest, limits: InverseLimits) -> Job {
        let now = Instant::now();
        Job {
            id,
            echo: Echo::of(request),
            started: now,
            limits,
            stop: AtomicBool::new(false),
            inner: Mutex::new(Inner {
                state: JobState::Running,
                progress: None,
                before_stage: 0,
                evaluations: 0,
                history: Vec::new(),
                result: None,
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

    /// Asks the run to stop (it ends as `stopped` after the evaluations in flight).
    pub fn request_stop(&self) {
        let mut s = self.lock();
        if s.state == JobState::Running && s.stop_reason.is_none() {
            s.stop_reason = Some(stopped(
                "inverse design stopped by request".into(),
                "run it again to start over",
            ));
        }
        self.stop.store(true, Ordering::Relaxed);
    }

    /// The result, when done.
    pub fn result(&self) -> Option<Arc<InverseResult>> {
        self.lock().result.clone()
    }

    /// Records what saving the result stored; the view's result carries it as `saved` (left
    /// out when empty, as the CLI does).
    pub fn set_saved(&self, saved: &[SavedDesign]) {
        if saved.is_empty() {
            return;
        }
        let mut s = self.lock();
        if let Some(Value::Object(fields)) = s.result_json.as_mut() {
            if let Ok(v) = serde_json::to_value(saved) {
                fields.insert("saved".into(), v);
            }
        }
    }

    /// The view a poll answers; polling keeps a running job alive.
    pub fn view(&self) -> JobView {
        let mut s = self.lock();
        s.last_seen = Instant::now();
        let end = s.ended.unwrap_or_else(Instant::now);
        JobView {
            id: self.id,
            state: s.state,
            stopping: s.state == JobState::Running && self.stop.load(Ordering::Relaxed),
            elapsed: end.duration_since(self.started).as_secs_f64(),
            request: self.echo.clone(),
            progress: s.progress.clone(),
            evaluations: s.evaluations,
            history: s.history.clone(),
            result: s.result_json.clone(),
            error: s.error.clone(),
        }
    }

    /// Takes a progress report; false when the run must stop (asked to, out of time, or
    /// nobody polled for too long).
    fn report(&self, p: &InverseProgress) -> bool {
        let mut s = self.lock();
        let stage_changed = s.progress.as_ref().is_some_and(|q| q.stage != p.stage);
        if stage_changed {
            s.before_stage = s.evaluations;
        }
        let before_best = s.progress.as_ref().and_then(|q| q.best);
        s.evaluations = s.before_stage + p.done;
        if let Some(best) = p.best {
            if before_best.is_none_or(|b| best < b) && s.history.len() < MAX_HISTORY {
                let n = s.evaluations as f64;
                s.history.push([n, best]);
            }
        }
        s.progress = Some(p.clone());
        if self.stop.load(Ordering::Relaxed) {
            return false;
        }
        let limits = &self.limits;
        let reason = if self.started.elapsed() > limits.max_run {
            Some(stopped(
                format!(
                    "inverse design stopped at this server's time limit of {} s",
                    limits.max_run.as_secs_f64()
                ),
                "ask for a smaller budget or fewer topologies, or run `isogami inverse` from the command line",
            ))
        } else if s.last_seen.elapsed() > limits.abandon {
            Some(stopped(
                format!(
                    "inverse design stopped: nobody asked for its progress for {} s",
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

    fn end(&self, state: JobState, error: Option<JobError>) {
        let mut s = self.lock();
        if s.state == JobState::Running {
            s.state = state;
            s.error = error;
            s.ended = Some(Instant::now());
        }
    }

    fn finish(&self, result: InverseResult) {
        let json = serde_json::to_value(&result);
        let mut s = self.lock();
        match json {
            Ok(v) => {
                s.result_json = Some(v);
                s.result = Some(Arc::new(result));
                drop(s);
                self.end(JobState::Done, None);
            }
            Err(e) => {
                drop(s);
                self.end(
                    JobState::Failed,
                    Some(ApiError::internal(format!("result JSON: {e}")).into()),
                );
            }
        }
    }

    /// Runs the job on this thread: the database's candidates for the target's constraints,
    /// then the library's inverse design. Ends the job however the run ends (a panic too).
    pub fn run(self: &Arc<Job>, state: &AppState, request: &InverseRequest) {
        struct EndGuard<'a>(&'a Job);
        impl Drop for EndGuard<'_> {
            fn drop(&mut self) {
                self.0.end(
                    JobState::Failed,
                    Some(ApiError::internal("the inverse-design task failed").into()),
                );
            }
        }
        let _guard = EndGuard(self);
        let constraints = &request.target.constraints;
        let candidates = match state.read_now(|s| Ok(s.inverse_candidates(constraints)?)) {
            Ok(c) => c,
            Err(e) => return self.end(JobState::Failed, Some(e.into())),
        };
        let outcome = inverse_design(&candidates, request, &mut |p| self.report(p));
        match outcome {
            Ok(result) => self.finish(result),
            Err(e) if e.is_cancelled() => {
                let reason = self.lock().stop_reason.clone();
                let reason = reason.unwrap_or_else(|| {
                    stopped(
                        "inverse design stopped".into(),
                        "run it again to start over",
                    )
                });
                self.end(JobState::Stopped, Some(reason));
            }
            Err(e) => self.end(JobState::Failed, Some(explain(&e))),
        }
    }
}

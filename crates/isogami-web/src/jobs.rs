//! What the server's long jobs share, inverse design ([`crate::inverse`]) and graded sheets
//! ([`crate::graded`]) alike: a registry of jobs by id ([`JobRegistry`]: a cap on those
//! running, ended ones forgotten after a while) and one job's life ([`Job`]: running until
//! done, failed or stopped — asked to, at the time limit, or abandoned by its pollers — with
//! why). What a kind of job runs, what its progress holds and what a poll answers are its own
//! module's; [`JobKind`] gives the rest: its caps, its words and its errors.

use crate::error::{ApiError, ApiResult};
use axum::http::StatusCode;
use serde::Serialize;
use serde_json::Value;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// Where a job is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum JobState {
    /// Running (also while a requested stop takes effect).
    Running,
    /// Ended with a result.
    Done,
    /// Ended with an error.
    Failed,
    /// Stopped before the end (asked to, at the time limit, or abandoned).
    Stopped,
}

/// An error as the API's error answers carry it.
#[derive(Debug, Clone, Serialize)]
pub struct JobError {
    /// One line naming the problem.
    pub error: String,
    /// Machine-readable kind.
    pub kind: &'static str,
    /// What to do.
    pub hint: String,
}

impl From<ApiError> for JobError {
    fn from(e: ApiError) -> JobError {
        JobError {
            error: e.message,
            kind: e.kind,
            hint: e.hint,
        }
    }
}

/// The caps of one kind's jobs that the registry and the runs obey.
#[derive(Debug, Clone, Copy)]
pub struct Caps {
    /// Jobs running at once (at least one).
    pub max_running: usize,
    /// Longest a job runs before it is stopped.
    pub max_run: Duration,
    /// A running job nobody polls for this long is stopped.
    pub abandon: Duration,
    /// An ended job is forgotten this long after it ended.
    pub keep: Duration,
    /// Most ended jobs remembered (the oldest go first).
    pub max_kept: usize,
}

/// One kind of job: what it keeps, its caps and its words.
pub trait JobKind: 'static {
    /// This server's caps of the kind.
    type Limits: Copy;
    /// The request as run, for the view.
    type Echo;
    /// What a run has done so far (progress, its result), kept under the job's lock.
    type Data: Default;
    /// Names a job in a 404 and in a task's failure: `inverse-design`.
    const NOUN: &'static str;
    /// The endpoint that starts one, for a 404's hint: `/api/inverse`.
    const ENDPOINT: &'static str;
    /// What stopped, in a stop's reason: `inverse design`.
    const RUN: &'static str;
    /// What to do after this server's time limit stopped a run.
    const TIME_LIMIT_HINT: &'static str;
    /// The caps of `limits` the registry and the runs obey.
    fn caps(limits: &Self::Limits) -> Caps;
    /// 409 `busy`: the most jobs run (`running`, their ids, oldest first; never empty).
    fn busy(running: &[u64]) -> ApiError;
    /// A library error that ended a run, in the API's terms.
    fn explain(e: &isogami::Error) -> JobError;
}

/// The answer to a job just started: 202 `{id, state}`.
pub fn accepted(id: u64) -> (StatusCode, axum::Json<Value>) {
    (
        StatusCode::ACCEPTED,
        axum::Json(serde_json::json!({ "id": id, "state": JobState::Running })),
    )
}

/// A stop's reason.
fn stopped(message: String, hint: &str) -> JobError {
    JobError {
        error: message,
        kind: "stopped",
        hint: hint.to_string(),
    }
}

struct Inner<D> {
    state: JobState,
    error: Option<JobError>,
    ended: Option<Instant>,
    last_seen: Instant,
    stop_reason: Option<JobError>,
    data: D,
}

/// What every poll answers besides the kind's own fields.
#[derive(Debug, Clone)]
pub struct Status {
    /// The job's id.
    pub id: u64,
    /// Where it is.
    pub state: JobState,
    /// A stop was asked for and the run has not ended yet.
    pub stopping: bool,
    /// Seconds since the job started (until it ended).
    pub elapsed: f64,
    /// When failed or stopped: why.
    pub error: Option<JobError>,
}

/// How a run's work fails: refused before the library ran (the database, say), or the
/// library's error (a cancellation among them).
#[derive(Debug)]
pub enum RunError {
    /// Refused before the library ran.
    Refused(ApiError),
    /// The library's error.
    Library(isogami::Error),
}

impl From<ApiError> for RunError {
    fn from(e: ApiError) -> RunError {
        RunError::Refused(e)
    }
}

impl From<isogami::Error> for RunError {
    fn from(e: isogami::Error) -> RunError {
        RunError::Library(e)
    }
}

/// One run of kind `K` and what it has done.
pub struct Job<K: JobKind> {
    id: u64,
    echo: K::Echo,
    started: Instant,
    limits: K::Limits,
    stop: AtomicBool,
    inner: Mutex<Inner<K::Data>>,
}

impl<K: JobKind> std::fmt::Debug for Job<K> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Job")
            .field("kind", &K::NOUN)
            .field("id", &self.id)
            .finish()
    }
}

impl<K: JobKind> Job<K> {
    fn new(id: u64, echo: K::Echo, limits: K::Limits) -> Self {
        let now = Instant::now();
        Job {
            id,
            echo,
            started: now,
            limits,
            stop: AtomicBool::new(false),
            inner: Mutex::new(Inner {
                state: JobState::Running,
                error: None,
                ended: None,
                last_seen: now,
                stop_reason: None,
                data: K::Data::default(),
            }),
        }
    }

    /// Its id.
    pub fn id(&self) -> u64 {
        self.id
    }

    /// The request as it runs.
    pub fn echo(&self) -> &K::Echo {
        &self.echo
    }

    /// The caps it runs under.
    pub fn limits(&self) -> &K::Limits {
        &self.limits
    }

    fn lock(&self) -> MutexGuard<'_, Inner<K::Data>> {
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

    /// `f` of what the run has done, under the job's lock.
    pub fn with_data<R>(&self, f: impl FnOnce(&mut K::Data) -> R) -> R {
        f(&mut self.lock().data)
    }

    /// `view` of its status and what the run has done, read at once; polling keeps a
    /// running job alive.
    pub fn poll<V>(&self, view: impl FnOnce(Status, &K::Data) -> V) -> V {
        let mut s = self.lock();
        s.last_seen = Instant::now();
        let end = s.ended.unwrap_or_else(Instant::now);
        let status = Status {
            id: self.id,
            state: s.state,
            stopping: s.state == JobState::Running && self.stop.load(Ordering::Relaxed),
            elapsed: end.duration_since(self.started).as_secs_f64(),
            error: s.error.clone(),
        };
        view(status, &s.data)
    }

    /// Asks the run to stop (it ends as `stopped` at its next check).
    pub fn request_stop(&self) {
        let mut s = self.lock();
        if s.state == JobState::Running && s.stop_reason.is_none() {
            s.stop_reason = Some(stopped(
                format!("{} stopped by request", K::RUN),
                "run it again to start over",
            ));
        }
        self.stop.store(true, Ordering::Relaxed);
    }

    /// False once the run must stop: asked to, out of time, or nobody polled for too long
    /// (the reason is recorded the first time).
    pub fn keep_going(&self) -> bool {
        if self.stop.load(Ordering::Relaxed) {
            return false;
        }
        let caps = K::caps(&self.limits);
        let mut s = self.lock();
        let reason = if self.started.elapsed() > caps.max_run {
            Some(stopped(
                format!(
                    "{} stopped at this server's time limit of {} s",
                    K::RUN,
                    caps.max_run.as_secs_f64()
                ),
                K::TIME_LIMIT_HINT,
            ))
        } else if s.last_seen.elapsed() > caps.abandon {
            Some(stopped(
                format!(
                    "{} stopped: nobody asked for its progress for {} s",
                    K::RUN,
                    caps.abandon.as_secs_f64()
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

    /// Runs `work` on this thread and ends the job however it ends (a panic too): done once
    /// `keep` has stored its result and the result's JSON, stopped with the reason recorded
    /// when the library was cancelled, failed otherwise.
    pub fn run_with<R: Serialize>(
        &self,
        work: impl FnOnce() -> Result<R, RunError>,
        keep: impl FnOnce(&mut K::Data, R, Value),
    ) {
        struct EndGuard<'a, K: JobKind>(&'a Job<K>);
        impl<K: JobKind> Drop for EndGuard<'_, K> {
            fn drop(&mut self) {
                self.0.end(
                    JobState::Failed,
                    Some(ApiError::internal(format!("the {} task failed", K::NOUN)).into()),
                );
            }
        }
        let _guard = EndGuard(self);
        match work() {
            Ok(result) => match serde_json::to_value(&result) {
                Ok(json) => {
                    keep(&mut self.lock().data, result, json);
                    self.end(JobState::Done, None);
                }
                Err(e) => self.end(
                    JobState::Failed,
                    Some(ApiError::internal(format!("result JSON: {e}")).into()),
                ),
            },
            Err(RunError::Refused(e)) => self.end(JobState::Failed, Some(e.into())),
            Err(RunError::Library(e)) if e.is_cancelled() => {
                let reason = self.lock().stop_reason.clone();
                let reason = reason.unwrap_or_else(|| {
                    stopped(format!("{} stopped", K::RUN), "run it again to start over")
                });
                self.end(JobState::Stopped, Some(reason));
            }
            Err(RunError::Library(e)) => self.end(JobState::Failed, Some(K::explain(&e))),
        }
    }
}

struct Registry<K: JobKind> {
    next: u64,
    /// Oldest first.
    jobs: Vec<Arc<Job<K>>>,
}

/// Every job of kind `K` this server remembers: at most [`Caps::max_running`] running; ended
/// ones kept for [`Caps::keep`] (and at most [`Caps::max_kept`] of them), then forgotten.
pub struct JobRegistry<K: JobKind> {
    inner: Mutex<Registry<K>>,
}

impl<K: JobKind> Default for JobRegistry<K> {
    fn default() -> Self {
        JobRegistry {
            inner: Mutex::new(Registry {
                next: 0,
                jobs: Vec::new(),
            }),
        }
    }
}

impl<K: JobKind> std::fmt::Debug for JobRegistry<K> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let r = self.lock();
        f.debug_struct("JobRegistry")
            .field("next", &r.next)
            .field("jobs", &r.jobs)
            .finish()
    }
}

impl<K: JobKind> JobRegistry<K> {
    fn lock(&self) -> MutexGuard<'_, Registry<K>> {
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Forgets ended jobs past their keeping time, and the oldest ended beyond the count.
    fn prune(r: &mut Registry<K>, caps: &Caps) {
        r.jobs
            .retain(|j| j.ended().is_none_or(|t| t.elapsed() <= caps.keep));
        let ended = r.jobs.iter().filter(|j| j.ended().is_some()).count();
        let mut extra = ended.saturating_sub(caps.max_kept);
        r.jobs.retain(|j| {
            if extra > 0 && j.ended().is_some() {
                extra -= 1;
                false
            } else {
                true
            }
        });
    }

    /// A new running job for the request `echo` describes, or 409 `busy` while the most
    /// jobs run.
    pub fn start(&self, echo: K::Echo, limits: &K::Limits) -> ApiResult<Arc<Job<K>>> {
        let caps = K::caps(limits);
        let mut r = self.lock();
        Self::prune(&mut r, &caps);
        let running = Self::running_in(&r);
        if running.len() >= caps.max_running.max(1) {
            return Err(K::busy(&running));
        }
        r.next += 1;
        let job = Arc::new(Job::new(r.next, echo, *limits));
        r.jobs.push(job.clone());
        Ok(job)
    }

    /// The job `id`, or 404.
    pub fn get(&self, id: &str, limits: &K::Limits) -> ApiResult<Arc<Job<K>>> {
        let caps = K::caps(limits);
        let mut r = self.lock();
        Self::prune(&mut r, &caps);
        let n: Option<u64> = id.parse().ok();
        r.jobs
            .iter()
            .find(|j| Some(j.id()) == n)
            .cloned()
            .ok_or_else(|| {
                ApiError::new(
                    StatusCode::NOT_FOUND,
                    "not_found",
                    format!(
                        "no {} job {:?} on this server",
                        K::NOUN,
                        crate::filters::truncate(id)
                    ),
                    format!(
                        "jobs are forgotten {} minutes after they end; POST {} starts one",
                        caps.keep.as_secs() / 60,
                        K::ENDPOINT
                    ),
                )
            })
    }

    /// Asks every running job to stop (the server is shutting down: the runtime waits for
    /// its blocking tasks).
    pub fn stop_all(&self) {
        for j in &self.lock().jobs {
            j.request_stop();
        }
    }

    /// The running jobs' ids, oldest first.
    pub fn running(&self) -> Vec<u64> {
        Self::running_in(&self.lock())
    }

    fn running_in(r: &Registry<K>) -> Vec<u64> {
        r.jobs
            .iter()
            .filter(|j| j.state() == JobState::Running)
            .map(|j| j.id())
            .collect()
    }
}

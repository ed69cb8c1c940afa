//! One inverse-design job: the run on the blocking pool, what it has done so far (the
//! library's progress, the evaluations counted across stages, the best objective over
//! evaluations), why it stopped, and its result in the form `isogami inverse --json` prints
//! (the result, plus `saved` once saved). The registry, stopping and the job's life are
//! [`crate::jobs`]'.

use super::limits::InverseLimits;
use super::view::{Echo, JobView};
use crate::error::ApiError;
use crate::jobs::{Caps, JobError, JobKind, JobRegistry};
use crate::state::AppState;
use axum::http::StatusCode;
use isogami::inverse::InverseResult;
use isogami::inverse::{inverse_design, InverseError, InverseProgress, InverseRequest};
use isogami_store::SavedDesign;
use serde_json::Value;
use std::sync::Arc;

/// Most points of the best-objective history kept (improvements only, so rarely reached).
const MAX_HISTORY: usize = 2000;

/// What an inverse-design run has done so far.
#[derive(Default)]
pub struct Data {
    progress: Option<InverseProgress>,
    /// Evaluations of the stages before the current one.
    before_stage: usize,
    evaluations: usize,
    history: Vec<[f64; 2]>,
    result: Option<Arc<InverseResult>>,
    result_json: Option<Value>,
}

/// Inverse design as a kind of job: one at a time.
#[derive(Debug)]
pub enum Inverse {}

impl JobKind for Inverse {
    type Limits = InverseLimits;
    type Echo = Echo;
    type Data = Data;
    const NOUN: &'static str = "inverse-design";
    const ENDPOINT: &'static str = "/api/inverse";
    const RUN: &'static str = "inverse design";
    const TIME_LIMIT_HINT: &'static str = "ask for a smaller budget or fewer topologies, or run \
        `isogami inverse` from the command line";

    fn caps(limits: &InverseLimits) -> Caps {
        Caps {
            max_running: 1,
            max_run: limits.max_run,
            abandon: limits.abandon,
            keep: limits.keep,
            max_kept: limits.max_kept,
        }
    }

    fn busy(running: &[u64]) -> ApiError {
        ApiError::new(
            StatusCode::CONFLICT,
            "busy",
            format!(
                "an inverse design is already running on this server (job {})",
                running[0]
            ),
            format!(
                "wait for it to end, or stop it (DELETE /api/inverse/{})",
                running[0]
            ),
        )
    }

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
}

/// One inverse-design run and what it has done.
pub type Job = crate::jobs::Job<Inverse>;

/// Every inverse-design job this server remembers.
pub type Jobs = JobRegistry<Inverse>;

impl Job {
    /// The result, when done.
    pub fn result(&self) -> Option<Arc<InverseResult>> {
        self.with_data(|d| d.result.clone())
    }

    /// Records what saving the result stored; the view's result carries it as `saved` (left
    /// out when empty, as the CLI does).
    pub fn set_saved(&self, saved: &[SavedDesign]) {
        if saved.is_empty() {
            return;
        }
        self.with_data(|d| {
            if let Some(Value::Object(fields)) = d.result_json.as_mut() {
                if let Ok(v) = serde_json::to_value(saved) {
                    fields.insert("saved".into(), v);
                }
            }
        });
    }

    /// The view a poll answers; polling keeps a running job alive.
    pub fn view(&self) -> JobView {
        self.poll(|s, d| JobView {
            id: s.id,
            state: s.state,
            stopping: s.stopping,
            elapsed: s.elapsed,
            request: self.echo().clone(),
            progress: d.progress.clone(),
            evaluations: d.evaluations,
            history: d.history.clone(),
            result: d.result_json.clone(),
            error: s.error,
        })
    }

    /// Takes a progress report; false when the run must stop (asked to, out of time, or
    /// nobody polled for too long).
    fn report(&self, p: &InverseProgress) -> bool {
        self.with_data(|d| {
            let stage_changed = d.progress.as_ref().is_some_and(|q| q.stage != p.stage);
            if stage_changed {
                d.before_stage = d.evaluations;
            }
            let before_best = d.progress.as_ref().and_then(|q| q.best);
            d.evaluations = d.before_stage + p.done;
            if let Some(best) = p.best {
                if before_best.is_none_or(|b| best < b) && d.history.len() < MAX_HISTORY {
                    let n = d.evaluations as f64;
                    d.history.push([n, best]);
                }
            }
            d.progress = Some(p.clone());
        });
        self.keep_going()
    }

    /// Runs the job on this thread: the database's candidates for the target's constraints,
    /// then the library's inverse design. Ends the job however the run ends (a panic too).
    pub fn run(self: &Arc<Job>, state: &AppState, request: &InverseRequest) {
        self.run_with(
            || {
                let constraints = &request.target.constraints;
                let candidates = state.read_now(|s| Ok(s.inverse_candidates(constraints)?))?;
                Ok(inverse_design(&candidates, request, &mut |p| {
                    self.report(p)
                })?)
            },
            |d, result: InverseResult, json| {
                d.result_json = Some(json);
                d.result = Some(Arc::new(result));
            },
        );
    }
}

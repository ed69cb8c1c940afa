//! What a poll of an inverse-design job answers: its state, the request as run, the progress,
//! the result in the CLI's `--json` form, and why it failed or stopped (the states and errors
//! every kind of job shares are [`crate::jobs`]').

use super::body::InverseBody;
use crate::jobs::{JobError, JobState};
use isogami::inverse::{InverseProgress, InverseRequest};
use serde::Serialize;
use serde_json::Value;

/// The request as run, for the view (the target in canonical text).
#[derive(Debug, Clone, Serialize)]
pub struct Echo {
    /// The target in canonical text.
    pub target: String,
    /// Topologies kept and refined.
    pub top: usize,
    /// Evaluations per refined design.
    pub budget: usize,
    /// Pre-screened designs re-deployed (the default resolved).
    pub confirm: usize,
    /// Screened designs triaged (the default resolved).
    pub triage: usize,
    /// Fresh shape samples per topology.
    pub samples: usize,
    /// Kerf the designs are deployed with (raised to the target's minimum).
    pub kerf: f64,
    /// Whether the kerf is refined too.
    pub refine_kerf: bool,
    /// The body that started the job, as given (the target text trimmed; a field left out
    /// null): what a page restores its form and command line from.
    pub body: InverseBody,
}

impl Echo {
    /// The request `r` as it runs (defaults resolved), started by `body`.
    pub fn of(r: &InverseRequest, body: &InverseBody) -> Echo {
        Echo {
            target: r.target.to_string(),
            top: r.top,
            budget: r.budget,
            confirm: r.confirm_count(),
            triage: r.triage_count(),
            samples: r.samples,
            kerf: r.effective_kerf(),
            refine_kerf: r.refine_kerf,
            body: body.echo(),
        }
    }
}

/// What a poll answers (`GET /api/inverse/{id}`).
#[derive(Debug, Clone, Serialize)]
pub struct JobView {
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
    /// The library's last progress report: stage, done and total in the stage, best
    /// objective, leaders.
    pub progress: Option<InverseProgress>,
    /// Evaluations so far, every stage counted.
    pub evaluations: usize,
    /// [evaluations, best objective] at every improvement of the run's best.
    pub history: Vec<[f64; 2]>,
    /// When done: the result as `isogami inverse --json` prints it.
    pub result: Option<Value>,
    /// When failed or stopped: why.
    pub error: Option<JobError>,
}

//! Inverse design (the paper's future work, §7): from a target behaviour to designs that have
//! it, by global screening of enumerated designs followed by local refinement of the tile
//! shape with the topology fixed.
//!
//! - [`target`]: what a user asks for — weighted goals (extreme expansion, Poisson-like
//!   behaviour, a locked shape, an expansion path) and constraints (families, cells, tile
//!   count, rotation margin, kerf, hinge clearance); compact text ([`parse`]) and JSON.
//! - [`objective`]: the scalar to minimise, computed from a deployment report.
//! - [`evaluate`]: one design at one kerf — valid (the exploration's own checks: well-shaped
//!   tiles, mobility 1, not locked, expansion threshold; then the constraints) and scored, or
//!   invalid with a typed reason.
//! - [`screen`]: stage 1 — pre-screen candidates on their stored reports, re-deploy the best,
//!   optionally sample fresh shapes, keep the best k of different topologies.
//! - [`refine`]: stage 2 — Nelder–Mead (argmin) on the shape parameters (and the kerf).
//! - [`inverse_design`]: the one entry point; every returned design is re-deployed and
//!   checked at the end.
//!
//! Plain data in and out; candidates come from the caller (the design database supplies
//! them through `isogami-store`). Evaluations run in parallel on rayon's pool; the caller's
//! progress callback runs on the calling thread and can stop the run.
//!
//! ```
//! use isogami::api::resolve_design;
//! use isogami::inverse::{inverse_design, Candidate, InverseRequest, Target};
//!
//! let design = resolve_design("rotating-squares")?;
//! let candidates = [Candidate { topology: design.to_string(), design, report: None }];
//! let request = InverseRequest::new(Target::parse("area")?);
//! let result = inverse_design(&candidates, &request, &mut |_| true)?;
//! let best = &result.results[0].after;
//! assert!((best.measures.max_area_ratio - 2.0).abs() < 2e-3); // 45°: (cos φ + sin φ)² = 2
//! # Ok::<(), isogami::Error>(())
//! ```

pub mod error;
pub mod evaluate;
mod monitor;
pub mod objective;
pub mod parse;
pub mod refine;
pub mod request;
pub mod screen;
pub mod target;

pub use error::InverseError;
pub use evaluate::{Evaluation, Evaluator, Invalidity, Outcome};
pub use objective::{goal_value, score, Score, Unmet};
pub use request::{
    InverseProgress, InverseRequest, InverseResult, Measures, RefinedDesign, Scored, Source,
    Stage,
};
pub use screen::Candidate;
pub use target::{Constraints, Goal, PathPoint, Target, Term};

use crate::contact::ContactSettings;
use evaluate::Stopped;
use monitor::{monitored, Monitor};
use rayon::prelude::*;
use screen::Screened;
use std::time::Instant;

/// Relative agreement required between a refined design's objective and its re-deployment.
const VERIFY_TOLERANCE: f64 = 1e-9;

/// Finds designs for `request.target` among `candidates` and refines them (see the module
/// documentation). `progress` is called on this thread after every evaluation; when it
/// returns `false` the run stops with [`InverseError::Cancelled`].
///
/// Errors: an invalid request, no candidate passing the constraints, no valid design among
/// the screened ones, or the stop.
pub fn inverse_design(
    candidates: &[Candidate],
    request: &InverseRequest,
    progress: &mut dyn FnMut(&InverseProgress) -> bool,
) -> crate::Result<InverseResult> {
    request.validate()?;
    if candidates.is_empty() {
        return Err(InverseError::NoCandidates { why: "given" }.into());
    }
    let start = Instant::now();
    let mut settings = request.settings;
    let kerf = request.effective_kerf();
    settings.deploy.contact = ContactSettings {
        kerf,
        dhat: 0.5 * kerf,
        ..settings.deploy.contact
    };
    let ev = Evaluator {
        target: &request.target,
        settings,
    };
    let run = monitored(progress, |monitor| run(candidates, request, &ev, monitor));
    let mut result = match run {
        Ok(r) => r?,
        Err(Stopped) => return Err(InverseError::Cancelled.into()),
    };
    result.seconds = start.elapsed().as_secs_f64();
    Ok(result)
}

type Run = Result<Result<InverseResult, InverseError>, Stopped>;

fn run(
    candidates: &[Candidate],
    request: &InverseRequest,
    ev: &Evaluator<'_>,
    monitor: &Monitor<'_>,
) -> Run {
    let (screened, counts) = screen::screen(candidates, request, ev, monitor)?;
    if counts.admitted == 0 {
        return Ok(Err(InverseError::NoCandidates {
            why: "pass the constraints",
        }));
    }
    if screened.is_empty() {
        return Ok(Err(InverseError::NothingValid {
            screened: counts.confirmed,
        }));
    }
    monitor.stage(Stage::Refine, screened.len() * request.budget);
    let refined = screened
        .par_iter()
        .map(|s| refine::refine(&s.evaluation, request.budget, request.refine_kerf, ev, monitor))
        .collect::<Result<Vec<_>, _>>()?;
    monitor.stage(Stage::Verify, refined.len());
    let mut results = screened
        .par_iter()
        .zip(refined)
        .map(|(s, r)| finish(s, r, ev, monitor))
        .collect::<Result<Vec<_>, _>>()?;
    results.sort_by(|a, b| a.after.objective.total_cmp(&b.after.objective));
    for (i, r) in results.iter_mut().enumerate() {
        r.rank = i + 1;
    }
    let evaluations = counts.confirmed
        + counts.sampled
        + results.iter().map(|r| r.evaluations + 1).sum::<usize>();
    Ok(Ok(InverseResult {
        target: request.target.to_string(),
        kerf: request.effective_kerf(),
        candidates: candidates.len(),
        admitted: counts.admitted,
        prescored: counts.prescored,
        confirmed: counts.confirmed,
        confirmed_valid: counts.confirmed_valid,
        sampled: counts.sampled,
        evaluations,
        seconds: 0.0,
        results,
    }))
}

/// Scored form of a valid evaluation.
fn scored(e: &Evaluation) -> Option<Scored> {
    match &e.outcome {
        Outcome::Valid { score, report } => Some(Scored::new(&e.design, e.kerf, score, report)),
        Outcome::Invalid(_) => None,
    }
}

/// Re-deploys the refined design from scratch and checks it is valid with the same
/// objective; keeps the screened design if not (never expected: evaluations are
/// deterministic).
fn finish(
    s: &Screened,
    r: refine::Refined,
    ev: &Evaluator<'_>,
    monitor: &Monitor<'_>,
) -> Result<RefinedDesign, Stopped> {
    let before = scored(&s.evaluation).expect("screened designs are valid");
    let check = ev.evaluate(&r.best.design, r.best.kerf, monitor.stop_flag())?;
    monitor.evaluated(check.objective());
    let agrees = match (check.objective(), r.best.objective()) {
        (Some(a), Some(b)) => (a - b).abs() <= VERIFY_TOLERANCE * (1.0 + b.abs()),
        _ => false,
    };
    let after = if agrees {
        scored(&check).expect("checked valid")
    } else {
        before.clone()
    };
    Ok(RefinedDesign {
        rank: 0,
        topology: s.topology.clone(),
        family: s.evaluation.design.family,
        cell: s.evaluation.design.dims,
        source: s.source,
        improved: after.objective < before.objective,
        before,
        after,
        evaluations: r.evaluations,
        invalid_evaluations: r.invalid,
    })
}

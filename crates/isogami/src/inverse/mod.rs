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
//! - [`refine`]: stage 2 — Nelder–Mead (argmin) on the shape parameters (and the kerf):
//!   every screened design (up to two shapes per topology) first gets a quarter of the budget
//!   (triage), then the k topologies with the best triaged points go on from each of their
//!   starting shapes with the rest, so a topology whose screened design starts further from
//!   the target but can reach it is not lost to screening order, and a start that runs into
//!   a poorer basin does not hide its sibling.
//! - [`verdict`]: whether a design meets the target (every goal that names a value within
//!   its tolerance) and how far it misses.
//! - [`inverse_design`]: the one entry point; every returned design is re-deployed and
//!   checked at the end, and carries its verdict.
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
mod explain;
mod monitor;
pub mod objective;
pub mod parse;
pub mod refine;
pub mod request;
pub mod screen;
pub mod target;
pub mod verdict;

pub use error::InverseError;
pub use evaluate::{Evaluation, Evaluator, Invalidity, Outcome};
pub use objective::{goal_value, score, Score, Unmet};
pub use request::{
    InverseProgress, InverseRequest, InverseResult, Leader, Measures, RefinedDesign, Scored,
    Source, Stage, LEADERS,
};
pub use screen::Candidate;
pub use target::{Constraints, Goal, PathPoint, Target, Term};
pub use verdict::{GoalVerdict, Verdict};

use crate::contact::ContactSettings;
use evaluate::Stopped;
use monitor::{monitored, Monitor};
use rayon::prelude::*;
use screen::Screened;
use std::time::Instant;

/// Relative agreement required between a refined design's objective and its re-deployment.
const VERIFY_TOLERANCE: f64 = 1e-9;

/// Finds designs for `request.target` among `candidates` and refines them (see the module
/// documentation). `progress` is called on this thread after every evaluation (with the
/// stage, counts, best objective and the leading topologies' best designs so far); when it
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
        return Err(InverseError::NoCandidates.into());
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
    let shown = request.top.max(LEADERS);
    let run = monitored(progress, shown, |monitor| {
        run(candidates, request, &ev, monitor)
    });
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
        return Ok(Err(explain::none_admitted(
            candidates,
            &request.target.constraints,
        )));
    }
    if screened.is_empty() {
        return Ok(Err(InverseError::NothingValid {
            screened: counts.confirmed + counts.sampled,
            reasons: counts.invalid_reasons,
        }));
    }
    // Triage: every screened design gets a short refinement; the best `top` topologies go on
    // from their best triaged point with the rest of the budget (successive halving in two
    // rounds).
    let first_budget = |s: &Screened| triage_budget(request, &s.evaluation);
    monitor.stage(Stage::Triage, screened.iter().map(first_budget).sum());
    let first = screened
        .par_iter()
        .map(|s| {
            refine::refine(
                &s.evaluation,
                &s.topology,
                first_budget(s),
                request.refine_kerf,
                ev,
                monitor,
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut order: Vec<usize> = (0..screened.len()).collect();
    let objective = |i: usize| first[i].best.objective().unwrap_or(f64::INFINITY);
    order.sort_by(|&a, &b| objective(a).total_cmp(&objective(b)));
    // The `top` topologies with the best triaged points go on, from every one of their
    // starting shapes (two basins of one topology are both followed).
    let mut kept: Vec<&str> = Vec::new();
    for &i in &order {
        let t = screened[i].topology.as_str();
        if kept.len() < request.top && !kept.contains(&t) {
            kept.push(t);
        }
    }
    let going: Vec<usize> = order
        .iter()
        .copied()
        .filter(|&i| kept.contains(&screened[i].topology.as_str()))
        .collect();
    let planned_more = going
        .iter()
        .map(|&i| request.budget - first_budget(&screened[i]))
        .sum();
    monitor.stage(Stage::Refine, planned_more);
    let more = going
        .par_iter()
        .map(|&i| {
            let rest = request.budget - first_budget(&screened[i]);
            let topology = &screened[i].topology;
            refine::refine(
                &first[i].best,
                topology,
                rest,
                request.refine_kerf,
                ev,
                monitor,
            )
        })
        .collect::<Result<Vec<_>, Stopped>>()?;
    // Per kept topology: its best start (as screened), its best refined point, and every
    // evaluation spent on it.
    let mut per_topology = Vec::new();
    for t in &kept {
        let starts: Vec<usize> = (0..going.len())
            .filter(|&g| screened[going[g]].topology == *t)
            .collect();
        let screened_best = going
            .iter()
            .copied()
            .filter(|&i| screened[i].topology == *t)
            .min_by(|&a, &b| {
                let v = |i: usize| screened[i].evaluation.objective().unwrap_or(f64::INFINITY);
                v(a).total_cmp(&v(b))
            })
            .expect("a kept topology has a start");
        let best = starts
            .iter()
            .map(|&g| &more[g].best)
            .min_by(|a, b| {
                let v = |e: &Evaluation| e.objective().unwrap_or(f64::INFINITY);
                v(a).total_cmp(&v(b))
            })
            .expect("a kept topology has a start")
            .clone();
        let evaluations = starts
            .iter()
            .map(|&g| first[going[g]].evaluations + more[g].evaluations)
            .sum();
        let invalid = starts
            .iter()
            .map(|&g| first[going[g]].invalid + more[g].invalid)
            .sum();
        per_topology.push((
            screened_best,
            refine::Refined {
                best,
                evaluations,
                invalid,
            },
        ));
    }
    let triage_evaluations: usize = first.iter().map(|r| r.evaluations).sum();
    let more_evaluations: usize = more.iter().map(|r| r.evaluations).sum();
    monitor.stage(Stage::Verify, per_topology.len());
    let mut results = per_topology
        .into_par_iter()
        .map(|(i, r)| finish(&screened[i], r, ev, monitor))
        .collect::<Result<Vec<_>, _>>()?;
    results.sort_by(|a, b| a.after.objective.total_cmp(&b.after.objective));
    for (i, r) in results.iter_mut().enumerate() {
        r.rank = i + 1;
    }
    let evaluations =
        counts.confirmed + counts.sampled + triage_evaluations + more_evaluations + results.len();
    Ok(Ok(InverseResult {
        target: request.target.to_string(),
        met: results.first().and_then(|r| r.verdict.met),
        kerf: request.effective_kerf(),
        candidates: candidates.len(),
        admitted: counts.admitted,
        prescored: counts.prescored,
        confirmed: counts.confirmed,
        confirmed_valid: counts.confirmed_valid,
        sampled: counts.sampled,
        triaged: screened.len(),
        evaluations,
        seconds: 0.0,
        results,
    }))
}

/// Evaluations of the first (triage) refinement of one design: a quarter of the budget, at
/// least two simplices' worth (2 (n + 1) for n unknowns), never more than the budget.
fn triage_budget(request: &InverseRequest, start: &Evaluation) -> usize {
    let n = start.design.params.len() + usize::from(request.refine_kerf);
    (request.budget / 4).max(2 * (n + 1)).min(request.budget)
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
    monitor.evaluated(&check, &s.topology);
    let agrees = match (check.objective(), r.best.objective()) {
        (Some(a), Some(b)) => (a - b).abs() <= VERIFY_TOLERANCE * (1.0 + b.abs()),
        _ => false,
    };
    let after = if agrees {
        scored(&check).expect("checked valid")
    } else {
        before.clone()
    };
    let verdict = Verdict::of(ev.target, &after.terms);
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
        verdict,
    })
}

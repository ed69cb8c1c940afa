//! Stage 1, screening: rank candidate designs by the target and keep the best k of different
//! topologies.
//!
//! 1. **Constraints.** Candidates whose family, cell or tile count the target excludes are
//!    dropped.
//! 2. **Pre-screening.** A candidate that carries its stored deployment report is scored on
//!    it ([`score`]; no deployment). Candidates scored valid come first, best objective first;
//!    those without a report or not valid on it follow in the order given. This is only a
//!    pre-filter: the stored report may have been made with another kerf or settings.
//! 3. **Confirmation.** The first M of that order, at most two per topology, are evaluated
//!    afresh ([`Evaluator`]: validity, deployment, constraints, score), in parallel.
//! 4. **Fresh samples** (optional). For the best k confirmed topologies, shape parameters on
//!    a local grid around the confirmed design (each parameter at −span, 0, +span times its
//!    scale max(|default|, 0.25); the points that move fewest parameters first) are evaluated.
//! 5. **Selection.** Among every valid evaluation, the best two shapes of each topology, best
//!    first, go on to refinement (as many as the request triages): two starting shapes per
//!    topology, because a local search from the shape that scores best may end in another
//!    basin than one from a shape that scores worse.

use super::evaluate::{Evaluation, Evaluator, Stopped};
use super::explain::{self, tile_count};
use super::monitor::Monitor;
use super::objective::score;
use super::request::{InverseRequest, Source, Stage};
use crate::deploy::DeploymentReport;
use crate::math::Real;
use crate::topology::Design;
use rayon::prelude::*;
use std::collections::HashMap;

/// Most designs of one topology among the confirmed.
const PER_TOPOLOGY: usize = 2;

/// A design offered to inverse design, as a database holds it.
#[derive(Debug, Clone)]
pub struct Candidate {
    /// The design.
    pub design: Design,
    /// Spec of its topology at default shape (designs sharing it differ only in shape).
    pub topology: String,
    /// Its stored deployment report, when there is one (used to pre-screen).
    pub report: Option<DeploymentReport>,
}

/// A valid screened design.
#[derive(Debug, Clone)]
pub(crate) struct Screened {
    pub evaluation: Evaluation,
    pub topology: String,
    pub source: Source,
}

impl Screened {
    fn objective(&self) -> Real {
        self.evaluation.objective().unwrap_or(Real::INFINITY)
    }
}

/// Counts of the screening stages.
#[derive(Debug, Clone, Default)]
pub(crate) struct ScreenCounts {
    pub admitted: usize,
    pub prescored: usize,
    pub confirmed: usize,
    pub confirmed_valid: usize,
    pub sampled: usize,
    /// When no screened design is valid: why (see [`explain::invalid_reasons`]).
    pub invalid_reasons: String,
}

/// The pre-screening score: the objective on the stored report if it is valid there.
fn prescore(ev: &Evaluator<'_>, c: &Candidate) -> Option<Real> {
    let report = c.report.as_ref()?;
    if let Some(min_deg) = ev.target.constraints.min_rotation_deg {
        if report.max_tile_rotation.to_degrees() < min_deg {
            return None;
        }
    }
    score(ev.target, report).ok().map(|s| s.objective)
}

/// Evaluates `jobs` in parallel, reporting each to the monitor.
fn evaluate_all(
    ev: &Evaluator<'_>,
    kerf: Real,
    jobs: Vec<(Design, String, Source)>,
    monitor: &Monitor<'_>,
) -> Result<Vec<Screened>, Stopped> {
    jobs.into_par_iter()
        .map(|(design, topology, source)| {
            let evaluation = ev.evaluate(&design, kerf, monitor.stop_flag())?;
            monitor.evaluated(&evaluation, &topology);
            Ok(Screened {
                evaluation,
                topology,
                source,
            })
        })
        .collect()
}

/// Offsets in {−1, 0, 1}^p without the origin, fewest moved parameters first, then in
/// lexicographic order; at most `limit`.
pub(crate) fn local_offsets(p: usize, limit: usize) -> Vec<Vec<i8>> {
    let total = 3usize.saturating_pow(p as u32);
    let mut all: Vec<Vec<i8>> = (1..total.min(3usize.pow(6)))
        .map(|mut k| {
            (0..p)
                .map(|_| {
                    let d = (k % 3) as i8;
                    k /= 3;
                    [0, 1, -1][d as usize]
                })
                .collect()
        })
        .collect();
    all.sort_by_key(|o: &Vec<i8>| (o.iter().filter(|&&x| x != 0).count(), o.clone()));
    all.truncate(limit);
    all
}

/// Fresh shape samples of `around`'s topology (see the module documentation).
fn samples_around(around: &Design, count: usize, span: Real) -> Vec<Design> {
    let defaults = around.family.default_params();
    local_offsets(around.params.len(), count)
        .into_iter()
        .map(|o| {
            let params: Vec<Real> = around
                .params
                .iter()
                .zip(&defaults)
                .zip(&o)
                .map(|((p, d), &k)| p + Real::from(k) * span * d.abs().max(0.25))
                .collect();
            around.at_params(&params)
        })
        .collect()
}

/// The best `per` valid designs of each topology (distinct shapes), best first, at most `k`
/// in all.
fn best_per_topology(mut pool: Vec<Screened>, per: usize, k: usize) -> Vec<Screened> {
    pool.retain(|s| s.evaluation.is_valid());
    // Stable: ties keep the earlier (better pre-screened, or candidate before sample).
    pool.sort_by(|a, b| a.objective().total_cmp(&b.objective()));
    let mut count: HashMap<String, usize> = HashMap::new();
    let mut shapes = std::collections::HashSet::new();
    pool.into_iter()
        .filter(|s| {
            let n = count.entry(s.topology.clone()).or_default();
            let fresh = shapes.insert(s.evaluation.design.to_string());
            if fresh && *n < per {
                *n += 1;
                true
            } else {
                false
            }
        })
        .take(k)
        .collect()
}

/// Runs the screening stage.
pub(crate) fn screen(
    candidates: &[Candidate],
    request: &InverseRequest,
    ev: &Evaluator<'_>,
    monitor: &Monitor<'_>,
) -> Result<(Vec<Screened>, ScreenCounts), Stopped> {
    let c = &request.target.constraints;
    let admitted: Vec<&Candidate> = candidates
        .iter()
        .filter(|x| c.admits_cell(x.design.family, x.design.dims, tile_count(&x.design)))
        .collect();
    let mut counts = ScreenCounts {
        admitted: admitted.len(),
        ..ScreenCounts::default()
    };
    let scores: Vec<Option<Real>> = admitted.par_iter().map(|x| prescore(ev, x)).collect();
    counts.prescored = admitted.iter().filter(|x| x.report.is_some()).count();
    let mut order: Vec<usize> = (0..admitted.len()).collect();
    // Valid pre-scores first, best first; the rest in the order given (stable sort).
    order.sort_by(|&a, &b| match (scores[a], scores[b]) {
        (Some(x), Some(y)) => x.total_cmp(&y),
        (Some(_), None) => std::cmp::Ordering::Less,
        (None, Some(_)) => std::cmp::Ordering::Greater,
        (None, None) => std::cmp::Ordering::Equal,
    });
    let mut per_topology: HashMap<&str, usize> = HashMap::new();
    let mut jobs = Vec::new();
    for &i in &order {
        if jobs.len() >= request.confirm_count() {
            break;
        }
        let x = admitted[i];
        let n = per_topology.entry(x.topology.as_str()).or_default();
        if *n < PER_TOPOLOGY {
            *n += 1;
            jobs.push((x.design.clone(), x.topology.clone(), Source::Candidate));
        }
    }
    let kerf = request.effective_kerf();
    monitor.stage(Stage::Confirm, jobs.len());
    counts.confirmed = jobs.len();
    let mut pool = evaluate_all(ev, kerf, jobs, monitor)?;
    counts.confirmed_valid = pool.iter().filter(|s| s.evaluation.is_valid()).count();

    if request.samples > 0 {
        let best = best_per_topology(pool.clone(), 1, request.top);
        let jobs: Vec<(Design, String, Source)> = best
            .iter()
            .flat_map(|s| {
                samples_around(&s.evaluation.design, request.samples, request.sample_span)
                    .into_iter()
                    .map(|d| (d, s.topology.clone(), Source::Sample))
            })
            .collect();
        monitor.stage(Stage::Sample, jobs.len());
        counts.sampled = jobs.len();
        pool.extend(evaluate_all(ev, kerf, jobs, monitor)?);
    }
    if !pool.iter().any(|s| s.evaluation.is_valid()) {
        counts.invalid_reasons = explain::invalid_reasons(
            pool.iter().map(|s| &s.evaluation),
            &request.target.constraints,
        );
    }
    Ok((
        best_per_topology(pool, PER_TOPOLOGY, request.triage_count()),
        counts,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn local_offsets_move_fewest_parameters_first() {
        let o = local_offsets(2, 100);
        assert_eq!(o.len(), 8);
        assert_eq!(o[..4], [vec![-1, 0], vec![0, -1], vec![0, 1], vec![1, 0]]);
        assert!(o[4..].iter().all(|v| v.iter().all(|&x| x != 0)));
        assert_eq!(local_offsets(3, 5).len(), 5);
        assert!(local_offsets(0, 5).is_empty());
        assert_eq!(local_offsets(6, 10_000).len(), 728);
    }

    #[test]
    fn samples_stay_on_the_topology() {
        let family: crate::tiling::Family = "IH28".parse().unwrap();
        let d = Design {
            family,
            params: family.default_params(),
            dims: crate::cell::CellDims::MINIMAL,
            joints: vec![crate::topology::JointChoice::A],
        };
        let s = samples_around(&d, 4, 0.1);
        assert_eq!(s.len(), 4.min(3usize.pow(d.params.len() as u32) - 1));
        for x in &s {
            assert_eq!((x.family, x.dims, &x.joints), (d.family, d.dims, &d.joints));
            let moved = x
                .params
                .iter()
                .zip(&d.params)
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(moved, 1, "first samples move one parameter");
        }
    }
}

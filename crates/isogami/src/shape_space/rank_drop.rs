//! Rank-dropping shapes of rigid topologies: a topology with no motion at its default shape
//! may gain one at another valid shape. The paper screens topologies at the default shape
//! only, so these designs are invisible to it.
//!
//! The search minimises σ = √(λ_min / max(λ_max, 1)) of H = JᵀJ over the well-shaped tiles
//! within the exploration's sampling box (default ± span · scale) by Nelder–Mead (argmin;
//! σ is not smooth where the rank drops, it behaves like a distance to the special set),
//! from the default shape and a few quasi-random starts, then polishes the best point with
//! the corrector along every parameter. A shape is reported only when it has exactly one DOF
//! by the mobility analysis's own threshold.

use super::classify::shape_problem;
use super::correct::correct;
use super::error::ShapeError;
use super::jacobian::{moved, reduced_jacobian};
use super::kernel::dof;
use super::ShapeSettings;
use crate::math::{DVec, Real};
use crate::topology::Design;
use argmin::core::{CostFunction, Error as ArgminError, Executor};
use argmin::solver::neldermead::NelderMead;
use serde::Serialize;
use std::cell::Cell;

/// Cost of a point outside the box or without a well-shaped tile.
const OUTSIDE: Real = 10.0;
/// The best point is polished when σ is below this.
const POLISH_BELOW: Real = 1e-2;

/// A rank-dropping shape found by [`rank_drop`].
#[derive(Debug, Clone, Serialize)]
pub struct RankDrop {
    /// The design at that shape.
    #[serde(skip)]
    pub design: Design,
    /// Its spec.
    pub spec: String,
    /// σ at the starting shape.
    pub start_sigma: Real,
    /// σ at the shape found (below the mobility threshold's square root).
    pub sigma: Real,
    /// Shapes evaluated.
    pub evaluations: usize,
}

struct Sigma<'a> {
    design: &'a Design,
    span: Real,
    calls: Cell<usize>,
}

impl Sigma<'_> {
    fn at(&self, x: &[Real]) -> Real {
        self.calls.set(self.calls.get() + 1);
        if x.iter().any(|v| !v.is_finite() || v.abs() > self.span) {
            return OUTSIDE;
        }
        let d = moved(self.design, x, 1.0);
        if shape_problem(&d).is_some() {
            return OUTSIDE;
        }
        let Ok(j) = reduced_jacobian(&d) else {
            return OUTSIDE;
        };
        let h = j.transpose() * &j;
        match crate::math::symmetric_eigen(h) {
            Some(s) => {
                let lmax = s.values.last().copied().unwrap_or(0.0).max(1.0);
                (s.values[0].max(0.0) / lmax).sqrt()
            }
            None => OUTSIDE,
        }
    }
}

impl CostFunction for &Sigma<'_> {
    type Param = Vec<Real>;
    type Output = Real;
    fn cost(&self, x: &Vec<Real>) -> Result<Real, ArgminError> {
        Ok(self.at(x))
    }
}

/// Searches the shapes of `design` (any DOF at its own shape) for one with exactly one DOF.
pub fn rank_drop(
    design: &Design,
    settings: &ShapeSettings,
) -> Result<Option<RankDrop>, ShapeError> {
    settings.validate()?;
    let p = design.params.len();
    if p == 0 {
        return Ok(None);
    }
    let sigma = Sigma {
        design,
        span: settings.search_span,
        calls: Cell::new(0),
    };
    let start_sigma = sigma.at(&vec![0.0; p]);
    let mut best = (start_sigma, vec![0.0; p]);
    for start in 0..settings.search_starts.max(1) {
        let centre: Vec<Real> = if start == 0 {
            vec![0.0; p]
        } else {
            super::classify::halton_point(start - 1, p)
                .iter()
                .map(|u| (2.0 * u - 1.0) * 0.5 * settings.search_span)
                .collect()
        };
        let mut simplex = vec![centre.clone()];
        for i in 0..p {
            let mut v = centre.clone();
            v[i] += 0.05;
            simplex.push(v);
        }
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(1e-12)
            .expect("a positive tolerance is accepted");
        let run = Executor::new(&sigma, solver)
            .configure(|s| s.max_iters(settings.search_iterations as u64))
            .run();
        if let Ok(r) = run {
            if let Some(x) = r.state.best_param {
                let cost = r.state.best_cost;
                if cost < best.0 {
                    best = (cost, x);
                }
            }
        }
    }
    let evaluations = sigma.calls.get();
    if best.0 > POLISH_BELOW {
        return Ok(None);
    }
    let near = moved(design, &best.1, 1.0);
    let basis: Vec<DVec> = (0..p)
        .map(|i| {
            let mut e = DVec::zeros(p);
            e[i] = 1.0;
            e
        })
        .collect();
    let Some(found) = correct(&near, &basis, settings.mobility)? else {
        return Ok(None);
    };
    if shape_problem(&found).is_some() {
        return Ok(None);
    }
    let (n, ratio) = dof(&found, settings.mobility)?;
    Ok((n == 1).then(|| RankDrop {
        spec: found.to_string(),
        design: found,
        start_sigma,
        sigma: ratio.max(0.0).sqrt(),
        evaluations,
    }))
}

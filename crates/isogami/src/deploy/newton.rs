//! Newton's method for one deployment step, with tile 0 held fixed and a line search that
//! never leaves the intersection-free set.

use crate::contact::{ClearanceTracker, ContactModel, HessianProjection, PairCache};
use crate::kinematics::Mechanism;
use crate::math::{DMat, DVec, Real};

/// The energy minimised by a step: E_joints + E_coll + progress + springs + drag.
#[derive(Debug, Clone)]
pub struct Objective {
    /// Progress term ½·w·(dirᵀ(q − origin) − beta)², if any: (dir, origin, beta, w).
    pub progress: Option<(DVec, DVec, Real, Real)>,
    /// Spring terms ½·k·(q[index] − target)².
    pub springs: Vec<(usize, Real)>,
    /// Spring stiffness k.
    pub spring_k: Real,
    /// Drag term ½·k·|q − origin|² over every coordinate, if any: (origin, k). It keeps
    /// what no force moves where it was (a sheet with several degrees of freedom has motions
    /// nothing else in the objective resists) and makes the Hessian positive definite.
    pub drag: Option<(DVec, Real)>,
}

impl Objective {
    /// Just the joints and contact.
    pub fn constraints_only() -> Objective {
        Objective {
            progress: None,
            springs: Vec::new(),
            spring_k: 0.0,
            drag: None,
        }
    }

    /// Just the joints and contact, with a drag of stiffness `k` towards `origin`.
    pub fn constraints_with_drag(origin: &DVec, k: Real) -> Objective {
        Objective {
            drag: Some((origin.clone(), k)),
            ..Objective::constraints_only()
        }
    }

    fn extra_energy(&self, q: &DVec) -> Real {
        let mut e = 0.0;
        if let Some((dir, origin, beta, w)) = &self.progress {
            let s = dir.dot(&(q - origin)) - beta;
            e += 0.5 * w * s * s;
        }
        for &(i, target) in &self.springs {
            e += 0.5 * self.spring_k * (q[i] - target).powi(2);
        }
        if let Some((origin, k)) = &self.drag {
            e += 0.5 * k * (q - origin).norm_squared();
        }
        e
    }

    fn add_extra(&self, q: &DVec, g: &mut DVec, h: &mut DMat) {
        if let Some((dir, origin, beta, w)) = &self.progress {
            let s = dir.dot(&(q - origin)) - beta;
            g.axpy(w * s, dir, 1.0);
            h.ger(*w, dir, dir, 1.0);
        }
        for &(i, target) in &self.springs {
            g[i] += self.spring_k * (q[i] - target);
            h[(i, i)] += self.spring_k;
        }
        if let Some((origin, k)) = &self.drag {
            g.axpy(*k, &(q - origin), 1.0);
            for i in 0..h.nrows() {
                h[(i, i)] += k;
            }
        }
    }
}

/// What a minimisation produced.
#[derive(Debug, Clone)]
pub struct SolveOutcome {
    /// Final state.
    pub q: DVec,
    /// Newton iterations taken.
    pub iterations: usize,
    /// True when the Newton step became negligible.
    pub converged: bool,
    /// Largest joint residual at the end.
    pub joint_residual: Real,
    /// Barrier energy at the end (> 0 means contact is active).
    pub barrier: Real,
}

/// Total objective value (+∞ when a vertex touches an edge) and the barrier energy in it.
/// Every state the line search evaluates is reached by conservative advancement from an
/// intersection-free state, so the barrier skips the exact overlap test here; stored frames
/// get it.
fn total(
    mech: &Mechanism,
    contact: &ContactModel,
    obj: &Objective,
    q: &DVec,
    cache: &mut PairCache,
) -> (Real, Real) {
    let coll = contact.energy_in_free_set_cached(mech, q, cache);
    if !coll.is_finite() {
        return (Real::INFINITY, coll);
    }
    (mech.energy(q) + coll + obj.extra_energy(q), coll)
}

/// Minimises `obj` from `start` (which must be intersection-free; `start_clearance`, when
/// known, a lower bound on its clearance) over every coordinate but
/// tile 0's. Gauss–Newton Hessian JᵀJ plus the PSD-projected barrier Hessian plus the
/// progress and spring terms, a dense Cholesky solve (regularised when needed), and a
/// backtracking line search capped by conservative advancement.
pub fn minimize(
    mech: &Mechanism,
    contact: &ContactModel,
    obj: &Objective,
    start: &DVec,
    start_clearance: Option<Real>,
    max_iterations: usize,
) -> SolveOutcome {
    let mut cache = PairCache::new();
    minimize_cached(
        mech,
        contact,
        obj,
        start,
        start_clearance,
        max_iterations,
        &mut cache,
    )
}

/// [`minimize`] with the broad phase's pair lists kept in `cache` (which a deployment keeps
/// from step to step).
pub(super) fn minimize_cached(
    mech: &Mechanism,
    contact: &ContactModel,
    obj: &Objective,
    start: &DVec,
    start_clearance: Option<Real>,
    max_iterations: usize,
    cache: &mut PairCache,
) -> SolveOutcome {
    let n = start.len();
    let mut q = start.clone();
    let (mut f, mut barrier) = total(mech, contact, obj, &q, cache);
    let mut converged = false;
    let mut iterations = 0;
    let mut stepper = ClearanceTracker::new(start_clearance);
    while iterations < max_iterations && f.is_finite() {
        iterations += 1;
        let jac = mech.jacobian(&q);
        let c = mech.residual(&q);
        let mut g = jac.transpose() * &c;
        let mut h = jac.transpose() * &jac;
        contact.add_derivatives_cached(
            mech,
            &q,
            &mut g,
            &mut h,
            HessianProjection::PerPairPsd,
            cache,
        );
        obj.add_extra(&q, &mut g, &mut h);
        let gr = g.rows(3, n - 3).into_owned();
        let hr = h.view((3, 3), (n - 3, n - 3)).into_owned();
        let Some(dr) = solve_regularised(hr, &gr) else {
            break;
        };
        let mut d = DVec::zeros(n);
        d.rows_mut(3, n - 3).copy_from(&dr);
        let slope = gr.dot(&dr);
        if dr.amax() < 1e-13 || slope > -1e-30 {
            converged = true;
            break;
        }
        let mut alpha = stepper.fraction_cached(mech, contact, &q, &d, cache);
        let mut accepted = false;
        for _ in 0..40 {
            let trial = &q + &d * alpha;
            let (ft, bt) = total(mech, contact, obj, &trial, cache);
            if ft.is_finite() && ft <= f + 1e-4 * alpha * slope {
                stepper.moved(alpha);
                q = trial;
                f = ft;
                barrier = bt;
                accepted = true;
                break;
            }
            alpha *= 0.5;
            if alpha < 1e-14 {
                break;
            }
        }
        if !accepted {
            break;
        }
        // Newton converges quadratically here: a step this small leaves an error of its
        // square, far below the joint tolerance.
        if (&d * alpha).amax() < 1e-9 {
            converged = true;
            break;
        }
    }
    let joint_residual = mech.residual(&q).amax();
    SolveOutcome {
        q,
        iterations,
        converged,
        joint_residual,
        barrier,
    }
}

/// Solves H d = −g by Cholesky, adding μI (growing) until H + μI factors.
fn solve_regularised(mut h: DMat, g: &DVec) -> Option<DVec> {
    let scale = h.diagonal().amax().max(1e-12);
    let mut mu = 1e-12 * scale;
    for _ in 0..12 {
        if let Some(ch) = nalgebra::Cholesky::new(h.clone()) {
            let d = ch.solve(&(-g));
            if d.iter().all(|x| x.is_finite()) {
                return Some(d);
            }
        }
        for i in 0..h.nrows() {
            h[(i, i)] += mu;
        }
        mu *= 100.0;
    }
    None
}

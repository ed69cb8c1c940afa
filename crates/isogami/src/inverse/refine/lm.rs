//! Levenberg–Marquardt on the stacked residuals of a matching target (lock, lock-f, path,
//! area(r), expansion(θ, e)):
//! minimises ½‖r(x)‖², r = (√wᵢ rᵢ), whose zero is the objective's zero, with forward
//! differences for the Jacobian (one evaluation per unknown, step 10⁻³ of a scale, taken
//! backwards when the forward point is invalid), kept up to date between them by Broyden's
//! rank-one updates (a fresh one after n accepted steps, or when a step from an updated one
//! fails), so most iterations cost one evaluation. The damped normal equations
//! (JᵀJ + λ diag(JᵀJ) + λ·10⁻⁹ I) δ = −Jᵀr are solved by Cholesky; a step is capped at 0.25
//! of a scale and accepted when it lowers ‖r‖, which divides λ by 3, else λ is multiplied by
//! 4. It ends when ‖r‖ is below 10⁻⁶, a step is below 10⁻⁷ of a scale
//! (or a failing step from a fresh Jacobian below 10⁻⁴), λ exceeds 10⁸, a point
//! has no residual (invalid), or the budget is spent; Nelder–Mead then takes over.

use super::track::Tracker;
use crate::math::{DMat, DVec, Real};

const FD_STEP: Real = 1e-3;
/// Residual norm below which the match is as good as the deployment resolves it (the
/// contact limit is found to about 10⁻⁵ of the edge length).
const NOISE: Real = 1e-6;
const MAX_STEP: Real = 0.25;

fn norm2(r: &[Real]) -> Real {
    r.iter().map(|v| v * v).sum()
}

/// The forward-difference Jacobian at `x` (residual `r`), or None when a column cannot be
/// had.
fn jacobian(tracker: &Tracker<'_, '_>, x: &[Real], r: &[Real]) -> Option<DMat> {
    let (m, n) = (r.len(), x.len());
    let mut j = DMat::zeros(m, n);
    for c in 0..n {
        let mut column = None;
        for h in [FD_STEP, -FD_STEP] {
            let mut y = x.to_vec();
            y[c] += h;
            if let Some(ry) = tracker.eval(&y)?.residual {
                if ry.len() == m {
                    column = Some((ry, h));
                    break;
                }
            }
        }
        let (ry, h) = column?;
        for i in 0..m {
            j[(i, c)] = (ry[i] - r[i]) / h;
        }
    }
    Some(j)
}

/// Runs Levenberg–Marquardt from the tracker's best point while it has residuals.
pub(super) fn polish(tracker: &Tracker<'_, '_>) {
    let mut x = tracker.best_x();
    let Some(mut r) = tracker.eval(&x).and_then(|p| p.residual) else {
        return;
    };
    let n = x.len();
    let Some(mut j) = jacobian(tracker, &x, &r) else {
        return;
    };
    // True while `j` is a finite-difference Jacobian at `x` (not a Broyden update).
    let mut fresh = true;
    let mut updates = 0;
    let mut lambda = 1e-3;
    while norm2(&r).sqrt() > NOISE && lambda < 1e8 {
        let jt = j.transpose();
        let jtj = &jt * &j;
        let g = &jt * DVec::from_column_slice(&r);
        let mut a = jtj.clone();
        for i in 0..n {
            a[(i, i)] += lambda * jtj[(i, i)] + lambda * 1e-9;
        }
        let Some(step) = a.cholesky().map(|c| -c.solve(&g)) else {
            lambda *= 4.0;
            continue;
        };
        let len = step.norm();
        if !len.is_finite() {
            return;
        }
        let step = if len > MAX_STEP {
            step * (MAX_STEP / len)
        } else {
            step
        };
        let y: Vec<Real> = x.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
        let Some(p) = tracker.eval(&y) else {
            return;
        };
        match p.residual {
            Some(ry) if ry.len() == r.len() && norm2(&ry) < norm2(&r) => {
                // Broyden's rank-one update: J ← J + (Δr − J Δx) Δxᵀ / (Δxᵀ Δx).
                let dr = DVec::from_column_slice(&ry) - DVec::from_column_slice(&r);
                let dx = DVec::from_column_slice(step.as_slice());
                let jdx = &j * &dx;
                j += (dr - jdx) * dx.transpose() / dx.norm_squared();
                fresh = false;
                updates += 1;
                x = y;
                r = ry;
                lambda = (lambda / 3.0).max(1e-12);
                if step.norm() < 1e-7 {
                    return;
                }
                if updates >= n {
                    let Some(jn) = jacobian(tracker, &x, &r) else {
                        return;
                    };
                    (j, fresh, updates) = (jn, true, 0);
                }
            }
            _ if !fresh => {
                // The updated Jacobian may be stale: take a fresh one before damping more.
                let Some(jn) = jacobian(tracker, &x, &r) else {
                    return;
                };
                (j, fresh, updates) = (jn, true, 0);
            }
            // A fresh Jacobian whose short step fails: the deployment's own resolution.
            _ if len < 1e-4 => return,
            _ => lambda *= 4.0,
        }
    }
}

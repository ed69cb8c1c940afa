//! The motion vector at a state: the null vector of H = JᵀJ (tile 0 fixed), signed to
//! continue the previous direction; at turning points, where the null space has dimension
//! greater than one, the null-space direction closest to the previous one.

use super::error::DeployError;
use crate::kinematics::Mechanism;
use crate::math::{symmetric_eigen, DVec, Real};
use crate::mobility::{reduced_hessian, MobilityError};

/// Eigenvalues below this fraction of max(λ_max, 1) count as zero when choosing a direction.
/// Looser than the mobility tolerance: near a turning point the second eigenvalue dips
/// towards zero and the path may continue along it.
pub const TURN_TOLERANCE: Real = 1e-7;

/// Unit motion vector (full state length, zero for tile 0) and the null-space dimension.
///
/// Fast path: away from turning points the null space of H is one-dimensional and the
/// direction is the solution of (H + v̂v̂ᵀ) v = v̂ (v̂ the previous direction), one Cholesky
/// solve: then Hv = v̂(1 − v̂ᵀv) forces v̂ᵀv = 1 and Hv = 0. It is used only when the
/// factorisation is well conditioned and the result is a null vector to 1e-10; otherwise
/// (turning points, several zero eigenvalues) the full eigen-decomposition decides.
pub fn motion_direction(
    mech: &Mechanism,
    q: &DVec,
    previous: &DVec,
) -> Result<(DVec, usize), DeployError> {
    let n = q.len();
    let h = reduced_hessian(mech, q);
    let prev = previous.rows(3, n - 3).into_owned();
    if let Some(v) = tangent_by_solve(&h, &prev) {
        let mut full = DVec::zeros(n);
        full.rows_mut(3, n - 3).copy_from(&v);
        return Ok((full, 1));
    }
    let spec = symmetric_eigen(h).ok_or(MobilityError::Eigen)?;
    let lmax = spec.values.last().copied().unwrap_or(0.0).max(1.0);
    let nullity = spec
        .values
        .iter()
        .take_while(|&&l| l < TURN_TOLERANCE * lmax)
        .count()
        .max(1);
    // Project the previous direction on the (near-)null space.
    let mut v = DVec::zeros(n - 3);
    for k in 0..nullity {
        let e = spec.vectors.column(k);
        v.axpy(e.dot(&prev), &e.into_owned(), 1.0);
    }
    let norm = v.norm();
    if norm < 1e-6 {
        // The previous direction left the null space entirely: take the smallest mode, with
        // the sign that best continues.
        v = spec.vectors.column(0).into_owned();
        if v.dot(&prev) < 0.0 {
            v = -v;
        }
    } else {
        v /= norm;
    }
    let mut full = DVec::zeros(n);
    full.rows_mut(3, n - 3).copy_from(&v);
    Ok((full, nullity))
}

/// The fast path of [`motion_direction`]; `None` when it cannot be trusted.
fn tangent_by_solve(h: &crate::math::DMat, prev: &DVec) -> Option<DVec> {
    let pn = prev.norm();
    if pn.is_nan() || pn <= 0.5 {
        return None;
    }
    let vp = prev / pn;
    let mut a = h.clone();
    a.ger(1.0, &vp, &vp, 1.0);
    let chol = nalgebra::Cholesky::new(a)?;
    let l = chol.l_dirty();
    let diag = (0..l.nrows()).map(|i| l[(i, i)] * l[(i, i)]);
    let (lo, hi) = diag.fold((Real::INFINITY, 0.0 as Real), |(lo, hi), d| {
        (lo.min(d), hi.max(d))
    });
    // A pivot this small means a second (near-)zero eigenvalue: a turning point.
    if lo.is_nan() || lo <= TURN_TOLERANCE * hi.max(1.0) {
        return None;
    }
    let v = chol.solve(&vp);
    let norm = v.norm();
    if !norm.is_finite() || norm == 0.0 {
        return None;
    }
    let v = v / norm;
    let hv = (h * &v).amax();
    (hv < 1e-10 * h.diagonal().amax().max(1.0)).then_some(v)
}

//! The motion vector at a state: the null vector of H = JᵀJ (tile 0 fixed), signed to
//! continue the previous direction; at turning points, where the null space has dimension
//! greater than one, the null-space direction closest to the previous one.

use crate::error::{Error, Result};
use crate::kinematics::Mechanism;
use crate::math::{symmetric_eigen, DVec, Real};
use crate::mobility::reduced_hessian;

/// Eigenvalues below this fraction of max(λ_max, 1) count as zero when choosing a direction.
/// Looser than the mobility tolerance: near a turning point the second eigenvalue dips
/// towards zero and the path may continue along it.
pub const TURN_TOLERANCE: Real = 1e-7;

/// Unit motion vector (full state length, zero for tile 0) and the null-space dimension.
pub fn motion_direction(mech: &Mechanism, q: &DVec, previous: &DVec) -> Result<(DVec, usize)> {
    let n = q.len();
    let spec = symmetric_eigen(reduced_hessian(mech, q))
        .ok_or_else(|| Error::Numerical("eigen-decomposition did not converge".into()))?;
    let lmax = spec.values.last().copied().unwrap_or(0.0).max(1.0);
    let nullity = spec
        .values
        .iter()
        .take_while(|&&l| l < TURN_TOLERANCE * lmax)
        .count()
        .max(1);
    let prev = previous.rows(3, n - 3);
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

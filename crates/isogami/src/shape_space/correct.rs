//! The corrector: back onto the shapes with one degree of freedom.
//!
//! From a shape next to the special set it moves along the given shape directions B
//! (scaled, orthonormal) by Newton steps on the signed pairing: at the current shape, with
//! the softest motion v and the candidate self-stresses w_k of J (`kernel::softest_pair`),
//! g_k = w_kᵀ J v is ±σ_min for the stress that pairs with v and 0 for the others, and
//! N_kj = w_kᵀ (∂J/∂B_j) v is its first-order change; the step δ solves g + N δ = 0 in the
//! least-squares, minimum-norm sense. Everything is recomputed at every shape. It converges
//! quadratically where the special set is a smooth manifold transversal to B.

use super::error::ShapeError;
use super::jacobian::{moved, reduced_jacobian};
use super::kernel::{dof, pairing, softest_pair};
use crate::math::{DVec, Real};
use crate::mobility::MobilitySettings;
use crate::topology::Design;

/// Most Newton iterations.
const MAX_ITERATIONS: usize = 30;
/// Converged when σ_min of J (entries O(1)) falls below this.
const SIGMA_TOL: Real = 1e-10;
/// Singular values of N below this fraction of the largest are ignored (difference noise).
const RANK_TOL: Real = 1e-7;

/// The shape on the special set next to `start`, moving only along `basis` (scaled
/// directions). `None` when it does not converge or the point it reaches does not have
/// exactly one DOF.
pub fn correct(
    start: &Design,
    basis: &[DVec],
    mobility: MobilitySettings,
) -> Result<Option<Design>, ShapeError> {
    let p = start.params.len();
    let dirs: Vec<Vec<Real>> = basis.iter().map(|b| b.iter().copied().collect()).collect();
    let mut offset = vec![0.0; p];
    for _ in 0..MAX_ITERATIONS {
        let design = moved(start, &offset, 1.0);
        let j = reduced_jacobian(&design)?;
        let (v, stresses) = softest_pair(&j, mobility)?;
        let g = stresses.transpose() * (&j * &v);
        if g.amax() < SIGMA_TOL {
            return Ok((dof(&design, mobility)?.0 == 1).then_some(design));
        }
        if dirs.is_empty() {
            return Ok(None);
        }
        let n = pairing(&design, &v, &stresses, &dirs)?;
        let svd = n.svd(true, true);
        let eps = RANK_TOL * svd.singular_values.max().max(Real::MIN_POSITIVE);
        let Ok(step) = svd.solve(&(-g), eps) else {
            return Ok(None);
        };
        if step.iter().any(|x| !x.is_finite()) {
            return Ok(None);
        }
        for (k, b) in basis.iter().enumerate() {
            offset
                .iter_mut()
                .zip(b.iter())
                .for_each(|(o, x)| *o += step[k] * x);
        }
        if offset.iter().any(|o| o.abs() > 1.0) {
            // A jump of a whole parameter scale is not a correction.
            return Ok(None);
        }
    }
    let design = moved(start, &offset, 1.0);
    let (n, ratio) = dof(&design, mobility)?;
    Ok((n == 1 && ratio.max(0.0).sqrt() < 1e3 * SIGMA_TOL).then_some(design))
}

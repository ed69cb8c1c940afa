//! Projection of a small symmetric matrix onto the positive semi-definite cone: eigen-decompose
//! and clamp negative eigenvalues to zero (the nearest PSD matrix in the Frobenius norm).

use crate::math::{DMat, Real, EIGEN_MAX_ITER};

/// The PSD projection of the symmetric part of `h`, or `None` when the eigen-decomposition
/// fails (non-finite entries or no convergence within the iteration cap).
///
/// Runs once per pair in contact at every Newton iteration, so it works on nalgebra's
/// decomposition directly (no sorted copy of the eigenvectors, no temporary matrix per
/// eigenvalue); the sum runs over the eigenvalues in ascending order, as
/// [`crate::math::symmetric_eigen`] returns them.
pub(crate) fn project_psd(h: &DMat) -> Option<DMat> {
    let n = h.nrows();
    let sym = DMat::from_fn(n, n, |i, j| (h[(i, j)] + h[(j, i)]) * 0.5);
    if sym.iter().any(|x| !x.is_finite()) {
        return None;
    }
    if n == 0 {
        return Some(sym);
    }
    let eig = nalgebra::SymmetricEigen::try_new(sym.clone(), Real::EPSILON, EIGEN_MAX_ITER)?;
    let values = &eig.eigenvalues;
    if values.iter().all(|&l| l >= 0.0) {
        return Some(sym);
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let mut out = DMat::zeros(n, n);
    for k in order {
        let l = values[k];
        if l > 0.0 {
            let v = eig.eigenvectors.column(k);
            for j in 0..n {
                for i in 0..n {
                    out[(i, j)] += v[i] * v[j] * l;
                }
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{symmetric_eigen, DVec};

    /// The projection written plainly: sorted spectrum, one outer product per eigenvalue.
    fn reference(h: &DMat) -> Option<DMat> {
        let sym = (h + h.transpose()) * 0.5;
        let spec = symmetric_eigen(sym.clone())?;
        if spec.values.first().is_none_or(|&l| l >= 0.0) {
            return Some(sym);
        }
        let n = sym.nrows();
        let mut out = DMat::zeros(n, n);
        for (k, &l) in spec.values.iter().enumerate() {
            if l > 0.0 {
                let v = spec.vectors.column(k);
                out += v * v.transpose() * l;
            }
        }
        Some(out)
    }

    #[test]
    fn agrees_with_the_plain_projection_bit_for_bit() {
        let mut seed = 5u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        };
        let mut projected = 0;
        for n in [1, 2, 3, 6, 7, 8, 9, 10] {
            for _ in 0..50 {
                // Rank-deficient sums of outer products with both signs, like a pair's
                // barrier Hessian.
                let mut h = DMat::zeros(n, n);
                for _ in 0..3 {
                    let v = DVec::from_fn(n, |_, _| rnd());
                    h += &v * v.transpose() * (2.0 * rnd() + 0.5);
                }
                h[(0, n - 1)] += 1e-3 * rnd();
                let (got, want) = (project_psd(&h).unwrap(), reference(&h).unwrap());
                assert_eq!(got, want, "n = {n}");
                projected += usize::from(got != (&h + h.transpose()) * 0.5);
            }
        }
        assert!(projected > 100, "{projected}");
        assert_eq!(
            project_psd(&DMat::zeros(0, 0)),
            reference(&DMat::zeros(0, 0))
        );
    }

    #[test]
    fn clamps_negative_eigenvalues_only() {
        let h = DMat::from_row_slice(3, 3, &[2.0, 1.0, 0.0, 1.0, -1.0, 0.5, 0.0, 0.5, 3.0]);
        let p = project_psd(&h).unwrap();
        let before = symmetric_eigen(h.clone()).unwrap();
        let after = symmetric_eigen(p.clone()).unwrap();
        assert!(before.values[0] < 0.0);
        assert!(after.values[0].abs() < 1e-12);
        for k in 1..3 {
            assert!((after.values[k] - before.values[k]).abs() < 1e-12);
        }
        // A PSD matrix comes back unchanged.
        let spd = DMat::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
        assert_eq!(project_psd(&spd).unwrap(), spd);
        assert!(project_psd(&DMat::from_element(2, 2, f64::NAN)).is_none());
    }
}

//! Projection of a small symmetric matrix onto the positive semi-definite cone: eigen-decompose
//! and clamp negative eigenvalues to zero (the nearest PSD matrix in the Frobenius norm).

use crate::math::{symmetric_eigen, DMat};

/// The PSD projection of the symmetric part of `h`, or `None` when the eigen-decomposition
/// fails (non-finite entries or no convergence within the iteration cap).
pub(crate) fn project_psd(h: &DMat) -> Option<DMat> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::symmetric_eigen;

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

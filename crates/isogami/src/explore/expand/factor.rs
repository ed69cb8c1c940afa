//! The linear algebra of the search (see the module documentation of [`super`]): adding a
//! joint's row to the incremental QR of the selected rows (the complement C by one
//! Householder reflection, Q, R and R⁻¹), the certificates that decide rigidity and
//! dof = 1 from σ_min(R) without an eigen-decomposition, and the motion of a certified leaf.

use super::{Expander, Search, DEPENDENT_REL_TOL, RIGID_MARGIN};
use crate::math::DVec;
use crate::mobility::area_rate;
use crate::topology::JointChoice;

impl Expander<'_> {
    /// ‖J‖_F² of the current choice (every edge decided): a bound on λ_max of H.
    pub(super) fn frobenius_sq(&self, s: &Search<'_>) -> f64 {
        s.edges
            .iter()
            .map(|&e| self.row_sq[e][usize::from(s.choice[e] == JointChoice::B)])
            .sum()
    }
    /// The unit vector orthogonal to a basis of N − 1 rows (the complement's one vector), as
    /// a full state vector signed the way `mobility` signs motions.
    pub(super) fn null_vector(&self, s: &Search<'_>) -> DVec {
        let n = self.cols;
        debug_assert_eq!(s.count + 1, n);
        let v = &s.comp[..n];
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut full = DVec::zeros(n + 3);
        for (c, x) in v.iter().enumerate() {
            full[c + 3] = x / norm;
        }
        let rate = area_rate(&self.reference, &self.reference.rest, &full);
        let flip = if rate.abs() > 1e-9 {
            rate < 0.0
        } else {
            full[full.iamax()] < 0.0
        };
        if flip {
            full = -full;
        }
        full
    }
    /// Appends `row` (Euclidean norm `norm`) to the basis when its residual, its projection on
    /// the complement, is not below `DEPENDENT_REL_TOL · norm`; the complement loses that
    /// direction (one Householder reflection of its coordinates). No allocation.
    pub(super) fn add_row(&self, s: &mut Search<'_>, row: &[(usize, f64)], norm: f64) {
        let n = self.cols;
        let k = s.count;
        if k == n || norm == 0.0 {
            return;
        }
        let d = n - k;
        // The row's coordinates in the complement (sparse products).
        let u = &mut s.coords[..d];
        for (x, cj) in u.iter_mut().zip(s.comp.chunks_exact(n)) {
            *x = row.iter().map(|&(c, v)| cj[c] * v).sum();
        }
        let rho = u.iter().map(|x| x * x).sum::<f64>().sqrt();
        if rho <= DEPENDENT_REL_TOL * norm {
            return;
        }
        // Slot k's R row changes: R⁻¹'s row k (and any after it) must be recomputed.
        s.l_valid = s.l_valid.min(k);
        // R's new row: the row's coefficients on the basis, then its residual.
        let (basis, _) = s.q.split_at(k * n);
        let rrow = &mut s.r[k * n..(k + 1) * n];
        for (x, qj) in rrow.iter_mut().zip(basis.chunks_exact(n)) {
            *x = row.iter().map(|&(c, v)| qj[c] * v).sum();
        }
        rrow[k] = rho;
        for x in &mut rrow[k + 1..] {
            *x = 0.0;
        }
        // Householder reflection H = I − β v vᵀ with v = u + sign(u₀) ρ e₀, so H u = −sign(u₀) ρ e₀:
        // (C H)'s first vector is −sign(u₀) C u / ρ, the new basis direction, and the others
        // span the new complement.
        let sign = if u[0] < 0.0 { -1.0 } else { 1.0 };
        u[0] += sign * rho;
        let beta = 1.0 / (rho * u[0].abs());
        let w = &mut s.image;
        w.fill(0.0);
        for (&vj, cj) in u.iter().zip(s.comp.chunks_exact(n)) {
            for (x, y) in w.iter_mut().zip(cj) {
                *x += vj * y;
            }
        }
        for (&vj, cj) in u.iter().zip(s.comp.chunks_exact_mut(n)) {
            let f = beta * vj;
            for (x, y) in cj.iter_mut().zip(w.iter()) {
                *x -= f * y;
            }
        }
        let qk = &mut s.q[k * n..(k + 1) * n];
        for (x, y) in qk.iter_mut().zip(&s.comp[..n]) {
            *x = -sign * y;
        }
        // Drop the first vector: the last one takes its place.
        if d > 1 {
            s.comp.copy_within((d - 1) * n..d * n, 0);
        }
        s.count = k + 1;
    }
    /// The rigidity certificate of a full basis (see module docs).
    pub(super) fn certified(&self, s: &mut Search<'_>, n: usize) -> bool {
        let threshold = s.threshold_sq;
        self.certified_with(s, n, threshold)
    }
    /// True when the leading `size` selected rows have σ_min(R)² ≥ margin · `threshold`, via
    /// σ_min(R) ≥ 1/‖R⁻¹‖_F.
    pub(super) fn certified_with(&self, s: &mut Search<'_>, size: usize, threshold: f64) -> bool {
        let n = self.cols;
        // Rows of R⁻¹ by forward substitution: row i is (e_i − Σ_{j<i} r[i][j] · row j) / r[i][i].
        // Entry (i, c) subtracts r[i][j] · l[j][c] for j = c, c + 1, …, i − 1 in that order, the
        // same operations in the same order as solving R x = e_c, so the values do not depend on
        // when they are made. Row by row, the updates of a row's entries are independent of
        // each other and run over contiguous memory.
        for i in s.l_valid..size {
            let (done, rest) = s.l.split_at_mut(i * n);
            let row = &mut rest[..=i];
            row.fill(0.0);
            row[i] = 1.0;
            let ri = &s.r[i * n..i * n + i];
            for (j, &rij) in ri.iter().enumerate() {
                let lj = &done[j * n..=j * n + j];
                for (x, y) in row[..=j].iter_mut().zip(lj) {
                    *x -= rij * y;
                }
            }
            let d = s.r[i * n + i];
            for x in row.iter_mut() {
                *x /= d;
            }
            s.l_sq[i] = row.iter().map(|x| x * x).sum();
        }
        s.l_valid = s.l_valid.max(size);
        let inv_sq: f64 = s.l_sq[..size].iter().sum();
        inv_sq.is_finite() && inv_sq > 0.0 && 1.0 / inv_sq >= RIGID_MARGIN * threshold
    }
}

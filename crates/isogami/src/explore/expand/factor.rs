//! The linear algebra of the search (see the module documentation of [`super`]): adding a
//! joint's row to the incremental QR of the selected rows (the complement C by one
//! Householder reflection, Q, R and R⁻¹), the certificates that decide rigidity and
//! dof = 1 from σ_min(R) without an eigen-decomposition, and the motion of a certified leaf.

use super::{Expander, RowId, Search, DEPENDENT_REL_TOL, RIGID_MARGIN};
use crate::math::DVec;
use crate::mobility::area_rate;
use crate::topology::JointChoice;

/// At most this many trailing rows of R are bounded instead of solved (one joint's two rows).
const BOUNDED_ROWS: usize = 2;

/// The bound of ‖R⁻¹‖_F² certifies only when it clears the threshold by this factor.
const BOUND_SLACK: f64 = 1.0 + 1e-6;

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
    pub(super) fn add_row(&self, s: &mut Search<'_>, id: RowId) {
        let n = self.cols;
        let row = self.row(id);
        let norm = self.row_norm[id.edge][id.end][id.index];
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
        // Slot k's R row changes: R⁻¹'s row k (and any after it) must be recomputed, and its
        // coefficients on the basis are made when a certificate needs them (`basis_rows`).
        s.l_valid = s.l_valid.min(k);
        s.r_valid = s.r_valid.min(k);
        s.slot_rows[k] = id;
        let rrow = &mut s.r[k * n..(k + 1) * n];
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
    ///
    /// The last one or two rows are first bounded rather than solved: with R split after row
    /// p as [P 0; B D] (D the last rows' diagonal block),
    /// R⁻¹ = [P⁻¹ 0; −D⁻¹BP⁻¹ D⁻¹], so ‖R⁻¹‖_F² = ‖P⁻¹‖_F² + ‖D⁻¹BP⁻¹‖_F² + ‖D⁻¹‖_F²
    /// ≤ f + ‖D⁻¹‖_F² (‖B‖_F² f + 1) with f = ‖P⁻¹‖_F² (from the rows of R⁻¹ already made).
    /// That costs O(N) where solving the two rows costs O(N²), and at most leaves it clears the
    /// threshold by decades. The bound is accepted only with [`BOUND_SLACK`] to spare, far
    /// more than the rounding of either computation (a matrix that passes has
    /// ‖R⁻¹‖₂ ≤ 1/√(margin · threshold), so its condition number keeps the relative error of
    /// the solved sum near 1e-10); otherwise the rows are solved and decide as before. So the
    /// answer is the solved certificate's, bit for bit.
    pub(super) fn certified_with(&self, s: &mut Search<'_>, size: usize, threshold: f64) -> bool {
        let limit = RIGID_MARGIN * threshold;
        self.basis_rows(s, size);
        let split = size.saturating_sub(BOUNDED_ROWS).max(s.l_valid.min(size));
        self.inverse_rows(s, split);
        if split < size {
            let solved: f64 = s.l_sq[..split].iter().sum();
            let bound = self.inverse_bound(s, split, size, solved);
            if bound.is_finite() && bound > 0.0 && 1.0 / bound >= limit * BOUND_SLACK {
                #[cfg(test)]
                tests::check_bounded(self, s, size, limit, bound);
                return true;
            }
            self.inverse_rows(s, size);
        }
        let inv_sq: f64 = s.l_sq[..size].iter().sum();
        inv_sq.is_finite() && inv_sq > 0.0 && 1.0 / inv_sq >= limit
    }
    /// Makes the coefficients on the basis of R's rows `r_valid..upto`: the sparse products
    /// q_j · row for j below the row's slot. Q's rows before a slot stay as they are while the
    /// slot is filled, so a row made late is the row made when it was added.
    fn basis_rows(&self, s: &mut Search<'_>, upto: usize) {
        let n = self.cols;
        for k in s.r_valid..upto {
            let row = self.row(s.slot_rows[k]);
            let (basis, _) = s.q.split_at(k * n);
            let rrow = &mut s.r[k * n..k * n + k];
            for (x, qj) in rrow.iter_mut().zip(basis.chunks_exact(n)) {
                *x = row.iter().map(|&(c, v)| qj[c] * v).sum();
            }
        }
        s.r_valid = s.r_valid.max(upto);
    }
    /// Makes rows `l_valid..upto` of R⁻¹ (and their squared norms).
    fn inverse_rows(&self, s: &mut Search<'_>, upto: usize) {
        let n = self.cols;
        // Rows of R⁻¹ by forward substitution: row i is (e_i − Σ_{j<i} r[i][j] · row j) / r[i][i].
        // Entry (i, c) subtracts r[i][j] · l[j][c] for j = c, c + 1, …, i − 1 in that order, the
        // same operations in the same order as solving R x = e_c, so the values do not depend on
        // when they are made. Row by row, the updates of a row's entries are independent of
        // each other and run over contiguous memory.
        for i in s.l_valid..upto {
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
        s.l_valid = s.l_valid.max(upto);
    }
    /// The upper bound f + ‖D⁻¹‖_F² (‖B‖_F² f + 1) of ‖R⁻¹‖_F² over the leading `size` rows,
    /// with rows `split..size` (one or two) bounded and `solved` = ‖P⁻¹‖_F² of the rows
    /// before them (see [`Expander::certified_with`]).
    fn inverse_bound(&self, s: &Search<'_>, split: usize, size: usize, solved: f64) -> f64 {
        let n = self.cols;
        let r = |i: usize, j: usize| s.r[i * n + j];
        let b_sq: f64 = (split..size)
            .map(|i| s.r[i * n..i * n + split].iter().map(|x| x * x).sum::<f64>())
            .sum();
        let d_inv_sq = match size - split {
            1 => 1.0 / (r(split, split) * r(split, split)),
            2 => {
                let (d11, d21, d22) = (
                    r(split, split),
                    r(split + 1, split),
                    r(split + 1, split + 1),
                );
                let off = d21 / (d11 * d22);
                1.0 / (d11 * d11) + 1.0 / (d22 * d22) + off * off
            }
            _ => return f64::INFINITY,
        };
        solved + d_inv_sq * (b_sq * solved + 1.0)
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use std::cell::Cell;

    thread_local! {
        /// Certificates decided by the bound on this thread.
        pub(in crate::explore::expand) static BOUNDED: Cell<u64> = const { Cell::new(0) };
    }

    /// Every certificate the bound gives is checked against all rows of R⁻¹ solved afresh: the
    /// solved certificate passes too, and the bound is not below the solved ‖R⁻¹‖_F².
    pub(super) fn check_bounded(
        ex: &Expander<'_>,
        s: &Search<'_>,
        size: usize,
        limit: f64,
        bound: f64,
    ) {
        let n = ex.cols;
        let mut l = vec![0.0; n * n];
        let mut inv_sq = 0.0;
        for i in 0..size {
            for c in 0..=i {
                let mut acc = if i == c { 1.0 } else { 0.0 };
                for j in c..i {
                    acc -= s.r[i * n + j] * l[j * n + c];
                }
                l[i * n + c] = acc / s.r[i * n + i];
            }
            inv_sq += l[i * n..=i * n + i].iter().map(|x| x * x).sum::<f64>();
        }
        assert!(
            inv_sq.is_finite() && inv_sq > 0.0 && 1.0 / inv_sq >= limit,
            "the bound certified {size} rows that the solved certificate refuses"
        );
        assert!(
            bound >= inv_sq * (1.0 - 1e-9),
            "bound {bound} below the solved ‖R⁻¹‖_F² {inv_sq}"
        );
        BOUNDED.with(|b| b.set(b.get() + 1));
    }
}

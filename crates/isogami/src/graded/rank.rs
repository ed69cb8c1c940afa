//! Degrees of freedom of a posed graded sheet, for sheets of any size: the smallest singular
//! values of its pins' Jacobian found by shift-and-invert subspace iteration over a sparse
//! Cholesky factorisation (a dense decomposition, cubic in the tiles, took 2 s a state at
//! 400 tiles).
//!
//! The pins' Jacobian J (2 rows per pin, x, y, θ columns per tile) has the 3 rigid motions in
//! its null space; holding tile 0's pose removes them, so the held matrix J₀ has one null
//! direction per degree of freedom. The smallest eigenvalues of J₀ᵀJ₀ are found by block
//! inverse iteration on J₀ᵀJ₀ + σI (σ a tiny shift that keeps the factorisation positive)
//! with a Rayleigh–Ritz step each round; the largest by power iteration. A singular value
//! below [`RANK_TOLERANCE`] of the largest counts as zero.

use super::model::GradedSheet;
use crate::math::{DMat, DVec, Real, Vec2};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

/// Singular values of the pins' Jacobian below this fraction of the largest count as zero:
/// ten times the pin tolerance ([`super::deploy::PIN_TOLERANCE`]), a motion that opens the
/// pins by no more than the precision they are closed to. A graded sheet is a mechanism to
/// that precision: its mode's singular value stays under 4e-7 of the largest (measured on
/// graded rotating squares, 100 and 400 tiles, along their whole paths). The next one is a
/// soft motion of the whole sheet, not a mechanism: near 1e-3 when well open, it falls with
/// the opening and with the sheet's size, about as opening / tiles (the *ungraded* rotating
/// squares at 10 % open: 4.0e-4 at 10×10 tiles, 8.1e-5 at 20×20), so a threshold fixed
/// near it (1e-4, before) counted an ungraded 400-tile sheet two DOF at 10 % open.
pub const RANK_TOLERANCE: Real = 1e-5;

/// Eigenvectors followed at once: degrees of freedom are counted up to this many.
pub const MAX_COUNTED: usize = 8;

/// Rounds of the subspace iteration.
const ROUNDS: usize = 12;

/// Degrees of freedom of the opened state of `sheet` (at most [`MAX_COUNTED`]: more reads as
/// that many), and the two smallest singular values past the rigid motions relative to the
/// largest (the mechanism's mode and the next). None when the factorisation fails.
pub fn dof(sheet: &GradedSheet) -> Option<(usize, [Real; 2])> {
    let tiles = sheet.tiles.len();
    if tiles < 2 {
        return Some((0, [0.0, 0.0]));
    }
    // J₀ᵀJ₀ over the poses of tiles 1.., as triplets (column c = 3(tile − 1) + k).
    let size = 3 * (tiles - 1);
    let mut triplets: Vec<Triplet<usize, usize, Real>> = Vec::new();
    let mut rows: Vec<Vec<(usize, Real)>> = Vec::with_capacity(2 * sheet.joints.len());
    for joint in &sheet.joints {
        let mut pair = [Vec::with_capacity(6), Vec::with_capacity(6)];
        for (tile, sign) in [(joint.a, 1.0), (joint.b, -1.0)] {
            if tile == 0 {
                continue;
            }
            let p = sheet.opened_corner(tile, joint.node);
            let pose = sheet.opened[tile];
            // ∂p/∂(x, y) = I; ∂p/∂θ = perp(p − first node's opened position)
            let d = p - Vec2::new(pose.x, pose.y);
            let c = 3 * (tile - 1);
            pair[0].push((c, sign));
            pair[0].push((c + 2, -sign * d.y));
            pair[1].push((c + 1, sign));
            pair[1].push((c + 2, sign * d.x));
        }
        rows.extend(pair);
    }
    for row in &rows {
        for &(c1, v1) in row {
            for &(c2, v2) in row {
                triplets.push(Triplet {
                    row: c1,
                    col: c2,
                    val: v1 * v2,
                });
            }
        }
    }
    let multiply = |x: &DVec| -> DVec {
        let mut y = DVec::zeros(size);
        for row in &rows {
            let jx: Real = row.iter().map(|&(c, v)| v * x[c]).sum();
            for &(c, v) in row {
                y[c] += v * jx;
            }
        }
        y
    };
    // The largest eigenvalue, by power iteration from a vector that meets every mode.
    let mut x = DVec::from_fn(size, |i, _| 1.0 + (i % 7) as Real / 7.0);
    let mut largest: Real = 0.0;
    for _ in 0..60 {
        let y = multiply(&x);
        let norm = y.norm();
        if norm == 0.0 {
            break;
        }
        largest = x.dot(&y) / x.norm_squared();
        x = y / norm;
    }
    if largest <= 0.0 || !largest.is_finite() {
        return None;
    }
    // Shift-and-invert: (A + σI)⁻¹ has the smallest eigenvalues of A as its largest.
    let shift = 1e-10 * largest;
    let mut shifted = triplets;
    shifted.extend((0..size).map(|k| Triplet {
        row: k,
        col: k,
        val: shift,
    }));
    let m = SparseColMat::<usize, Real>::try_new_from_triplets(size, size, &shifted).ok()?;
    let symbolic = SymbolicLlt::try_new(m.symbolic(), Side::Lower).ok()?;
    let llt = Llt::try_new_with_symbolic(symbolic, m.as_ref(), Side::Lower).ok()?;
    let k = MAX_COUNTED.min(size);
    let mut basis = DMat::from_fn(size, k, |i, j| {
        // A deterministic start that is not orthogonal to any low mode.
        let h = (i as u64 + 1).wrapping_mul(2654435761) ^ (j as u64 + 1).wrapping_mul(40503);
        (h % 1000) as Real / 1000.0 - 0.5
    });
    let mut values: Vec<Real> = Vec::new();
    for _ in 0..ROUNDS {
        basis = orthonormal(basis);
        let mut rhs = Mat::<Real>::from_fn(size, k, |i, j| basis[(i, j)]);
        llt.solve_in_place(rhs.as_mut());
        let next = orthonormal(DMat::from_fn(size, k, |i, j| rhs[(i, j)]));
        // Rayleigh–Ritz on A itself (not the shifted inverse) for accurate small values.
        let applied = DMat::from_columns(
            &(0..k)
                .map(|j| multiply(&next.column(j).into_owned()))
                .collect::<Vec<_>>(),
        );
        let projected = next.transpose() * &applied;
        let projected = (&projected + projected.transpose()) * 0.5;
        let spectrum = crate::math::symmetric_eigen(projected)?;
        basis = &next * &spectrum.vectors;
        values = spectrum.values;
    }
    let mut singular: Vec<Real> = values
        .iter()
        .map(|v| (v.max(0.0) / largest).sqrt())
        .collect();
    singular.sort_by(Real::total_cmp);
    let zero = singular.iter().filter(|&&s| s <= RANK_TOLERANCE).count();
    let small = [
        singular.first().copied().unwrap_or(0.0),
        singular.get(1).copied().unwrap_or(0.0),
    ];
    Some((zero, small))
}

/// The columns of `m` made orthonormal (modified Gram–Schmidt, twice for stability).
fn orthonormal(mut m: DMat) -> DMat {
    for _ in 0..2 {
        for j in 0..m.ncols() {
            for i in 0..j {
                let d = m.column(i).dot(&m.column(j));
                let ci = m.column(i).into_owned();
                m.column_mut(j).axpy(-d, &ci, 1.0);
            }
            let n = m.column(j).norm();
            if n > 0.0 {
                m.column_mut(j).unscale_mut(n);
            }
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::super::{setup, GradedRequest};
    use super::*;
    use crate::math::symmetric_eigen;

    /// The dense count, for comparison: every singular value of the full Jacobian.
    fn dense(sheet: &GradedSheet) -> (usize, Real) {
        let t = sheet.tiles.len();
        let mut j = DMat::zeros(2 * sheet.joints.len(), 3 * t);
        for (r, joint) in sheet.joints.iter().enumerate() {
            for (tile, sign) in [(joint.a, 1.0), (joint.b, -1.0)] {
                let p = sheet.opened_corner(tile, joint.node);
                let pose = sheet.opened[tile];
                let d = p - Vec2::new(pose.x, pose.y);
                j[(2 * r, 3 * tile)] += sign;
                j[(2 * r + 1, 3 * tile + 1)] += sign;
                j[(2 * r, 3 * tile + 2)] += sign * -d.y;
                j[(2 * r + 1, 3 * tile + 2)] += sign * d.x;
            }
        }
        let spectrum = symmetric_eigen(j.transpose() * &j).unwrap();
        let mut sv: Vec<Real> = spectrum.values.iter().map(|v| v.max(0.0).sqrt()).collect();
        sv.sort_by(|a, b| b.total_cmp(a));
        let rank = sv.iter().filter(|&&s| s > RANK_TOLERANCE * sv[0]).count();
        let n = sv.len();
        ((3 * t).saturating_sub(rank + 3), sv[n - 5] / sv[0])
    }

    /// A large sheet barely open is still one mechanism: the ungraded rotating squares,
    /// 20×20 tiles, 5 % of the way along its motion. Its next singular value is a soft
    /// motion of the whole sheet (small because the sheet is large and nearly closed), far
    /// above the mechanism's own; the threshold fixed near it before (1e-4) counted two DOF
    /// here.
    #[test]
    fn a_large_sheet_barely_open_counts_one_dof() {
        let request = GradedRequest {
            design: "rotating-squares".into(),
            rows: 10,
            cols: 10,
            states: 1,
            t: Some(0.05),
            ..GradedRequest::default()
        };
        let (sheet, _) = setup(&request).unwrap();
        assert_eq!(sheet.tiles.len(), 400);
        let (count, small) = dof(&sheet).unwrap();
        assert_eq!(count, 1, "{small:?}");
        assert!(small[0] < 1e-8, "{small:?}");
        assert!(
            small[1] < 1e-4 && small[1] > 5.0 * RANK_TOLERANCE,
            "{small:?}"
        );
    }

    /// The periodic start of rotating squares (a one-DOF sheet) and the same sheet with
    /// pins removed (more DOF) count as the dense decomposition counts them.
    #[test]
    fn the_sparse_count_matches_the_dense_one() {
        let request = GradedRequest {
            design: "rotating-squares".into(),
            rows: 3,
            cols: 3,
            states: 1,
            ..GradedRequest::default()
        };
        let (sheet, _) = setup(&request).unwrap();
        let (count, small) = dof(&sheet).unwrap();
        let (dense_count, dense_next) = dense(&sheet);
        assert_eq!(count, 1);
        assert_eq!(count, dense_count);
        assert!(small[0] < 1e-6, "{small:?}");
        // The next singular value: the held tile changes it a little, not its order.
        assert!(
            small[1] > 10.0 * RANK_TOLERANCE,
            "{small:?} vs dense {dense_next}"
        );
        for cut in [2, 5] {
            let mut loose = sheet.clone();
            loose.joints.truncate(loose.joints.len() - cut);
            let (count, _) = dof(&loose).unwrap();
            assert_eq!(count, dense(&loose).0, "{cut} pins removed");
            assert!(count > 1);
        }
    }
}

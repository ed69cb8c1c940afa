//! The first-order motions of a finite sheet: the kernel of its sparse H = JᵀJ.
//!
//! J has two rows per pin and three columns (x, y, θ) per tile, with no lattice columns: the
//! boundary is free. One reference tile's columns are left out, which removes the three
//! rigid motions of its piece, so the kernel's dimension is the sheet's degrees of freedom
//! (for a sheet in one piece).
//!
//! Sheets of thousands of tiles are too big for a dense eigen-solver, so the kernel comes
//! from subspace iteration with H + σI factorised once by a sparse Cholesky (faer: AMD
//! ordering, supernodal) and σ far below the zero threshold: each solve multiplies a kernel
//! direction by 1/σ and any other by 1/(λ + σ), so a few solves leave a block that spans
//! the kernel, and Rayleigh–Ritz on it gives the small eigenvalues and their vectors. The
//! block grows until it holds at least two non-zero Ritz values (so the gap to the smallest
//! non-zero eigenvalue is seen). Small sheets use the dense solver directly.
//!
//! ## Which eigenvalues are zero
//!
//! No fixed threshold separates them. A sheet's softest real motion stiffens as the sheet
//! grows — the lowest non-zero eigenvalue of rotating squares' H is 6.1e-6 at 10×10, 2.9e-7
//! at 20×20 and 1.5e-8 at 40×40 — while its true zeros stay at rounding, about ε·λ_max.
//! A threshold fixed at 1e-9·λ_max therefore counts large sheets' soft motions as motions
//! (an IH15 sheet of 14×14 cells, one DOF by a dense SVD, was pruned by 252 tiles).
//! So the rank is decided by the spectrum itself ([`zero_count`]): eigenvalues are scaled
//! by λ_max (a Gershgorin bound), anything below the rounding floor `ε · √unknowns` is
//! rounding (a backward-stable eigenvalue of H is off by about ε·λ_max times a factor that
//! grows with its size, like √size for errors of independent sign), and the zeros are the eigenvalues below the largest
//! relative gap `μ_{k} / max(μ_{k−1}, floor)` of the sorted, scaled spectrum, the gap's lower
//! side within [`ZERO_REACH`] floors. The zeros form one cluster at rounding (measured at
//! 1e-19..1e-20 of λ_max) and the motions another, decades above the floor at every size
//! tested (rotating squares' softest 2e-9 of λ_max at 40×40, against a floor of 2e-14);
//! within either cluster neighbouring eigenvalues differ by small factors, so the largest
//! ratio is the gap between them. The reach keeps a soft but real motion, far above
//! rounding yet far below the stiff ones, from being counted as a zero because the gap
//! above it is the larger. A sheet whose lowest eigenvalue is itself above the reach (rigid,
//! no motion) has no zero.

use super::error::FiniteError;
use super::sheet::FiniteSheet;
use crate::kinematics::Mechanism;
use crate::math::{perp, rotation, symmetric_eigen, xorshift, DMat, Real, Vec2};
use crate::stop::KeepGoing;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::{Mat, Side};

/// Sheets with at most this many unknowns use the dense eigen-solver.
const DENSE_MAX: usize = 90;

/// Solves per round of subspace iteration.
const SOLVES: usize = 3;

/// The kernel of a finite sheet's H at one state.
#[derive(Debug, Clone)]
pub struct SheetKernel {
    /// The tile whose columns were left out (its velocity is zero in every vector).
    pub reference: usize,
    /// Degrees of freedom: eigenvalues below the spectrum's largest relative gap.
    pub dof: usize,
    /// The rounding floor `ε · √unknowns · λ_max` (λ_max a Gershgorin bound): eigenvalues
    /// below it are rounding whatever the gap.
    pub threshold: Real,
    /// The lowest eigenvalues computed, ascending (every eigenvalue for a small sheet).
    pub values: Vec<Real>,
    /// The scale the eigenvalues are judged against: a Gershgorin bound on λ_max.
    pub scale: Real,
    /// Largest eigenvalue counted as zero.
    pub largest_zero: Option<Real>,
    /// Smallest eigenvalue counted as non-zero (a Ritz value: an upper bound when the
    /// iteration has not converged on it).
    pub smallest_nonzero: Option<Real>,
    /// The kernel, one column per motion, in full sheet coordinates (3 per tile, x, y, θ;
    /// the reference tile's rows zero), orthonormal.
    pub vectors: DMat,
}

impl SheetKernel {
    /// log10(smallest non-zero / largest zero), the largest zero taken no lower than the
    /// rounding floor (a zero computed as 1e-300, or negative, is rounding all the same).
    pub fn gap_decades(&self) -> Option<Real> {
        match (self.largest_zero, self.smallest_nonzero) {
            (Some(z), Some(nz)) => Some((nz / z.max(self.threshold)).log10()),
            _ => None,
        }
    }
}

/// Rounding floor of the scaled spectrum: ε times the square root of the number of unknowns
/// (rounding errors of independent sign add up like a random walk).
pub fn rounding_floor(unknowns: usize) -> Real {
    Real::EPSILON * (unknowns.max(1) as Real).sqrt()
}

/// A zero may sit at most this many rounding floors up: an eigenvalue further above rounding
/// is a motion's stiffness, however soft (a closed IH1 sheet has one at 50 floors, 3e-12 of
/// λ_max, a singular value 7e-6 of J's where its zeros are 1e-19).
pub const ZERO_REACH: Real = 10.0;

/// How many of the ascending eigenvalues `values` (the lowest of H's, possibly not all) are
/// zero: those below the largest ratio `μ_k / max(μ_{k−1}, floor)` of the spectrum scaled by
/// `scale` (λ_max), with μ_{−1} = floor = [`rounding_floor`]`(unknowns)`, among the splits
/// whose lower side is within [`ZERO_REACH`] floors (see the module documentation). Ties go
/// to the lower split.
pub fn zero_count(values: &[Real], scale: Real, unknowns: usize) -> usize {
    let floor = rounding_floor(unknowns);
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let mut below = floor;
    let mut best = (0, Real::NEG_INFINITY);
    for (k, &v) in values.iter().enumerate() {
        if below > ZERO_REACH * floor {
            break;
        }
        let mu = (v / scale).max(floor);
        let ratio = mu / below;
        if ratio > best.1 {
            best = (k, ratio);
        }
        below = mu;
    }
    // Every computed eigenvalue within reach of the floor: all are zeros.
    if values.iter().all(|&v| v / scale <= ZERO_REACH * floor) {
        return values.len();
    }
    best.0
}

/// The 2 × 6 Jacobian block of one pin: columns (x_a, y_a, θ_a, x_b, y_b, θ_b).
fn pin_rows(s_a: Vec2, theta_a: Real, s_b: Vec2, theta_b: Real) -> [[Real; 6]; 2] {
    let da = rotation(theta_a) * perp(&s_a);
    let db = rotation(theta_b) * perp(&s_b);
    [
        [1.0, 0.0, da.x, -1.0, 0.0, -db.x],
        [0.0, 1.0, da.y, 0.0, -1.0, -db.y],
    ]
}

/// The largest piece's lowest tile (the reference whose columns are left out).
fn reference_tile(sheet: &FiniteSheet) -> usize {
    sheet
        .in_largest_piece()
        .iter()
        .position(|&inside| inside)
        .unwrap_or(0)
}

/// The kernel of the sheet's H at tile poses `poses` (as [`FiniteSheet::poses`] gives).
/// `keep_going` is polled between the sparse solver's solves: `false` ends the work with
/// [`FiniteError::Cancelled`].
pub fn sheet_kernel(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    poses: &[(Vec2, Real)],
    keep_going: KeepGoing<'_>,
) -> Result<SheetKernel, FiniteError> {
    let n = sheet.len();
    if n == 0 {
        return Err(FiniteError::EmptySheet);
    }
    if poses
        .iter()
        .any(|(p, t)| !(p.x.is_finite() && p.y.is_finite() && t.is_finite()))
    {
        return Err(FiniteError::NonFinite);
    }
    let reference = reference_tile(sheet);
    // Column of (tile, coordinate) in the reduced matrix.
    let col = |tile: usize, d: usize| -> Option<usize> {
        match tile.cmp(&reference) {
            std::cmp::Ordering::Less => Some(3 * tile + d),
            std::cmp::Ordering::Equal => None,
            std::cmp::Ordering::Greater => Some(3 * tile + d - 3),
        }
    };
    let size = 3 * (n - 1);
    // H = JᵀJ pin by pin (lower triangle and diagonal), then summed per entry in (row,
    // column) order: a fixed order, so that results repeat to the last digit.
    let mut listed: Vec<((usize, usize), Real)> = Vec::with_capacity(36 * sheet.joints.len());
    for j in &sheet.joints {
        let joint = &mech.joints[j.joint];
        let rows = pin_rows(joint.s_a, poses[j.a].1, joint.s_b, poses[j.b].1);
        let cols: [Option<usize>; 6] = [
            col(j.a, 0),
            col(j.a, 1),
            col(j.a, 2),
            col(j.b, 0),
            col(j.b, 1),
            col(j.b, 2),
        ];
        for r in 0..6 {
            for c in 0..6 {
                let (Some(cr), Some(cc)) = (cols[r], cols[c]) else {
                    continue;
                };
                if cr < cc {
                    continue;
                }
                let v = rows[0][r] * rows[0][c] + rows[1][r] * rows[1][c];
                if v != 0.0 {
                    listed.push(((cr, cc), v));
                }
            }
        }
    }
    listed.sort_by_key(|&(rc, _)| rc);
    let mut entries: Vec<((usize, usize), Real)> = Vec::with_capacity(listed.len());
    for (rc, v) in listed {
        match entries.last_mut() {
            Some((last, sum)) if *last == rc => *sum += v,
            _ => entries.push((rc, v)),
        }
    }
    // Gershgorin bound on λ_max (H is symmetric: row sums over both triangles).
    let mut row_sum = vec![0.0; size];
    for &((r, c), v) in &entries {
        row_sum[r] += v.abs();
        if r != c {
            row_sum[c] += v.abs();
        }
    }
    let lambda_max = row_sum
        .iter()
        .copied()
        .fold(0.0, Real::max)
        .max(Real::MIN_POSITIVE);
    let threshold = rounding_floor(size) * lambda_max;
    let (values, vectors) = if size <= DENSE_MAX {
        dense_spectrum(&entries, size)?
    } else {
        sparse_spectrum(&entries, size, lambda_max, keep_going)?
    };
    let dof = zero_count(&values, lambda_max, size);
    // Lift the kernel vectors to full coordinates (the reference tile's rows zero).
    let mut full = DMat::zeros(3 * n, dof);
    for k in 0..dof {
        for t in 0..n {
            for d in 0..3 {
                if let Some(c) = col(t, d) {
                    full[(3 * t + d, k)] = vectors[(c, k)];
                }
            }
        }
    }
    Ok(SheetKernel {
        reference,
        dof,
        threshold,
        largest_zero: values[..dof].last().copied(),
        smallest_nonzero: values.get(dof).copied(),
        values,
        scale: lambda_max,
        vectors: full,
    })
}

/// Ascending eigenvalues and their vectors of the whole reduced H (dense).
fn dense_spectrum(
    entries: &[((usize, usize), Real)],
    size: usize,
) -> Result<(Vec<Real>, DMat), FiniteError> {
    let mut h = DMat::zeros(size, size);
    for &((r, c), v) in entries {
        h[(r, c)] = v;
        h[(c, r)] = v;
    }
    let spec = symmetric_eigen(h).ok_or(FiniteError::Eigen)?;
    Ok((spec.values, spec.vectors))
}

/// The smallest eigenvalues (the zeros by [`zero_count`] and at least two above them, or
/// all) and their vectors, by shift-inverted subspace iteration on a sparse Cholesky factor.
/// `keep_going` is polled between solves.
fn sparse_spectrum(
    entries: &[((usize, usize), Real)],
    size: usize,
    lambda_max: Real,
    keep_going: KeepGoing<'_>,
) -> Result<(Vec<Real>, DMat), FiniteError> {
    // σ near the rounding floor (so kernel directions dominate after a few solves, and the
    // softest motions of a large sheet, ~1e-9·λ_max, are still far above it), large enough
    // for the factorisation of a singular H + σI to stay positive.
    let mut sigma = 1e-12 * lambda_max;
    let llt = loop {
        let mut triplets: Vec<Triplet<usize, usize, Real>> = entries
            .iter()
            .map(|&((r, c), v)| Triplet {
                row: r,
                col: c,
                val: v,
            })
            .collect();
        triplets.extend((0..size).map(|i| Triplet {
            row: i,
            col: i,
            val: sigma,
        }));
        let h = SparseColMat::<usize, Real>::try_new_from_triplets(size, size, &triplets)
            .map_err(|_| FiniteError::Factorisation)?;
        match h.sp_cholesky(Side::Lower) {
            Ok(llt) => break llt,
            Err(_) if sigma < 1e-10 * lambda_max => sigma *= 10.0,
            Err(_) => return Err(FiniteError::Factorisation),
        }
    };
    let listed: Vec<(usize, usize, Real)> = entries.iter().map(|&((r, c), v)| (r, c, v)).collect();
    let multiply = |x: &DMat| -> DMat {
        let mut y = DMat::zeros(x.nrows(), x.ncols());
        for &(r, c, v) in &listed {
            for k in 0..x.ncols() {
                y[(r, k)] += v * x[(c, k)];
                if r != c {
                    y[(c, k)] += v * x[(r, k)];
                }
            }
        }
        y
    };
    let mut block = 16.min(size);
    // A fixed pseudo-random start, so that results repeat.
    let mut random = xorshift(0x2545_f491_4f6c_dd1d);
    loop {
        let mut m = Mat::<Real>::from_fn(size, block, |_, _| random() - 0.5);
        for _ in 0..SOLVES {
            if !keep_going() {
                return Err(FiniteError::Cancelled);
            }
            llt.solve_in_place(m.as_mut());
            // faer's blocked Householder QR: a tall block's orthonormal basis at GEMM speed
            // (nalgebra's column-by-column reflections were two thirds of a 40×40 count).
            m = m.qr().compute_thin_Q();
        }
        let x = DMat::from_fn(size, block, |r, c| m[(r, c)]);
        if x.iter().any(|v| !v.is_finite()) {
            return Err(FiniteError::NonFinite);
        }
        let hx = multiply(&x);
        let small = x.transpose() * &hx;
        let small = (&small + small.transpose()) * 0.5;
        let spec = symmetric_eigen(small).ok_or(FiniteError::Eigen)?;
        let zeros = zero_count(&spec.values, lambda_max, size);
        if zeros + 2 <= block || block == size {
            let vectors = &x * spec.vectors;
            return Ok((spec.values, vectors));
        }
        block = (2 * block).min(size);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spectra made by a rule (seeded): k zeros at rounding (anywhere in ±floor, negative
    /// ones included), then motions from a lowest one 1e-9..1e-2 of λ_max (a sheet's soft
    /// motions at any size) rising by factors up to 30 to λ_max. The count is k every time,
    /// whatever the scale of H.
    #[test]
    fn the_zeros_are_the_cluster_below_the_largest_gap() {
        let mut rand = xorshift(0x9e37_79b9_7f4a_7c15);
        for case in 0..2000 {
            let unknowns = 30 + (rand() * 20_000.0) as usize;
            let scale = (10.0 as Real).powf(4.0 * rand() - 2.0);
            let floor = rounding_floor(unknowns);
            let k = (rand() * 6.0) as usize;
            let mut values: Vec<Real> = (0..k)
                .map(|_| (2.0 * rand() - 1.0) * floor * scale)
                .collect();
            let mut mu = (10.0 as Real).powf(-9.0 + 7.0 * rand());
            while mu < 1.0 && values.len() < k + 40 {
                values.push(mu * scale);
                mu *= 1.0 + 29.0 * rand();
            }
            values.sort_by(Real::total_cmp);
            assert_eq!(
                zero_count(&values, scale, unknowns),
                k,
                "case {case}: {values:?}"
            );
        }
    }

    #[test]
    fn a_spectrum_all_at_rounding_is_all_zeros_and_none_is_none() {
        assert_eq!(zero_count(&[0.0, 1e-17, -1e-16], 2.0, 100), 3);
        assert_eq!(zero_count(&[], 2.0, 100), 0);
        assert_eq!(zero_count(&[1e-3, 2e-3, 0.5], 2.0, 100), 0);
    }

    /// The closed IH1 sheet of the issue: a zero at 1e-19, a soft motion 50 floors up, the
    /// stiff ones from 1e-7: one zero, though the gap above the soft motion is the larger.
    #[test]
    fn a_soft_motion_far_above_rounding_is_not_a_zero() {
        let floor = rounding_floor(318);
        let values = [2e-19, 50.0 * floor, 9e-8, 1e-5, 1.3e-5];
        assert_eq!(zero_count(&values, 1.0, 318), 1);
    }

    #[test]
    fn the_gap_is_finite_when_the_largest_zero_is_negative_or_nil() {
        let kernel = |z: Real| SheetKernel {
            reference: 0,
            dof: 1,
            threshold: 1e-13,
            largest_zero: Some(z),
            smallest_nonzero: Some(1e-6),
            values: vec![z, 1e-6],
            scale: 1.0,
            vectors: DMat::zeros(3, 1),
        };
        for z in [-3e-15, 0.0, 1e-300] {
            let gap = kernel(z).gap_decades().unwrap();
            assert!((gap - 7.0).abs() < 1e-9, "{z}: {gap}");
        }
        assert!((kernel(1e-11).gap_decades().unwrap() - 5.0).abs() < 1e-9);
    }
}

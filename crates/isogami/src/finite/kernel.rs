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

use super::error::FiniteError;
use super::sheet::FiniteSheet;
use crate::kinematics::Mechanism;
use crate::math::{perp, rotation, symmetric_eigen, DMat, Real, Vec2};
use crate::mobility::MobilitySettings;
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
    /// Degrees of freedom: eigenvalues below the threshold.
    pub dof: usize,
    /// The zero threshold: `rel_tol · max(λ_max bound, 1)`.
    pub threshold: Real,
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
    /// log10(smallest non-zero / largest zero), capped at 300.
    pub fn gap_decades(&self) -> Option<Real> {
        match (self.largest_zero, self.smallest_nonzero) {
            (Some(z), Some(nz)) => Some((nz / z.max(1e-300)).log10().min(300.0)),
            _ => None,
        }
    }
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
pub fn sheet_kernel(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    poses: &[(Vec2, Real)],
    settings: MobilitySettings,
) -> Result<SheetKernel, FiniteError> {
    settings.validate()?;
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
    let lambda_max = row_sum.iter().copied().fold(0.0, Real::max);
    let threshold = settings.rel_tol * lambda_max.max(1.0);
    let (values, vectors) = if size <= DENSE_MAX {
        dense_spectrum(&entries, size)?
    } else {
        sparse_spectrum(&entries, size, threshold)?
    };
    let dof = values.iter().filter(|&&v| v < threshold).count();
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

/// The smallest eigenvalues (every one below `threshold` and at least two above it, or all)
/// and their vectors, by shift-inverted subspace iteration on a sparse Cholesky factor.
fn sparse_spectrum(
    entries: &[((usize, usize), Real)],
    size: usize,
    threshold: Real,
) -> Result<(Vec<Real>, DMat), FiniteError> {
    // σ well below the threshold (so kernel directions dominate after a few solves), large
    // enough for the factorisation of a singular H + σI to stay positive.
    let mut sigma = 1e-3 * threshold;
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
            Err(_) if sigma < 0.1 * threshold => sigma *= 10.0,
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
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    loop {
        // A fixed pseudo-random start, so that results repeat.
        let mut x = DMat::from_fn(size, block, |_, _| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as Real / (1u64 << 53) as Real - 0.5
        });
        for _ in 0..SOLVES {
            let mut m = Mat::<Real>::from_fn(size, block, |r, c| x[(r, c)]);
            llt.solve_in_place(m.as_mut());
            x = DMat::from_fn(size, block, |r, c| m[(r, c)]);
            x = x.qr().q();
        }
        if x.iter().any(|v| !v.is_finite()) {
            return Err(FiniteError::NonFinite);
        }
        let hx = multiply(&x);
        let small = x.transpose() * &hx;
        let small = (&small + small.transpose()) * 0.5;
        let spec = symmetric_eigen(small).ok_or(FiniteError::Eigen)?;
        let zeros = spec.values.iter().filter(|&&v| v < threshold).count();
        if zeros + 2 <= block || block == size {
            let vectors = &x * spec.vectors;
            return Ok((spec.values, vectors));
        }
        block = (2 * block).min(size);
    }
}

//! Scalar and vector aliases plus the small dense linear algebra the pipeline needs.
//!
//! Every decomposition goes through this module so the backend (nalgebra today) can change in
//! one place. Iterative decompositions are always called with an iteration cap: the unbounded
//! forms can spin forever on bad input. Nothing here knows about tiles or joints.

/// The one scalar type of the pipeline.
pub type Real = f64;
/// A 2D point or vector.
pub type Vec2 = nalgebra::Vector2<Real>;
/// A 2×2 matrix.
pub type Mat2 = nalgebra::Matrix2<Real>;
/// A dense dynamically sized matrix.
pub type DMat = nalgebra::DMatrix<Real>;
/// A dense dynamically sized vector.
pub type DVec = nalgebra::DVector<Real>;

/// Iteration cap for symmetric eigen-decompositions (QR sweeps).
pub const EIGEN_MAX_ITER: usize = 10_000;

/// A seeded xorshift stream of reals in [0, 1): a fixed pseudo-random sequence, so that what
/// it starts (an iteration's first block, a test's generated cases) repeats run after run.
pub fn xorshift(mut seed: u64) -> impl FnMut() -> Real {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as Real / (1u64 << 53) as Real
    }
}

/// Builds a 2D vector.
#[inline]
pub fn vec2(x: Real, y: Real) -> Vec2 {
    Vec2::new(x, y)
}

/// 2D cross product (z component of the 3D cross product).
#[inline]
pub fn cross(a: &Vec2, b: &Vec2) -> Real {
    a.x * b.y - a.y * b.x
}

/// Rotation of `v` by +90°.
#[inline]
pub fn perp(v: &Vec2) -> Vec2 {
    vec2(-v.y, v.x)
}

/// Rotation matrix for angle `theta` (radians, counter-clockwise).
#[inline]
pub fn rotation(theta: Real) -> Mat2 {
    let (s, c) = theta.sin_cos();
    Mat2::new(c, -s, s, c)
}

/// Eigenvalues (ascending) and matching unit eigenvectors (columns) of a symmetric matrix.
#[derive(Debug, Clone)]
pub struct SymmetricSpectrum {
    /// Eigenvalues in ascending order.
    pub values: Vec<Real>,
    /// Column `k` is the unit eigenvector of `values[k]`.
    pub vectors: DMat,
}

/// Symmetric eigen-decomposition with an iteration cap; `None` when it does not converge or
/// the input holds a non-finite entry.
pub fn symmetric_eigen(h: DMat) -> Option<SymmetricSpectrum> {
    if h.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let n = h.nrows();
    if n == 0 {
        return Some(SymmetricSpectrum {
            values: Vec::new(),
            vectors: DMat::zeros(0, 0),
        });
    }
    let eig = nalgebra::SymmetricEigen::try_new(h, Real::EPSILON, EIGEN_MAX_ITER)?;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let values = order.iter().map(|&k| eig.eigenvalues[k]).collect();
    let vectors = DMat::from_fn(n, n, |r, c| eig.eigenvectors[(r, order[c])]);
    Some(SymmetricSpectrum { values, vectors })
}

//! Deformation gradient, polar decomposition and directional expansion of 2×2 maps.

use super::error::MeasureError;
use crate::math::{cross, Mat2, Real, Vec2};
use std::f64::consts::TAU;

/// Relative threshold below which the closed tiling vectors count as parallel.
const DEGENERATE_LATTICE: Real = 1e-12;

/// Expansions smaller than this (in absolute value) make a Poisson ratio meaningless.
pub(crate) const POISSON_MIN_EXPANSION: Real = 1e-9;

fn finite(vs: &[&Vec2]) -> bool {
    vs.iter().all(|v| v.iter().all(|x| x.is_finite()))
}

fn mat_finite(m: &Mat2) -> bool {
    m.iter().all(|x| x.is_finite())
}

/// The macroscopic deformation gradient F with [u w] = F [u0 w0] (paper eq. 10).
///
/// `u0`, `w0` are the closed-state tiling vectors, `u`, `w` the current ones. Errors when an
/// input is not finite or when u0, w0 are (nearly) parallel, |u0 × w0| ≤ 1e-12 |u0||w0|.
pub fn deformation_gradient(
    u0: &Vec2,
    w0: &Vec2,
    u: &Vec2,
    w: &Vec2,
) -> Result<Mat2, MeasureError> {
    if !finite(&[u0, w0, u, w]) {
        return Err(MeasureError::NonFiniteLattice {
            u0: *u0,
            w0: *w0,
            u: *u,
            w: *w,
        });
    }
    let det0 = cross(u0, w0);
    if det0.abs() <= DEGENERATE_LATTICE * u0.norm() * w0.norm() {
        return Err(MeasureError::ParallelLattice { u0: *u0, w0: *w0 });
    }
    let closed = Mat2::from_columns(&[*u0, *w0]);
    let current = Mat2::from_columns(&[*u, *w]);
    // Explicit 2×2 inverse: closed⁻¹ = adj(closed) / det0.
    let inv = Mat2::new(w0.y, -w0.x, -u0.y, u0.x) / det0;
    let f = current * inv;
    debug_assert!((f * closed - current).norm() <= 1e-9 * (1.0 + current.norm()));
    Ok(f)
}

/// Polar decomposition F = RU: R a rotation, U symmetric positive definite (closed form).
///
/// With F = [[a, b], [c, d]], R is the rotation by φ = atan2(c − b, a + d), the unique angle
/// for which RᵀF is symmetric with positive trace; U = RᵀF (symmetrised to remove rounding).
/// Errors when F has a non-finite entry or det F ≤ 0 (an inverted or collapsed lattice has no
/// such decomposition): the result is never NaN.
pub fn polar(f: &Mat2) -> Result<(Mat2, Mat2), MeasureError> {
    if !mat_finite(f) {
        return Err(MeasureError::NonFiniteGradient {
            f: [f[(0, 0)], f[(1, 0)], f[(0, 1)], f[(1, 1)]],
        });
    }
    let det = f.determinant();
    if det <= 0.0 {
        return Err(MeasureError::Inverted { det });
    }
    let (a, b, c, d) = (f[(0, 0)], f[(0, 1)], f[(1, 0)], f[(1, 1)]);
    // det F > 0 forbids a + d = c − b = 0 (a symmetric RᵀF with zero trace has det ≤ 0).
    let phi = (c - b).atan2(a + d);
    let r = crate::math::rotation(phi);
    let u = r.transpose() * f;
    let off = 0.5 * (u[(0, 1)] + u[(1, 0)]);
    let u = Mat2::new(u[(0, 0)], off, off, u[(1, 1)]);
    Ok((r, u))
}

/// Directional expansion ε(θ) = dᵀ(U − I)d with d = (cos θ, sin θ).
pub fn directional_expansion(u: &Mat2, theta: Real) -> Real {
    let (s, c) = theta.sin_cos();
    let off = u[(0, 1)] + u[(1, 0)];
    c * c * (u[(0, 0)] - 1.0) + s * s * (u[(1, 1)] - 1.0) + c * s * off
}

/// Principal expansions (min, max): the eigenvalues of U − I (U is symmetrised first).
pub fn principal_expansions(u: &Mat2) -> (Real, Real) {
    let (a, d) = (u[(0, 0)], u[(1, 1)]);
    let b = 0.5 * (u[(0, 1)] + u[(1, 0)]);
    let mean = 0.5 * (a + d);
    let radius = (0.5 * (a - d)).hypot(b);
    (mean - radius - 1.0, mean + radius - 1.0)
}

/// Two principal stretches that differ by at most this fraction of their mean count as equal
/// (U isotropic), and [`principal_direction`] is then exactly 0.
///
/// Why: when U is a multiple of I every direction is principal, and the angle atan2 computes
/// from the off-diagonal entries of a nearly isotropic U is the angle of its rounding and
/// solver noise, jumping anywhere in (−π/2, π/2] from one frame to the next (rotating squares
/// reported 0, ±0.785, −1.339 and −1.555 over one deployment). Accepted states close every
/// joint to 1e-9 of the mean edge length, which perturbs the stretches by about that fraction;
/// a real anisotropy worth a direction is many orders larger.
pub const ISOTROPIC_STRETCH_TOL: Real = 1e-9;

/// Angle in (−π/2, π/2] of the direction of maximum expansion (eigenvector of the larger
/// eigenvalue of U). Exactly 0 when U is isotropic, its principal stretches differing by at
/// most [`ISOTROPIC_STRETCH_TOL`] times their mean (every direction is then principal, and
/// any other angle would be noise).
pub fn principal_direction(u: &Mat2) -> Real {
    let (a, d) = (u[(0, 0)], u[(1, 1)]);
    let b = 0.5 * (u[(0, 1)] + u[(1, 0)]);
    // Difference of the principal stretches, 2·radius, against their mean.
    let spread = 2.0 * (0.5 * (a - d)).hypot(b);
    let mean = 0.5 * (a + d);
    if spread <= ISOTROPIC_STRETCH_TOL * mean.abs() {
        return 0.0;
    }
    0.5 * (2.0 * b).atan2(a - d)
}

/// The directional profile of U for a polar plot: `n` samples (θ_k, ε(θ_k)) with
/// θ_k = 2πk/n, k = 0..n (the curve is closed by joining the last sample to the first).
pub fn expansion_profile(u: &Mat2, n: usize) -> Vec<(Real, Real)> {
    (0..n)
        .map(|k| {
            let theta = TAU * k as Real / n as Real;
            (theta, directional_expansion(u, theta))
        })
        .collect()
}

/// Area ratio of the deployed to the closed cell: det F.
pub fn area_ratio(f: &Mat2) -> Real {
    f.determinant()
}

/// Effective Poisson ratio −ε_min/ε_max of one frame (−1 for isotropic expansion, positive
/// when one direction shrinks while the other grows). `None` when ε_max is within 1e-9 of 0
/// or an input is not finite, where the ratio means nothing.
pub fn effective_poisson_ratio(min: Real, max: Real) -> Option<Real> {
    if !min.is_finite() || !max.is_finite() || max.abs() <= POISSON_MIN_EXPANSION {
        return None;
    }
    Some(-min / max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{rotation, vec2};
    use std::f64::consts::{FRAC_PI_2, PI};

    /// Deterministic pseudo-random numbers in [-1, 1) (xorshift), no dependency needed.
    fn rng(seed: &mut u64) -> Real {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as Real / (1u64 << 52) as Real - 1.0
    }

    fn lattice() -> (Vec2, Vec2) {
        (vec2(2.0, 0.3), vec2(-0.4, 1.7))
    }

    #[test]
    fn isotropic_stretch_and_rotation() {
        // Rotating squares at angle φ: the lattice stretches by s = cos φ + sin φ and the
        // sheet may turn as a whole; U = s I whatever the rotation.
        let (u0, w0) = lattice();
        for (phi, turn) in [(0.3, 0.0), (PI / 4.0, 1.1), (1.2, -2.5)] {
            let s: Real = phi.cos() + phi.sin();
            let m = rotation(turn) * s;
            let f = deformation_gradient(&u0, &w0, &(m * u0), &(m * w0)).unwrap();
            assert!((f - m).norm() < 1e-13);
            let (r, u) = polar(&f).unwrap();
            assert!((r - rotation(turn)).norm() < 1e-13, "R = {r}");
            assert!((u - Mat2::identity() * s).norm() < 1e-13, "U = {u}");
            let (lo, hi) = principal_expansions(&u);
            assert!((lo - (s - 1.0)).abs() < 1e-13 && (hi - (s - 1.0)).abs() < 1e-13);
            let nu = effective_poisson_ratio(lo, hi).unwrap();
            assert!((nu + 1.0).abs() < 1e-12, "Poisson ratio {nu}");
            assert!((area_ratio(&f) - s * s).abs() < 1e-12);
        }
    }

    #[test]
    fn stretch_along_a_tilted_axis_then_rotate() {
        // U = Q diag(1.5, 0.8) Qᵀ with principal axis at 30°, then a rotation of 0.7 rad.
        let axis = PI / 6.0;
        let q = rotation(axis);
        let u_true = q * Mat2::new(1.5, 0.0, 0.0, 0.8) * q.transpose();
        let f_true = rotation(0.7) * u_true;
        let (u0, w0) = lattice();
        let f = deformation_gradient(&u0, &w0, &(f_true * u0), &(f_true * w0)).unwrap();
        let (r, u) = polar(&f).unwrap();
        assert!((u - u_true).norm() < 1e-12, "U = {u}");
        assert!((r - rotation(0.7)).norm() < 1e-12);
        let (lo, hi) = principal_expansions(&u);
        assert!((lo + 0.2).abs() < 1e-12 && (hi - 0.5).abs() < 1e-12);
        assert!((principal_direction(&u) - axis).abs() < 1e-12);
        assert!((effective_poisson_ratio(lo, hi).unwrap() - 0.4).abs() < 1e-12);
        assert!((area_ratio(&f) - 1.2).abs() < 1e-12);
        // Along the principal axes ε takes the principal values.
        assert!((directional_expansion(&u, axis) - 0.5).abs() < 1e-12);
        assert!((directional_expansion(&u, axis + FRAC_PI_2) + 0.2).abs() < 1e-12);
    }

    #[test]
    fn isotropic_stretch_has_principal_angle_zero() {
        // U = s·I plus noise well inside the tolerance, in every direction: angle exactly 0
        // (atan2 of the noise alone would give anything in (−π/2, π/2]).
        let s = 1.37;
        let noise = 0.3 * ISOTROPIC_STRETCH_TOL * s;
        for axis in [0.0, 0.4, -1.2, 1.5] {
            let q = rotation(axis);
            let u = q * Mat2::new(s + noise, 0.0, 0.0, s - noise) * q.transpose();
            assert_eq!(principal_direction(&u), 0.0, "axis {axis}");
            // The raw angle of that noise is the axis, not 0: the rule is what makes it 0.
            let b = 0.5 * (u[(0, 1)] + u[(1, 0)]);
            let raw = 0.5 * (2.0 * b).atan2(u[(0, 0)] - u[(1, 1)]);
            assert!(axis == 0.0 || raw.abs() > 0.3, "axis {axis}: raw {raw}");
        }
        assert_eq!(principal_direction(&(Mat2::identity() * s)), 0.0);
        // Just above the tolerance the true direction comes back.
        let gap = 4.0 * ISOTROPIC_STRETCH_TOL * s;
        let q = rotation(0.4);
        let u = q * Mat2::new(s + gap, 0.0, 0.0, s - gap) * q.transpose();
        assert!((principal_direction(&u) - 0.4).abs() < 1e-6);
        // A clearly anisotropic U at −1.2 rad keeps its angle.
        let q = rotation(-1.2);
        let u = q * Mat2::new(1.5, 0.0, 0.0, 1.1) * q.transpose();
        assert!((principal_direction(&u) + 1.2).abs() < 1e-12);
    }

    #[test]
    fn simple_shear_has_the_known_stretch() {
        // F = [[1, γ], [0, 1]]: U has eigenvalues √(1 + γ²/4) ± γ/2 and det 1.
        let g = 0.8;
        let f = Mat2::new(1.0, g, 0.0, 1.0);
        let (_, u) = polar(&f).unwrap();
        let root = (1.0 + g * g / 4.0_f64).sqrt();
        let (lo, hi) = principal_expansions(&u);
        assert!((lo - (root - g / 2.0 - 1.0)).abs() < 1e-12);
        assert!((hi - (root + g / 2.0 - 1.0)).abs() < 1e-12);
        assert!((u.determinant() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn polar_reconstructs_random_maps() {
        let mut seed = 0x9e37_79b9_7f4a_7c15;
        let mut done = 0;
        while done < 2000 {
            let f = Mat2::new(
                3.0 * rng(&mut seed),
                3.0 * rng(&mut seed),
                3.0 * rng(&mut seed),
                3.0 * rng(&mut seed),
            );
            if f.determinant() <= 1e-6 {
                assert!(f.determinant() > 0.0 || polar(&f).is_err());
                continue;
            }
            done += 1;
            let (r, u) = polar(&f).unwrap();
            let scale = 1.0 + f.norm();
            assert!((r * u - f).norm() < 1e-12 * scale, "RU != F for {f}");
            assert!((r.transpose() * r - Mat2::identity()).norm() < 1e-13);
            assert!((r.determinant() - 1.0).abs() < 1e-13);
            assert_eq!(u[(0, 1)], u[(1, 0)]);
            let (lo, _) = principal_expansions(&u);
            assert!(lo + 1.0 > 0.0, "U not positive definite: {u}");
        }
    }

    #[test]
    fn directional_extremes_are_the_principal_expansions() {
        let mut seed = 12345;
        for _ in 0..200 {
            let f = Mat2::new(
                1.0 + rng(&mut seed),
                rng(&mut seed),
                rng(&mut seed),
                1.0 + rng(&mut seed),
            );
            let Ok((_, u)) = polar(&f) else { continue };
            let (lo, hi) = principal_expansions(&u);
            let profile = expansion_profile(&u, 20_000);
            let smin = profile.iter().map(|p| p.1).fold(Real::INFINITY, Real::min);
            let smax = profile
                .iter()
                .map(|p| p.1)
                .fold(Real::NEG_INFINITY, Real::max);
            // Sampling error is second order in the angle step: (2π/20000)² · spread.
            let tol = 1e-6 * (1.0 + hi - lo);
            assert!(
                smin >= lo - 1e-12 && (smin - lo).abs() < tol,
                "{smin} vs {lo}"
            );
            assert!(
                smax <= hi + 1e-12 && (smax - hi).abs() < tol,
                "{smax} vs {hi}"
            );
            // ... and the maximum sits at the principal direction (mod π).
            let psi = principal_direction(&u);
            assert!((directional_expansion(&u, psi) - hi).abs() < 1e-12);
        }
    }

    #[test]
    fn profile_samples_the_full_circle() {
        let u = Mat2::new(1.3, 0.1, 0.1, 0.9);
        let p = expansion_profile(&u, 8);
        assert_eq!(p.len(), 8);
        assert_eq!(p[0].0, 0.0);
        assert!((p[4].0 - PI).abs() < 1e-15);
        assert!(expansion_profile(&u, 0).is_empty());
    }

    #[test]
    fn bad_inputs_are_errors_not_nan() {
        let (u0, w0) = lattice();
        assert!(deformation_gradient(&u0, &(u0 * 2.0), &u0, &w0).is_err());
        assert!(deformation_gradient(&u0, &w0, &vec2(Real::NAN, 0.0), &w0).is_err());
        // Inverted (reflected) lattice.
        let flip = Mat2::new(1.0, 0.0, 0.0, -1.0);
        let f = deformation_gradient(&u0, &w0, &(flip * u0), &(flip * w0)).unwrap();
        assert!(
            matches!(polar(&f), Err(MeasureError::Inverted { det }) if (det - f.determinant()).abs() < 1e-12),
            "{:?}",
            polar(&f)
        );
        assert_eq!(
            deformation_gradient(&u0, &(u0 * 2.0), &u0, &w0),
            Err(MeasureError::ParallelLattice { u0, w0: u0 * 2.0 })
        );
        assert!(polar(&Mat2::zeros()).is_err());
        assert!(polar(&Mat2::new(Real::INFINITY, 0.0, 0.0, 1.0)).is_err());
        assert_eq!(effective_poisson_ratio(0.0, 0.0), None);
        assert_eq!(effective_poisson_ratio(Real::NAN, 0.5), None);
    }
}

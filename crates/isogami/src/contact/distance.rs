//! Unsigned point–segment distance with its gradient and Hessian in the six coordinates of
//! (p, a, b): point p, segment ab. As in IPC the closest feature picks the formula: the
//! endpoint a (t ≤ 0), the endpoint b (t ≥ 1) or the line through ab (0 < t < 1), where t is
//! the projection parameter of p. The distance is C¹ across the case boundaries.

use crate::math::{cross, Real, Vec2};
use nalgebra::{SMatrix, SVector};

/// A vector over (p, a, b).
pub(crate) type Vec6 = SVector<Real, 6>;
/// A matrix over (p, a, b).
pub(crate) type Mat6 = SMatrix<Real, 6, 6>;
type Vec4 = SVector<Real, 4>;
type Mat4 = SMatrix<Real, 4, 4>;

/// The distance and its derivatives over (p, a, b).
#[derive(Debug, Clone, Copy)]
pub(crate) struct DistanceDerivatives {
    pub(crate) d: Real,
    pub(crate) grad: Vec6,
    pub(crate) hess: Mat6,
}

/// Distance from p to the closed segment ab (ab may be degenerate).
#[cfg(test)]
pub(crate) fn point_edge_distance(p: &Vec2, a: &Vec2, b: &Vec2) -> Real {
    crate::geometry::point_segment_distance(p, a, b)
}

/// The square of the distance from p to the closed segment ab, by the formula of
/// [`crate::geometry::point_segment_distance`]: its square root is exactly that distance (a
/// norm is the square root of the squared norm), so the narrow phase can compare squares
/// and take one root where it needs a distance.
pub(crate) fn point_edge_distance_squared(p: &Vec2, a: &Vec2, b: &Vec2) -> Real {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 == 0.0 {
        return (p - a).norm_squared();
    }
    let t = ((p - a).dot(&ab) / len2).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm_squared()
}

/// The distance from p to segment ab with gradient and Hessian, or `None` when the distance
/// is zero or the segment degenerate (the barrier is infinite there anyway).
pub(crate) fn point_edge_derivatives(p: &Vec2, a: &Vec2, b: &Vec2) -> Option<DistanceDerivatives> {
    let (r, e) = (p - a, b - a);
    let len2 = e.norm_squared();
    if len2.is_nan() || len2 <= 0.0 {
        return None;
    }
    let t = r.dot(&e) / len2;
    if t <= 0.0 {
        point_point(p, a, 1)
    } else if t >= 1.0 {
        point_point(p, b, 2)
    } else {
        point_line(&r, &e)
    }
}

/// d = |p − x| where x is block `k` (1 = a, 2 = b) of (p, a, b).
fn point_point(p: &Vec2, x: &Vec2, k: usize) -> Option<DistanceDerivatives> {
    let v = p - x;
    let d = v.norm();
    if d.is_nan() || d <= 0.0 {
        return None;
    }
    let n = v / d;
    let proj = (nalgebra::Matrix2::identity() - n * n.transpose()) / d;
    let mut grad = Vec6::zeros();
    let mut hess = Mat6::zeros();
    grad.fixed_rows_mut::<2>(0).copy_from(&n);
    grad.fixed_rows_mut::<2>(2 * k).copy_from(&(-n));
    for (bi, bj, sign) in [(0, 0, 1.0), (k, k, 1.0), (0, k, -1.0), (k, 0, -1.0)] {
        hess.fixed_view_mut::<2, 2>(2 * bi, 2 * bj)
            .copy_from(&(proj * sign));
    }
    Some(DistanceDerivatives { d, grad, hess })
}

/// Distance from p to the line through ab, via D = c² / L in z = (r, e) = (p − a, b − a)
/// with c = cross(e, r) and L = |e|², then mapped to (p, a, b).
fn point_line(r: &Vec2, e: &Vec2) -> Option<DistanceDerivatives> {
    let c = cross(e, r);
    let l = e.norm_squared();
    let dist2 = c * c / l;
    let d = dist2.sqrt();
    if d.is_nan() || d <= 0.0 {
        return None;
    }
    let gc = Vec4::new(-e.y, e.x, r.y, -r.x);
    let mut hc = Mat4::zeros();
    (hc[(0, 3)], hc[(3, 0)], hc[(1, 2)], hc[(2, 1)]) = (-1.0, -1.0, 1.0, 1.0);
    let gl = Vec4::new(0.0, 0.0, 2.0 * e.x, 2.0 * e.y);
    let hl = Mat4::from_diagonal(&Vec4::new(0.0, 0.0, 2.0, 2.0));
    let g_d2 = gc * (2.0 * c / l) - gl * (c * c / (l * l));
    let h_d2 = gc * gc.transpose() * (2.0 / l) + hc * (2.0 * c / l)
        - (gc * gl.transpose() + gl * gc.transpose()) * (2.0 * c / (l * l))
        - hl * (c * c / (l * l))
        + gl * gl.transpose() * (2.0 * c * c / (l * l * l));
    let gz = g_d2 / (2.0 * d);
    let hz = h_d2 / (2.0 * d) - gz * gz.transpose() / d;
    // z = T x with r = p − a, e = b − a.
    #[rustfmt::skip]
    let tmat = SMatrix::<Real, 4, 6>::from_row_slice(&[
        1.0, 0.0, -1.0,  0.0, 0.0, 0.0,
        0.0, 1.0,  0.0, -1.0, 0.0, 0.0,
        0.0, 0.0, -1.0,  0.0, 1.0, 0.0,
        0.0, 0.0,  0.0, -1.0, 0.0, 1.0,
    ]);
    Some(DistanceDerivatives {
        d,
        grad: tmat.transpose() * gz,
        hess: tmat.transpose() * hz * tmat,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    fn unpack(x: &Vec6) -> (Vec2, Vec2, Vec2) {
        (vec2(x[0], x[1]), vec2(x[2], x[3]), vec2(x[4], x[5]))
    }

    fn check(x: Vec6) {
        let (p, a, b) = unpack(&x);
        let dd = point_edge_derivatives(&p, &a, &b).unwrap();
        assert!((dd.d - point_edge_distance(&p, &a, &b)).abs() < 1e-15);
        let h = 1e-6;
        for k in 0..6 {
            let mut xp = x;
            let mut xm = x;
            xp[k] += h;
            xm[k] -= h;
            let (pp, ap, bp) = unpack(&xp);
            let (pm, am, bm) = unpack(&xm);
            let fd = (point_edge_distance(&pp, &ap, &bp) - point_edge_distance(&pm, &am, &bm))
                / (2.0 * h);
            assert!(
                (fd - dd.grad[k]).abs() < 1e-8,
                "grad {k}: {fd} vs {}",
                dd.grad[k]
            );
            let gp = point_edge_derivatives(&pp, &ap, &bp).unwrap().grad;
            let gm = point_edge_derivatives(&pm, &am, &bm).unwrap().grad;
            let col = (gp - gm) / (2.0 * h);
            for j in 0..6 {
                let want = dd.hess[(j, k)];
                assert!(
                    (col[j] - want).abs() < 1e-6,
                    "hess {j},{k}: {} vs {want}",
                    col[j]
                );
            }
        }
        assert!((dd.hess - dd.hess.transpose()).norm() < 1e-12);
    }

    #[test]
    fn squared_distance_is_the_square_of_the_distance_bit_for_bit() {
        let mut seed = 11u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 4.0 - 2.0
        };
        for k in 0..2000 {
            let (p, a) = (Vec2::new(rnd(), rnd()), Vec2::new(rnd(), rnd()));
            // Every tenth segment degenerate.
            let b = if k % 10 == 0 {
                a
            } else {
                Vec2::new(rnd(), rnd())
            };
            let d = point_edge_distance(&p, &a, &b);
            assert_eq!(point_edge_distance_squared(&p, &a, &b).sqrt(), d);
        }
    }

    #[test]
    fn derivatives_in_all_three_cases() {
        // Interior (above the segment), beyond a, beyond b.
        check(Vec6::new(0.3, 0.4, -0.2, 0.1, 1.1, -0.3));
        check(Vec6::new(-0.7, 0.5, -0.2, 0.1, 1.1, -0.3));
        check(Vec6::new(1.9, -0.2, -0.2, 0.1, 1.1, -0.3));
        // Below the segment (the other sign of the cross product).
        check(Vec6::new(0.5, -0.6, -0.2, 0.1, 1.1, -0.3));
    }
}

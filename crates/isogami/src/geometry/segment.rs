//! Segment predicates: proper crossings and distances.

use crate::math::{cross, Real, Vec2};

/// True when the open segments `ab` and `cd` cross at a single interior point of both, with
/// every endpoint farther than `tol` from the other segment's line.
pub fn segments_properly_cross(a: &Vec2, b: &Vec2, c: &Vec2, d: &Vec2, tol: Real) -> bool {
    let lab = (b - a).norm();
    let lcd = (d - c).norm();
    if lab <= tol || lcd <= tol {
        return false;
    }
    // Signed distances of each endpoint from the other segment's line.
    let o1 = cross(&(b - a), &(c - a)) / lab;
    let o2 = cross(&(b - a), &(d - a)) / lab;
    let o3 = cross(&(d - c), &(a - c)) / lcd;
    let o4 = cross(&(d - c), &(b - c)) / lcd;
    ((o1 > tol && o2 < -tol) || (o1 < -tol && o2 > tol))
        && ((o3 > tol && o4 < -tol) || (o3 < -tol && o4 > tol))
}

/// Distance from point `p` to the closed segment `ab`.
pub fn point_segment_distance(p: &Vec2, a: &Vec2, b: &Vec2) -> Real {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 == 0.0 {
        return (p - a).norm();
    }
    let t = ((p - a).dot(&ab) / len2).clamp(0.0, 1.0);
    (p - (a + ab * t)).norm()
}

/// Distance between the closed segments `ab` and `cd` (zero when they intersect).
pub fn segment_distance(a: &Vec2, b: &Vec2, c: &Vec2, d: &Vec2) -> Real {
    if segments_properly_cross(a, b, c, d, 0.0) {
        return 0.0;
    }
    point_segment_distance(a, c, d)
        .min(point_segment_distance(b, c, d))
        .min(point_segment_distance(c, a, b))
        .min(point_segment_distance(d, a, b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn crossing_and_touching() {
        let (a, b) = (vec2(0.0, 0.0), vec2(2.0, 2.0));
        assert!(segments_properly_cross(
            &a,
            &b,
            &vec2(0.0, 2.0),
            &vec2(2.0, 0.0),
            1e-9
        ));
        // Touching at an endpoint is not a proper crossing.
        assert!(!segments_properly_cross(
            &a,
            &b,
            &vec2(1.0, 1.0),
            &vec2(2.0, 0.0),
            1e-9
        ));
        // Collinear overlap is not a proper crossing either.
        assert!(!segments_properly_cross(
            &a,
            &b,
            &vec2(1.0, 1.0),
            &vec2(3.0, 3.0),
            1e-9
        ));
        assert_eq!(
            segment_distance(&a, &b, &vec2(0.0, 2.0), &vec2(2.0, 0.0)),
            0.0
        );
        let d = segment_distance(&a, &vec2(1.0, 0.0), &vec2(0.0, 1.0), &vec2(1.0, 1.0));
        assert!((d - 1.0).abs() < 1e-15);
    }
}

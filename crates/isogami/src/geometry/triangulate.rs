//! Ear-clipping triangulation of a simple polygon: a fixed set of triangles whose orientation
//! tells whether a moved copy of the polygon is still the same shape turned the same way.

use super::polygon::signed_area;
use super::segment::point_segment_distance;
use crate::math::{cross, Real, Vec2};

/// Triangles (index triples into `poly`, counter-clockwise) covering the simple polygon
/// `poly` (either orientation), by ear clipping: every corner clipped is convex and no
/// other corner lies in or on its triangle. `None` when no ear is found (the polygon is not
/// simple).
pub fn triangulate(poly: &[Vec2]) -> Option<Vec<[usize; 3]>> {
    let n = poly.len();
    if n < 3 {
        return None;
    }
    let mut left: Vec<usize> = (0..n).collect();
    if signed_area(poly) < 0.0 {
        left.reverse();
    }
    let scale = poly
        .iter()
        .map(|p| p.norm())
        .fold(0.0, Real::max)
        .max(1e-300);
    let tol = 1e-12 * scale;
    let mut out = Vec::with_capacity(n - 2);
    while left.len() > 3 {
        let m = left.len();
        let ear = (0..m).find(|&k| {
            let (a, b, c) = (left[(k + m - 1) % m], left[k], left[(k + 1) % m]);
            let (pa, pb, pc) = (poly[a], poly[b], poly[c]);
            if cross(&(pb - pa), &(pc - pb)) <= tol * scale {
                return false;
            }
            left.iter().all(|&o| {
                o == a || o == b || o == c || !in_or_on_triangle(poly[o], pa, pb, pc, tol)
            })
        })?;
        let (a, b, c) = (left[(ear + m - 1) % m], left[ear], left[(ear + 1) % m]);
        out.push([a, b, c]);
        left.remove(ear);
    }
    out.push([left[0], left[1], left[2]]);
    Some(out)
}

/// True when `p` lies inside the counter-clockwise triangle `abc` or within `tol` of it.
fn in_or_on_triangle(p: Vec2, a: Vec2, b: Vec2, c: Vec2, tol: Real) -> bool {
    let inside = cross(&(b - a), &(p - a)) >= 0.0
        && cross(&(c - b), &(p - b)) >= 0.0
        && cross(&(a - c), &(p - c)) >= 0.0;
    inside
        || point_segment_distance(&p, &a, &b) <= tol
        || point_segment_distance(&p, &b, &c) <= tol
        || point_segment_distance(&p, &c, &a) <= tol
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::TestRng;

    fn area_of(poly: &[Vec2], tris: &[[usize; 3]]) -> Real {
        tris.iter()
            .map(|t| signed_area(&[poly[t[0]], poly[t[1]], poly[t[2]]]))
            .sum()
    }

    /// Random star-shaped polygons (concave ones among them), both orientations: n − 2
    /// triangles, each counter-clockwise with positive area, summing to the polygon's area.
    #[test]
    fn ear_clipping_covers_random_star_shaped_polygons() {
        let mut rng = TestRng::new(41);
        for case in 0..300 {
            let n = 3 + case % 12;
            // A corner in each of n equal sectors about the origin: star-shaped about it.
            let mut poly: Vec<Vec2> = (0..n)
                .map(|k| {
                    let a = (k as Real + 0.8 * rng.unit()) / n as Real * std::f64::consts::TAU;
                    Vec2::new(a.cos(), a.sin()) * (0.2 + rng.unit())
                })
                .collect();
            if case % 2 == 1 {
                poly.reverse();
            }
            let tris = triangulate(&poly).expect("a simple polygon has ears");
            assert_eq!(tris.len(), poly.len() - 2, "case {case}");
            for t in &tris {
                assert!(
                    signed_area(&[poly[t[0]], poly[t[1]], poly[t[2]]]) > 0.0,
                    "case {case}"
                );
            }
            let want = signed_area(&poly).abs();
            assert!(
                (area_of(&poly, &tris) - want).abs() < 1e-9 * want.max(1.0),
                "case {case}"
            );
        }
    }

    /// An L (one reflex corner): its reflex corner is never the tip of an ear.
    #[test]
    fn a_reflex_corner_is_never_clipped_as_an_ear() {
        let l: Vec<Vec2> = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
            .iter()
            .map(|&(x, y)| Vec2::new(x, y))
            .collect();
        let tris = triangulate(&l).unwrap();
        assert_eq!(tris.len(), 4);
        assert!(tris.iter().all(|t| t[1] != 3));
        assert!((area_of(&l, &tris) - 3.0).abs() < 1e-12);
    }
}

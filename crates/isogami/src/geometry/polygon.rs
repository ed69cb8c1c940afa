//! Polygon predicates. Polygons are vertex lists without a repeated closing vertex.

use super::segment::{point_segment_distance, segment_distance, segments_properly_cross};
use crate::math::{cross, perp, Real, Vec2};

/// Shoelace signed area: positive for counter-clockwise polygons.
pub fn signed_area(poly: &[Vec2]) -> Real {
    let n = poly.len();
    (0..n)
        .map(|i| cross(&poly[i], &poly[(i + 1) % n]))
        .sum::<Real>()
        * 0.5
}

/// Convex hull of `points`, counter-clockwise, without collinear points (Andrew's monotone
/// chain). Fewer than three distinct points come back as they are, sorted.
pub fn convex_hull(points: &[Vec2]) -> Vec<Vec2> {
    let mut p: Vec<Vec2> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let turn = |o: &Vec2, a: &Vec2, b: &Vec2| cross(&(a - o), &(b - o));
    let mut hull: Vec<Vec2> = Vec::with_capacity(2 * p.len());
    for pass in [p.clone(), p.iter().rev().copied().collect()] {
        let start = hull.len();
        for v in pass {
            while hull.len() >= start + 2
                && turn(&hull[hull.len() - 2], &hull[hull.len() - 1], &v) <= 0.0
            {
                hull.pop();
            }
            hull.push(v);
        }
        hull.pop();
    }
    hull
}

/// Area centroid of a polygon with non-zero area.
pub fn centroid(poly: &[Vec2]) -> Vec2 {
    let n = poly.len();
    // Shift to the first vertex for accuracy far from the origin.
    let o = poly[0];
    let mut c = Vec2::zeros();
    let mut a2 = 0.0;
    for i in 0..n {
        let p = poly[i] - o;
        let q = poly[(i + 1) % n] - o;
        let w = cross(&p, &q);
        a2 += w;
        c += (p + q) * w;
    }
    o + c / (3.0 * a2)
}

/// Why a vertex loop is not a simple polygon.
#[derive(Debug, Clone, PartialEq)]
pub enum SimplicityProblem {
    /// Fewer than three vertices.
    TooFewVertices,
    /// Edge `edge` is shorter than the tolerance.
    DegenerateEdge {
        /// Edge index (from vertex `edge` to `edge + 1`).
        edge: usize,
    },
    /// The enclosed area is (near) zero.
    ZeroArea,
    /// Two edges touch or cross away from a shared vertex.
    SelfIntersection {
        /// First edge index.
        a: usize,
        /// Second edge index.
        b: usize,
    },
}

impl std::fmt::Display for SimplicityProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::TooFewVertices => write!(f, "polygon with fewer than three vertices"),
            Self::DegenerateEdge { edge } => {
                write!(f, "degenerate tile (edge {edge} has zero length)")
            }
            Self::ZeroArea => write!(f, "degenerate tile (zero area)"),
            Self::SelfIntersection { a, b } => {
                write!(f, "self-intersecting tile (edges {a} and {b} meet)")
            }
        }
    }
}

/// `None` when `poly` is a simple polygon at tolerance `tol` (an absolute length): every edge
/// longer than `tol`, non-adjacent edges farther apart than `tol`, adjacent edges not folded
/// back onto each other, and area above `tol²`. Collinear consecutive edges are allowed.
pub fn is_simple_problem(poly: &[Vec2], tol: Real) -> Option<SimplicityProblem> {
    let n = poly.len();
    if n < 3 {
        return Some(SimplicityProblem::TooFewVertices);
    }
    for i in 0..n {
        if (poly[(i + 1) % n] - poly[i]).norm() <= tol {
            return Some(SimplicityProblem::DegenerateEdge { edge: i });
        }
    }
    for i in 0..n {
        let (a, b) = (&poly[i], &poly[(i + 1) % n]);
        for j in i + 1..n {
            let (c, d) = (&poly[j], &poly[(j + 1) % n]);
            let adjacent_after = j == i + 1;
            let adjacent_before = i == 0 && j == n - 1;
            let bad = if adjacent_after {
                // Shared vertex b == c: the far ends must not lie on the other edge.
                point_segment_distance(d, a, b) <= tol || point_segment_distance(a, c, d) <= tol
            } else if adjacent_before {
                // Shared vertex a == d.
                point_segment_distance(c, a, b) <= tol || point_segment_distance(b, c, d) <= tol
            } else {
                segment_distance(a, b, c, d) <= tol
            };
            if bad {
                return Some(SimplicityProblem::SelfIntersection { a: i, b: j });
            }
        }
    }
    if signed_area(poly).abs() <= tol * tol {
        return Some(SimplicityProblem::ZeroArea);
    }
    None
}

/// True when `p` lies inside `poly` and farther than `tol` from its boundary.
pub fn point_in_polygon_strict(p: &Vec2, poly: &[Vec2], tol: Real) -> bool {
    let n = poly.len();
    let mut winding = 0i32;
    for i in 0..n {
        let (a, b) = (&poly[i], &poly[(i + 1) % n]);
        if point_segment_distance(p, a, b) <= tol {
            return false;
        }
        if a.y <= p.y {
            if b.y > p.y && cross(&(b - a), &(p - a)) > 0.0 {
                winding += 1;
            }
        } else if b.y <= p.y && cross(&(b - a), &(p - a)) < 0.0 {
            winding -= 1;
        }
    }
    winding != 0
}

fn bounding_boxes_apart(p: &[Vec2], q: &[Vec2], tol: Real) -> bool {
    let bb = |s: &[Vec2]| {
        s.iter().fold(
            (
                Real::INFINITY,
                Real::INFINITY,
                Real::NEG_INFINITY,
                Real::NEG_INFINITY,
            ),
            |(x0, y0, x1, y1), v| (x0.min(v.x), y0.min(v.y), x1.max(v.x), y1.max(v.y)),
        )
    };
    let (a, b) = (bb(p), bb(q));
    a.2 < b.0 - tol || b.2 < a.0 - tol || a.3 < b.1 - tol || b.3 < a.1 - tol
}

/// Points just inside `poly` next to each edge midpoint (for counter-clockwise polygons).
fn inner_edge_points(poly: &[Vec2], nudge: Real) -> impl Iterator<Item = Vec2> + '_ {
    let n = poly.len();
    let orient = signed_area(poly).signum();
    (0..n).filter_map(move |i| {
        let e = poly[(i + 1) % n] - poly[i];
        let len = e.norm();
        (len > 0.0).then(|| (poly[i] + poly[(i + 1) % n]) * 0.5 + perp(&e) * (orient * nudge / len))
    })
}

/// True when the interiors of two simple polygons overlap by more than `tol` (an absolute
/// length). Polygons that only share boundary (edges or vertices) do not overlap.
///
/// Decided by three exact tests, any of which proves overlap: two edges cross properly; a
/// vertex of one lies strictly inside the other; a point just inside one polygon next to an
/// edge midpoint lies strictly inside the other (this catches coincident polygons and
/// polygons touching the other's boundary only at vertices). The nudge is `2·tol`, so `tol`
/// must be small against the polygons' feature size.
pub fn interiors_overlap(p: &[Vec2], q: &[Vec2], tol: Real) -> bool {
    if bounding_boxes_apart(p, q, tol) {
        return false;
    }
    let (np, nq) = (p.len(), q.len());
    for i in 0..np {
        for j in 0..nq {
            if segments_properly_cross(&p[i], &p[(i + 1) % np], &q[j], &q[(j + 1) % nq], tol) {
                return true;
            }
        }
    }
    if p.iter().any(|v| point_in_polygon_strict(v, q, tol))
        || q.iter().any(|v| point_in_polygon_strict(v, p, tol))
    {
        return true;
    }
    let nudge = 2.0 * tol.max(Real::EPSILON);
    inner_edge_points(p, nudge).any(|v| point_in_polygon_strict(&v, q, tol * 0.5))
        || inner_edge_points(q, nudge).any(|v| point_in_polygon_strict(&v, p, tol * 0.5))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_a_square_and_its_inner_points() {
        let pts: Vec<Vec2> = [
            (0.0, 0.0),
            (1.0, 0.0),
            (0.5, 0.5),
            (1.0, 1.0),
            (0.0, 1.0),
            (0.5, 0.0),
        ]
        .iter()
        .map(|&(x, y)| Vec2::new(x, y))
        .collect();
        let h = convex_hull(&pts);
        assert_eq!(h.len(), 4, "{h:?}");
        assert!((signed_area(&h) - 1.0).abs() < 1e-15);
    }
    use crate::math::vec2;

    fn square(x: Real, y: Real, s: Real) -> Vec<Vec2> {
        vec![
            vec2(x, y),
            vec2(x + s, y),
            vec2(x + s, y + s),
            vec2(x, y + s),
        ]
    }

    #[test]
    fn area_and_centroid() {
        let sq = square(1.0, 2.0, 2.0);
        assert_eq!(signed_area(&sq), 4.0);
        assert!((centroid(&sq) - vec2(2.0, 3.0)).norm() < 1e-15);
        let rev: Vec<_> = sq.iter().rev().copied().collect();
        assert_eq!(signed_area(&rev), -4.0);
    }

    #[test]
    fn simplicity() {
        assert_eq!(is_simple_problem(&square(0.0, 0.0, 1.0), 1e-9), None);
        let bowtie = vec![
            vec2(0.0, 0.0),
            vec2(1.0, 1.0),
            vec2(1.0, 0.0),
            vec2(0.0, 1.0),
        ];
        assert!(matches!(
            is_simple_problem(&bowtie, 1e-9),
            Some(SimplicityProblem::SelfIntersection { .. })
        ));
        let degenerate = vec![
            vec2(0.0, 0.0),
            vec2(0.0, 0.0),
            vec2(1.0, 0.0),
            vec2(0.0, 1.0),
        ];
        assert_eq!(
            is_simple_problem(&degenerate, 1e-9),
            Some(SimplicityProblem::DegenerateEdge { edge: 0 })
        );
        // A collinear vertex is fine; a fold-back spike is not.
        let collinear = vec![
            vec2(0.0, 0.0),
            vec2(0.5, 0.0),
            vec2(1.0, 0.0),
            vec2(0.0, 1.0),
        ];
        assert_eq!(is_simple_problem(&collinear, 1e-9), None);
        let spike = vec![
            vec2(0.0, 0.0),
            vec2(1.0, 0.0),
            vec2(0.5, 0.0),
            vec2(0.0, 1.0),
        ];
        assert!(is_simple_problem(&spike, 1e-9).is_some());
    }

    #[test]
    fn overlap_cases() {
        let a = square(0.0, 0.0, 1.0);
        // Sharing an edge or a corner is not overlap.
        assert!(!interiors_overlap(&a, &square(1.0, 0.0, 1.0), 1e-9));
        assert!(!interiors_overlap(&a, &square(1.0, 1.0, 1.0), 1e-9));
        // Coincident, contained, partially overlapping, crossing.
        assert!(interiors_overlap(&a, &a, 1e-9));
        assert!(interiors_overlap(&a, &square(0.25, 0.25, 0.5), 1e-9));
        assert!(interiors_overlap(&a, &square(0.5, 0.5, 1.0), 1e-9));
        let diamond = vec![
            vec2(0.5, -0.2),
            vec2(1.2, 0.5),
            vec2(0.5, 1.2),
            vec2(-0.2, 0.5),
        ];
        assert!(interiors_overlap(&a, &diamond, 1e-9));
        // Inscribed diamond touching only at the square's edge midpoints.
        let inscribed = vec![
            vec2(0.5, 0.0),
            vec2(1.0, 0.5),
            vec2(0.5, 1.0),
            vec2(0.0, 0.5),
        ];
        assert!(interiors_overlap(&a, &inscribed, 1e-9));
        // Separated by a gap.
        assert!(!interiors_overlap(&a, &square(1.01, 0.0, 1.0), 1e-9));
    }

    #[test]
    fn strict_containment() {
        let a = square(0.0, 0.0, 1.0);
        assert!(point_in_polygon_strict(&vec2(0.5, 0.5), &a, 1e-9));
        assert!(!point_in_polygon_strict(&vec2(1.0, 0.5), &a, 1e-9));
        assert!(!point_in_polygon_strict(&vec2(1.5, 0.5), &a, 1e-9));
    }
}

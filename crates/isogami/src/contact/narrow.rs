//! Narrow phase of one pair of placed collision polygons: vertex–edge distances in both
//! directions, and the exact overlap test.

use super::distance::point_edge_distance_squared;
use crate::geometry::interiors_overlap;
use crate::math::{Real, Vec2};

/// Overlap deeper than this (units of L) counts as overlap in the exact test.
pub(crate) const OVERLAP_TOL: Real = 1e-12;

/// One vertex–edge combination: vertex `vertex` of side `vertex_side` (0 = A, 1 = B) against
/// edge `edge` (vertex `edge` → `edge + 1`) of the other side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct VertexEdge {
    pub(crate) vertex_side: usize,
    pub(crate) vertex: usize,
    pub(crate) edge: usize,
    pub(crate) d: Real,
}

/// Calls `f` for every vertex–edge combination of polygons `a` and `b` (world coordinates)
/// closer than `limit`, vertices of `a` against edges of `b` first.
pub(crate) fn for_each_close(a: &[Vec2], b: &[Vec2], limit: Real, mut f: impl FnMut(VertexEdge)) {
    // Squares first: d = √d² < limit implies d² < limit²·(1 + 4ε) whatever the rounding, so
    // this test drops only combinations the exact test below would drop too (for a tiny
    // limit, whose square may underflow, it drops only d² = ∞, which the exact test drops
    // as well).
    let limit2 = if limit > 1e-100 {
        limit * limit * (1.0 + 4.0 * Real::EPSILON)
    } else {
        Real::INFINITY
    };
    for (vertex_side, (vs, es)) in [(a, b), (b, a)].into_iter().enumerate() {
        for (vertex, p) in vs.iter().enumerate() {
            for_each_edge(es, |edge, e0, e1| {
                let d2 = point_edge_distance_squared(p, e0, e1);
                if d2 >= limit2 {
                    return;
                }
                let d = d2.sqrt();
                if d < limit {
                    f(VertexEdge {
                        vertex_side,
                        vertex,
                        edge,
                        d,
                    });
                }
            });
        }
    }
}

/// Calls `f(k, v_k, v_k+1)` for every edge of a closed polygon, in order (the last edge
/// closes it), without an index modulo per edge.
#[inline]
fn for_each_edge(poly: &[Vec2], mut f: impl FnMut(usize, &Vec2, &Vec2)) {
    let (Some(first), Some(last)) = (poly.first(), poly.last()) else {
        return;
    };
    for (k, pair) in poly.windows(2).enumerate() {
        f(k, &pair[0], &pair[1]);
    }
    f(poly.len() - 1, last, first);
}

/// Smallest vertex–edge distance between `a` and `b` in both directions.
pub(crate) fn min_vertex_edge_distance(a: &[Vec2], b: &[Vec2]) -> Real {
    // The square root of the smallest square is the smallest distance, bit for bit (the
    // root is monotone and exactly what a distance takes).
    let mut best = Real::INFINITY;
    for (vs, es) in [(a, b), (b, a)] {
        for p in vs {
            for_each_edge(es, |_, e0, e1| {
                best = best.min(point_edge_distance_squared(p, e0, e1));
            });
        }
    }
    best.sqrt()
}

/// Distance between the polygons as sets: 0 when they overlap, else the smallest
/// vertex–edge distance.
pub(crate) fn polygon_distance(a: &[Vec2], b: &[Vec2]) -> Real {
    if interiors_overlap(a, b, OVERLAP_TOL) {
        return 0.0;
    }
    min_vertex_edge_distance(a, b)
}

/// Fills `out` with `poly` moved by `shift`.
pub(crate) fn shifted_into(poly: &[Vec2], shift: Vec2, out: &mut Vec<Vec2>) {
    out.clear();
    out.extend(poly.iter().map(|v| v + shift));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn distances_both_ways() {
        let a = [
            vec2(0.0, 0.0),
            vec2(1.0, 0.0),
            vec2(1.0, 1.0),
            vec2(0.0, 1.0),
        ];
        // A triangle whose tip points at the square's right edge: the closest feature is a
        // vertex of b against an edge of a.
        let b = [vec2(1.1, 0.5), vec2(2.0, 0.0), vec2(2.0, 1.0)];
        assert!((min_vertex_edge_distance(&a, &b) - 0.1).abs() < 1e-15);
        assert!((polygon_distance(&a, &b) - 0.1).abs() < 1e-15);
        let mut hits = Vec::new();
        for_each_close(&a, &b, 0.2, |c| hits.push(c));
        assert_eq!(hits.len(), 1);
        assert_eq!(
            (hits[0].vertex_side, hits[0].vertex, hits[0].edge),
            (1, 0, 1)
        );
        // Crossing polygons are at distance 0 even though no vertex is near an edge.
        let bar = [
            vec2(0.4, -1.0),
            vec2(0.6, -1.0),
            vec2(0.6, 2.0),
            vec2(0.4, 2.0),
        ];
        let wide = [
            vec2(-1.0, 0.4),
            vec2(2.0, 0.4),
            vec2(2.0, 0.6),
            vec2(-1.0, 0.6),
        ];
        assert!(min_vertex_edge_distance(&bar, &wide) > 0.3);
        assert_eq!(polygon_distance(&bar, &wide), 0.0);
    }
}

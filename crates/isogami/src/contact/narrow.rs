//! Narrow phase of one pair of placed collision polygons: vertex–edge distances in both
//! directions, and the exact overlap test.

use super::distance::point_edge_distance;
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
    for (vertex_side, (vs, es)) in [(a, b), (b, a)].into_iter().enumerate() {
        let n = es.len();
        for (vertex, p) in vs.iter().enumerate() {
            for edge in 0..n {
                let d = point_edge_distance(p, &es[edge], &es[(edge + 1) % n]);
                if d < limit {
                    f(VertexEdge {
                        vertex_side,
                        vertex,
                        edge,
                        d,
                    });
                }
            }
        }
    }
}

/// Smallest vertex–edge distance between `a` and `b` in both directions.
pub(crate) fn min_vertex_edge_distance(a: &[Vec2], b: &[Vec2]) -> Real {
    let mut best = Real::INFINITY;
    for_each_close(a, b, Real::INFINITY, |c| best = best.min(c.d));
    best
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

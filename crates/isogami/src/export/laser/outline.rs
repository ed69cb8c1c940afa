//! The outline of a patch: its boundary loops (each with the material on its left) and the
//! outline cut, every boundary edge moved by half the kerf into the waste (to its right)
//! with mitred corners, so that the burn's inner edge lies on the design outline.

use super::graph::PatchGraph;
use crate::math::{cross, Real, Vec2};

/// One boundary loop: vertex ids in order (material on the left) and the kerf-compensated
/// cut path, vertex for vertex.
#[derive(Debug, Clone)]
pub(super) struct Loop {
    /// Vertex ids of the design outline.
    pub vertices: Vec<usize>,
    /// The outline cut: `vertices[k]` moved into the waste (mitre point of the offset lines).
    pub cut: Vec<Vec2>,
}

/// The boundary loops of `graph` and their cut paths offset by `half_kerf`.
pub(super) fn outline_loops(graph: &PatchGraph, half_kerf: Real) -> Vec<Loop> {
    // Boundary edges are oriented with their only tile on the left: follow them head to tail.
    let boundary: Vec<usize> = (0..graph.edges.len())
        .filter(|&e| graph.edges[e].right.is_none())
        .collect();
    let mut out_of: Vec<Vec<usize>> = vec![Vec::new(); graph.points.len()];
    for &e in &boundary {
        out_of[graph.edges[e].v[0]].push(e);
    }
    let mut used = vec![false; graph.edges.len()];
    let mut loops = Vec::new();
    for &start in &boundary {
        if used[start] {
            continue;
        }
        let mut vertices = Vec::new();
        let mut e = start;
        while !used[e] {
            used[e] = true;
            let [a, b] = graph.edges[e].v;
            vertices.push(a);
            let back = graph.point(a) - graph.point(b);
            // At a vertex where the boundary pinches, take the first outgoing edge clockwise
            // from the way back: the loop then keeps hugging the same piece of material.
            let next = out_of[b]
                .iter()
                .copied()
                .filter(|&f| !used[f] || f == start)
                .min_by(|&f, &g| {
                    let cw = |f: usize| {
                        let d = graph.point(graph.edges[f].v[1]) - graph.point(b);
                        clockwise_angle(&back, &d)
                    };
                    cw(f).total_cmp(&cw(g))
                });
            match next {
                Some(f) => e = f,
                None => break,
            }
        }
        let pts: Vec<Vec2> = vertices.iter().map(|&v| graph.point(v)).collect();
        let cut = offset_right(&pts, half_kerf);
        loops.push(Loop { vertices, cut });
    }
    loops
}

/// Angle in (0, 2π] turned clockwise from `from` to `to`.
fn clockwise_angle(from: &Vec2, to: &Vec2) -> Real {
    let a = cross(to, from).atan2(from.dot(to));
    if a <= 0.0 {
        a + std::f64::consts::TAU
    } else {
        a
    }
}

/// The closed polyline `pts` with every edge moved by `h` to its right, consecutive offset
/// lines meeting at their intersection (mitre); where two edges are parallel the offset
/// vertex is moved along the common normal.
pub(super) fn offset_right(pts: &[Vec2], h: Real) -> Vec<Vec2> {
    let n = pts.len();
    let right = |k: usize| {
        let d = (pts[(k + 1) % n] - pts[k]).normalize();
        (d, Vec2::new(d.y, -d.x))
    };
    (0..n)
        .map(|k| {
            let (d0, n0) = right((k + n - 1) % n);
            let (d1, n1) = right(k);
            let s = cross(&d0, &d1);
            if s.abs() < 1e-9 {
                return pts[k] + n0 * h;
            }
            // Point on both lines: pts[k] + h n0 + a d0 = pts[k] + h n1 + b d1.
            let a = cross(&(n1 - n0), &d1) * h / s;
            pts[k] + n0 * h + d0 * a
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::signed_area;

    #[test]
    fn a_square_grows_by_half_the_kerf_on_every_side() {
        let sq = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 2.0),
            Vec2::new(0.0, 2.0),
        ];
        let out = offset_right(&sq, 0.1);
        assert!((out[0] - Vec2::new(-0.1, -0.1)).norm() < 1e-12);
        assert!((out[2] - Vec2::new(2.1, 2.1)).norm() < 1e-12);
        assert!((signed_area(&out) - 2.2 * 2.2).abs() < 1e-12);
    }

    #[test]
    fn a_reflex_corner_moves_along_its_bisector() {
        // An L shape: the corner at (1, 1) is reflex for the material.
        let l = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 2.0),
            Vec2::new(0.0, 2.0),
        ];
        let out = offset_right(&l, 0.1);
        assert!((out[3] - Vec2::new(1.1, 1.1)).norm() < 1e-12);
        // A straight run keeps its vertex on the normal.
        let line = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 1.0),
        ];
        assert!((offset_right(&line, 0.1)[1] - Vec2::new(1.0, -0.1)).norm() < 1e-12);
    }
}

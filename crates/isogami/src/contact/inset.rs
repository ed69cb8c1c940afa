//! Insetting a tile polygon by half the kerf: every edge line moves inward by `h` and
//! consecutive offset lines are intersected (mitred corners).

use crate::geometry::{is_simple_problem, signed_area, SimplicityProblem};
use crate::math::{perp, Real, Vec2};

/// Smallest accepted `1 + cos(turn)` at a vertex: below it the polygon folds back on itself
/// there (a spike) and the mitre point runs off to infinity.
const SPIKE_TOL: Real = 1e-9;

/// Why a polygon cannot be inset.
#[derive(Debug, Clone, PartialEq)]
pub enum InsetProblem {
    /// The input has fewer than three vertices.
    TooFewVertices(usize),
    /// The input has a NaN or infinite coordinate at this vertex.
    NonFiniteVertex(usize),
    /// The input is not counter-clockwise.
    Clockwise,
    /// Edge `k` of the input has zero length.
    ZeroEdge(usize),
    /// The polygon folds back by 180° at this vertex.
    Spike(usize),
    /// Inset edge `edge` runs backwards: the inset is wider than that edge allows.
    EdgeVanishes(usize),
    /// The inset polygon is not simple.
    NotSimple(SimplicityProblem),
    /// The inset polygon runs clockwise.
    Inverted,
}

impl std::fmt::Display for InsetProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::TooFewVertices(n) => {
                write!(
                    f,
                    "the tile itself is unusable ({n} vertices, fewer than three)"
                )
            }
            Self::NonFiniteVertex(v) => {
                write!(f, "the tile itself is unusable (vertex {v} is not finite)")
            }
            Self::Clockwise => f.write_str("the tile itself is unusable (not counter-clockwise)"),
            Self::ZeroEdge(e) => {
                write!(f, "the tile itself is unusable (edge {e} has zero length)")
            }
            Self::Spike(v) => write!(f, "the tile folds back at vertex {v}"),
            Self::EdgeVanishes(e) => write!(f, "edge {e} vanishes (it is too short)"),
            Self::NotSimple(p) => write!(f, "the inset polygon is not simple: {p}"),
            Self::Inverted => f.write_str("the inset polygon is inverted"),
        }
    }
}

impl std::error::Error for InsetProblem {}

/// The inward unit normal of every edge k (vertex k → k+1) of `poly`, the left side of a
/// counter-clockwise traversal, after checking that `poly` has at least three finite
/// vertices, is counter-clockwise and has no zero-length edge.
pub(crate) fn inward_normals(poly: &[Vec2]) -> Result<Vec<Vec2>, InsetProblem> {
    let n = poly.len();
    if n < 3 {
        return Err(InsetProblem::TooFewVertices(n));
    }
    if let Some(v) = poly
        .iter()
        .position(|v| !(v.x.is_finite() && v.y.is_finite()))
    {
        return Err(InsetProblem::NonFiniteVertex(v));
    }
    if signed_area(poly) <= 0.0 {
        return Err(InsetProblem::Clockwise);
    }
    let mut normals = Vec::with_capacity(n);
    for k in 0..n {
        let e = poly[(k + 1) % n] - poly[k];
        let len = e.norm();
        if len.is_nan() || len <= 0.0 {
            return Err(InsetProblem::ZeroEdge(k));
        }
        normals.push(perp(&e) / len);
    }
    Ok(normals)
}

/// The polygon `poly` (counter-clockwise, possibly non-convex, collinear consecutive edges
/// allowed) with every edge moved inward by `h > 0`. Vertex k of the result belongs to
/// vertex k of the input. Fails when the result is not a simple counter-clockwise polygon
/// whose edges keep their directions.
pub fn inset_polygon(poly: &[Vec2], h: Real) -> Result<Vec<Vec2>, InsetProblem> {
    let n = poly.len();
    let normals = inward_normals(poly)?;
    // The point at distance h inside both lines through vertex k: v + h·m with m·n₁ = m·n₂ = 1,
    // m = (n₁ + n₂) / (1 + n₁·n₂). Collinear edges give m = n with no special case.
    let mut out = Vec::with_capacity(n);
    for k in 0..n {
        let (n1, n2) = (normals[(k + n - 1) % n], normals[k]);
        let denom = 1.0 + n1.dot(&n2);
        if denom <= SPIKE_TOL {
            return Err(InsetProblem::Spike(k));
        }
        out.push(poly[k] + (n1 + n2) * (h / denom));
    }
    for k in 0..n {
        let (e, f) = (poly[(k + 1) % n] - poly[k], out[(k + 1) % n] - out[k]);
        if e.dot(&f) <= 0.0 {
            return Err(InsetProblem::EdgeVanishes(k));
        }
    }
    let tol = 1e-12 * (1.0 + h);
    if let Some(p) = is_simple_problem(&out, tol) {
        return Err(InsetProblem::NotSimple(p));
    }
    if signed_area(&out) <= 0.0 {
        return Err(InsetProblem::Inverted);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::point_segment_distance;
    use crate::math::vec2;

    fn close(a: Vec2, b: Vec2) -> bool {
        (a - b).norm() < 1e-14
    }

    #[test]
    fn square_with_collinear_vertex() {
        let sq = [
            vec2(0.0, 0.0),
            vec2(0.5, 0.0),
            vec2(1.0, 0.0),
            vec2(1.0, 1.0),
            vec2(0.0, 1.0),
        ];
        let r = inset_polygon(&sq, 0.1).unwrap();
        assert!(close(r[0], vec2(0.1, 0.1)));
        assert!(close(r[1], vec2(0.5, 0.1)));
        assert!(close(r[2], vec2(0.9, 0.1)));
        assert!(close(r[3], vec2(0.9, 0.9)));
        assert!(close(r[4], vec2(0.1, 0.9)));
    }

    #[test]
    fn non_convex_l_shape_keeps_distance_to_every_edge_line() {
        let l = [
            vec2(0.0, 0.0),
            vec2(2.0, 0.0),
            vec2(2.0, 1.0),
            vec2(1.0, 1.0),
            vec2(1.0, 2.0),
            vec2(0.0, 2.0),
        ];
        let h = 0.05;
        let r = inset_polygon(&l, h).unwrap();
        // The reflex vertex (1,1) moves diagonally into the tile, h/sin(135°) from the corner.
        assert!(close(r[3], vec2(0.95, 0.95)));
        // Every inset edge is parallel to its original at distance h.
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            let n = perp(&(b - a)).normalize();
            for p in [r[k], r[(k + 1) % l.len()]] {
                assert!(((p - a).dot(&n) - h).abs() < 1e-14);
            }
        }
        // Inset vertices stay at least h from the whole original boundary.
        for p in &r {
            for k in 0..l.len() {
                assert!(point_segment_distance(p, &l[k], &l[(k + 1) % l.len()]) >= h - 1e-14);
            }
        }
    }

    #[test]
    fn failures_name_the_problem() {
        let thin = [
            vec2(0.0, 0.0),
            vec2(1.0, 0.0),
            vec2(1.0, 0.05),
            vec2(0.0, 0.05),
        ];
        assert!(inset_polygon(&thin, 0.1).is_err());
        let cw = [vec2(0.0, 0.0), vec2(0.0, 1.0), vec2(1.0, 0.0)];
        assert_eq!(inset_polygon(&cw, 0.01), Err(InsetProblem::Clockwise));
        let spike = [
            vec2(0.0, 0.0),
            vec2(1.0, 0.0),
            vec2(0.5, 0.0),
            vec2(0.0, 1.0),
        ];
        assert!(inset_polygon(&spike, 0.01).is_err());
        // A short edge between two sharp corners vanishes.
        let short = [
            vec2(0.0, 0.0),
            vec2(1.0, 0.0),
            vec2(1.0, 0.02),
            vec2(0.0, 1.0),
        ];
        assert!(inset_polygon(&short, 0.05).is_err());
    }
}

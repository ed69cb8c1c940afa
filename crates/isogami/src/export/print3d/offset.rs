//! Insetting a tile polygon edge by edge: each edge line moves inward by its own distance
//! (the print gap on edges shared with a neighbour, nothing on the patch outline) and
//! consecutive offset lines are intersected (mitred corners). Where two nearly collinear
//! edges move by different distances the polygon takes a small square step instead of a
//! far-away mitre point.

use crate::contact::inset::inward_normals;
use crate::contact::InsetProblem;
use crate::geometry::{is_simple_problem, signed_area};
use crate::math::{cross, perp, Real, Vec2};

/// Smallest accepted `1 + cos(turn)` at a vertex (a fold-back spike below it).
const SPIKE_TOL: Real = 1e-9;

/// Below this |sin| between two edges moved by different distances, the corner is a step.
const STEP_SIN: Real = 1e-3;

/// `poly` (counter-clockwise, possibly non-convex) with edge k (vertex k → k+1) moved inward
/// by `d[k] ≥ 0`. Fails when the result is not a simple counter-clockwise polygon whose
/// moved edges keep their direction.
pub fn inset_edges(poly: &[Vec2], d: &[Real]) -> Result<Vec<Vec2>, InsetProblem> {
    let n = poly.len();
    let normals = inward_normals(poly)?;
    // Per output vertex: the input edges of the segments before and after it (`None` for
    // the short segment of a step).
    let mut out: Vec<(Vec2, Option<usize>, Option<usize>)> = Vec::with_capacity(n + 2);
    for k in 0..n {
        let prev = (k + n - 1) % n;
        let (n1, n2) = (normals[prev], normals[k]);
        let (d1, d2) = (d[prev], d[k]);
        let dot = n1.dot(&n2);
        if 1.0 + dot <= SPIKE_TOL {
            return Err(InsetProblem::Spike(k));
        }
        let sin = cross(&n1, &n2);
        if d1 == d2 {
            out.push((
                poly[k] + (n1 + n2) * (d1 / (1.0 + dot)),
                Some(prev),
                Some(k),
            ));
        } else if sin.abs() < STEP_SIN && dot > 0.0 {
            out.push((poly[k] + n1 * d1, Some(prev), None));
            out.push((poly[k] + n2 * d2, None, Some(k)));
        } else {
            // x with n1·x = d1 and n2·x = d2.
            let x = (perp(&n2) * d1 - perp(&n1) * d2) / -sin;
            out.push((poly[k] + x, Some(prev), Some(k)));
        }
    }
    let m = out.len();
    for i in 0..m {
        let (p, _, after) = out[i];
        let (q, before, _) = out[(i + 1) % m];
        if let (Some(k), true) = (after, after == before) {
            if (poly[(k + 1) % n] - poly[k]).dot(&(q - p)) <= 0.0 {
                return Err(InsetProblem::EdgeVanishes(k));
            }
        }
    }
    let pts: Vec<Vec2> = out.into_iter().map(|(p, _, _)| p).collect();
    let scale = poly.iter().fold(1.0 as Real, |m, p| m.max(p.norm()));
    if let Some(p) = is_simple_problem(&pts, 1e-12 * scale) {
        return Err(InsetProblem::NotSimple(p));
    }
    if signed_area(&pts) <= 0.0 {
        return Err(InsetProblem::Inverted);
    }
    Ok(pts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    fn square(s: Real) -> Vec<Vec2> {
        vec![vec2(0.0, 0.0), vec2(s, 0.0), vec2(s, s), vec2(0.0, s)]
    }

    #[test]
    fn equal_distances_inset_a_square_uniformly() {
        let out = inset_edges(&square(10.0), &[1.0; 4]).unwrap();
        assert!((signed_area(&out) - 64.0).abs() < 1e-12);
        assert!((out[0] - vec2(1.0, 1.0)).norm() < 1e-12);
    }

    #[test]
    fn only_the_moved_edges_move() {
        // Bottom and right edges shared with neighbours, top and left on the outline.
        let out = inset_edges(&square(10.0), &[0.5, 0.5, 0.0, 0.0]).unwrap();
        assert!((signed_area(&out) - 9.5 * 9.5).abs() < 1e-12);
        let xs = out.iter().map(|p| p.x).fold(Real::NEG_INFINITY, Real::max);
        let ys = out.iter().map(|p| p.y).fold(Real::INFINITY, Real::min);
        assert!((xs - 9.5).abs() < 1e-12 && (ys - 0.5).abs() < 1e-12);
    }

    #[test]
    fn a_concave_l_shape_insets_and_a_straight_vertex_steps() {
        // L shape: the reflex corner at (5, 5).
        let l = vec![
            vec2(0.0, 0.0),
            vec2(10.0, 0.0),
            vec2(10.0, 5.0),
            vec2(5.0, 5.0),
            vec2(5.0, 10.0),
            vec2(0.0, 10.0),
        ];
        let out = inset_edges(&l, &[0.5; 6]).unwrap();
        // Each edge moved by 0.5: area = 75 - 0.5·perimeter + corner terms (4 convex, 1
        // reflex mitre squares): 75 - 20 + (5 - 1)·0.25 = 56.
        assert!(
            (signed_area(&out) - 56.0).abs() < 1e-9,
            "{}",
            signed_area(&out)
        );
        // A vertex in the middle of a straight side where the offset changes.
        let mut s = square(10.0);
        s.insert(1, vec2(5.0, 0.0));
        let out = inset_edges(&s, &[0.0, 1.0, 0.0, 0.0, 0.0]).unwrap();
        assert_eq!(out.len(), 6);
        assert!((signed_area(&out) - (100.0 - 5.0)).abs() < 1e-9);
    }

    #[test]
    fn too_wide_an_inset_is_refused() {
        assert!(inset_edges(&square(1.0), &[0.6; 4]).is_err());
        let e = inset_edges(&square(1.0), &[0.6, 0.0, 0.6, 0.0]).unwrap_err();
        assert!(!e.to_string().is_empty());
    }
}

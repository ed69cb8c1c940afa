//! How deep two overlapping polygons reach into each other: the size of an overlap, where
//! [`super::interiors_overlap`] only says whether there is one.

use super::polygon::point_in_polygon_strict;
use super::segment::point_segment_distance;
use crate::math::{Real, Vec2};

/// Points sampled along every edge (ends included) when no corner of either polygon lies
/// inside the other (edges crossing like two bars).
const EDGE_SAMPLES: usize = 16;

/// The deepest a point of either simple polygon's boundary lies inside the other: its
/// distance to the other's boundary (0 when neither reaches into the other by more than
/// `tol`, an absolute length). Corners first, then points along the edges, so two bars
/// crossing without a corner inside each other are measured too.
pub fn overlap_depth(p: &[Vec2], q: &[Vec2], tol: Real) -> Real {
    let depth_in = |point: &Vec2, poly: &[Vec2]| -> Real {
        if !point_in_polygon_strict(point, poly, tol) {
            return 0.0;
        }
        let n = poly.len();
        (0..n)
            .map(|i| point_segment_distance(point, &poly[i], &poly[(i + 1) % n]))
            .fold(Real::INFINITY, Real::min)
    };
    let along = |poly: &[Vec2]| -> Vec<Vec2> {
        let n = poly.len();
        (0..n)
            .flat_map(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % n]);
                (0..EDGE_SAMPLES).map(move |s| a + (b - a) * (s as Real / EDGE_SAMPLES as Real))
            })
            .collect()
    };
    let deepest = |a: &[Vec2], b: &[Vec2]| a.iter().map(|v| depth_in(v, b)).fold(0.0, Real::max);
    let corners = deepest(p, q).max(deepest(q, p));
    if corners > 0.0 {
        return corners
            .max(deepest(&along(p), q))
            .max(deepest(&along(q), p));
    }
    deepest(&along(p), q).max(deepest(&along(q), p))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: Real, y: Real, side: Real) -> Vec<Vec2> {
        vec![
            Vec2::new(x, y),
            Vec2::new(x + side, y),
            Vec2::new(x + side, y + side),
            Vec2::new(x, y + side),
        ]
    }

    /// Two unit squares offset by (d, ½) overlap in a (1 − d) × ½ rectangle: the deepest
    /// boundary point of one inside the other is min(1 − d, ½) deep, found to within an
    /// edge sample's spacing; squares that only touch or lie apart have depth 0.
    #[test]
    fn the_depth_of_two_offset_squares_is_their_overlap() {
        for d in [0.1, 0.5, 0.9, 0.99] {
            let a = square(0.0, 0.0, 1.0);
            let b = square(d, 0.5, 1.0);
            let want = (1.0 - d).min(0.5);
            let got = overlap_depth(&a, &b, 1e-9);
            let spacing = 1.0 / EDGE_SAMPLES as Real;
            assert!(
                got <= want + 1e-12 && got >= want - spacing,
                "d {d}: {got} vs {want}"
            );
        }
        assert_eq!(
            overlap_depth(&square(0.0, 0.0, 1.0), &square(1.0, 0.0, 1.0), 1e-9),
            0.0
        );
        assert_eq!(
            overlap_depth(&square(0.0, 0.0, 1.0), &square(3.0, 0.0, 1.0), 1e-9),
            0.0
        );
    }

    /// Two thin bars crossing like a plus sign have no corner inside each other; their
    /// depth is half the bar's width, found along the edges.
    #[test]
    fn crossing_bars_are_measured_along_their_edges() {
        let w = 0.2;
        let horizontal = vec![
            Vec2::new(-1.0, -w / 2.0),
            Vec2::new(1.0, -w / 2.0),
            Vec2::new(1.0, w / 2.0),
            Vec2::new(-1.0, w / 2.0),
        ];
        let vertical: Vec<Vec2> = horizontal.iter().map(|p| Vec2::new(p.y, p.x)).collect();
        let got = overlap_depth(&horizontal, &vertical, 1e-9);
        assert!(got > 0.0 && got <= w / 2.0 + 1e-12, "{got}");
        assert!(got >= w / 2.0 * 0.8, "{got}");
    }
}

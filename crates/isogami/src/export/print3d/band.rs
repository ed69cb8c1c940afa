//! A lamella slab's footprint at a joint (see [`super::layout`]): the band `hinge` wide
//! across the joint's gap, closed or opened, and the convex hull of its corners.

use crate::geometry::signed_area;
use crate::math::{cross, Real, Vec2};

/// A lamella slab at an opened joint: the band between two lines across the joint's gap,
/// normal to the bisector `b` of the two copies of the edge and `hinge` apart, so the neck
/// (the band across the gap) is `hinge` wide at any opening. Closed, the copies coincide
/// and the band is the rectangle `[s0, s0 + hinge]` along the edge, `w` to either side.
///
/// On a copy with direction d and inward normal n, the band line at distance r from V
/// along b meets the line at depth u into the tile at `s = (r − u n·b) / d·b` along the
/// edge. The band starts at `r0`, the least r at which no point of the slab within either
/// tile (depth 0 to w) is nearer to V along the edge than `s0` (the closed slab's start, which
/// keeps its clearances); it reaches `reach` along the edge.
pub(super) struct Band {
    pub(super) closed: bool,
    b: Vec2,
    r0: Real,
    hinge: Real,
    w: Real,
    pub(super) reach: Real,
}

impl Band {
    pub(super) fn new(sides: &[(Vec2, Vec2, Vec2); 2], s0: Real, w: Real, hinge: Real) -> Band {
        let sum = sides[0].1 + sides[1].1;
        let closed = cross(&sides[0].1, &sides[1].1).abs() < 1e-12 && sum.norm() > 1.0;
        let b = if closed {
            sides[0].1
        } else if sum.norm() > 1e-9 {
            sum.normalize()
        } else {
            sides[0].1
        };
        let mut r0: Real = 0.0;
        let mut reach: Real = 0.0;
        for (_, d, n) in sides {
            let cos = d.dot(&b);
            let nb = n.dot(&b);
            if cos < 1e-3 {
                // Opened to a straight angle or beyond: no band crosses the gap.
                return Band {
                    closed,
                    b,
                    r0: 0.0,
                    hinge,
                    w,
                    reach: Real::INFINITY,
                };
            }
            r0 = r0.max(s0 * cos + (w * nb).max(0.0));
            reach = reach.max(-w * nb.min(0.0) / cos);
        }
        let cos = sides[0].1.dot(&b);
        Band {
            closed,
            b,
            r0,
            hinge,
            w,
            reach: reach + (r0 + hinge) / cos,
        }
    }

    /// The band's two corners at depth w into the tile of copy `(_, d, n)`, the joint at `v`.
    /// Where the joint is closed (the copies parallel) they are computed as the rectangle's,
    /// from the copy's own vertex: a slab corner often lies exactly on an outline edge of its
    /// tile, and the mesh union must see the same point there, not one 1e-15 away (a sliver
    /// that a float32 STL collapses).
    pub(super) fn corners(&self, v: Vec2, side: &(Vec2, Vec2, Vec2), s0: Real) -> [Vec2; 2] {
        let (own, d, n) = *side;
        if self.closed {
            let start = own + d * s0;
            return [start + n * self.w, own + d * (s0 + self.hinge) + n * self.w];
        }
        let at = |r: Real| v + d * ((r - self.w * n.dot(&self.b)) / d.dot(&self.b)) + n * self.w;
        [at(self.r0), at(self.r0 + self.hinge)]
    }
}

/// Counter-clockwise convex hull (Andrew's monotone chain) of a few points.
pub(super) fn convex_hull(points: &[Vec2]) -> Vec<Vec2> {
    let mut pts = points.to_vec();
    pts.sort_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
    let mut hull: Vec<Vec2> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        for p in &pts {
            while hull.len() >= start + 2
                && cross(
                    &(hull[hull.len() - 1] - hull[hull.len() - 2]),
                    &(p - hull[hull.len() - 2]),
                ) <= 0.0
            {
                hull.pop();
            }
            hull.push(*p);
        }
        hull.pop();
        if pass == 0 {
            pts.reverse();
        }
    }
    debug_assert!(hull.len() < 3 || signed_area(&hull) > 0.0);
    hull
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn the_hull_of_a_rectangle_is_counter_clockwise() {
        let h = convex_hull(&[
            vec2(0.0, 1.0),
            vec2(2.0, 0.0),
            vec2(0.0, 0.0),
            vec2(2.0, 1.0),
        ]);
        assert_eq!(h.len(), 4);
        assert!((signed_area(&h) - 2.0).abs() < 1e-12);
    }
}

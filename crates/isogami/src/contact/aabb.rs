//! Axis-aligned bounding boxes: the broad phase.

use crate::math::{Real, Vec2};

/// A closed axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Aabb {
    pub(crate) lo: Vec2,
    pub(crate) hi: Vec2,
}

impl Aabb {
    /// The box of a non-empty point set.
    pub(crate) fn of(points: &[Vec2]) -> Aabb {
        let mut lo = Vec2::repeat(Real::INFINITY);
        let mut hi = Vec2::repeat(Real::NEG_INFINITY);
        for p in points {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        Aabb { lo, hi }
    }

    /// The box moved by `shift`.
    pub(crate) fn shifted(&self, shift: Vec2) -> Aabb {
        Aabb {
            lo: self.lo + shift,
            hi: self.hi + shift,
        }
    }

    /// Euclidean distance between the boxes (0 when they touch or overlap): a lower bound of
    /// the distance between anything inside them.
    pub(crate) fn gap(&self, other: &Aabb) -> Real {
        let dx = (other.lo.x - self.hi.x)
            .max(self.lo.x - other.hi.x)
            .max(0.0);
        let dy = (other.lo.y - self.hi.y)
            .max(self.lo.y - other.hi.y)
            .max(0.0);
        dx.hypot(dy)
    }

    /// True when the boxes come closer than `margin` along both axes (a cheap, conservative
    /// "might be within `margin`" test).
    pub(crate) fn near(&self, other: &Aabb, margin: Real) -> bool {
        other.lo.x - self.hi.x < margin
            && self.lo.x - other.hi.x < margin
            && other.lo.y - self.hi.y < margin
            && self.lo.y - other.hi.y < margin
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn gap_and_nearness() {
        let a = Aabb::of(&[vec2(0.0, 0.0), vec2(1.0, 1.0)]);
        let b = a.shifted(vec2(4.0, 5.0));
        assert!((a.gap(&b) - 5.0).abs() < 1e-15);
        assert!(!a.near(&b, 2.9));
        assert!(a.near(&b, 4.1));
        let c = a.shifted(vec2(0.5, 0.5));
        assert_eq!(a.gap(&c), 0.0);
        assert!(a.near(&c, 0.0));
    }
}

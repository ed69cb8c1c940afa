//! The few state variables one candidate pair touches, and the chain rule from collision
//! vertex positions to them. A vertex with lever arm m = R(θ)s of a tile in cell (k_u, k_w)
//! sits at x = m + p + k_u u + k_w w: ∂x/∂p = I, ∂x/∂θ = perp(m), ∂x/∂u = k_u I,
//! ∂x/∂w = k_w I, and the only second derivative is ∂²x/∂θ² = −m.

use super::pairs::CandidatePair;
use crate::kinematics::StateLayout;
use crate::math::{perp, Real, Vec2};
use nalgebra::SMatrix;

/// At most two tiles (x, y, θ each) plus u and w.
pub(crate) const MAX_LOCAL: usize = 10;

/// Jacobian of (p, a, b) (one vertex and one edge) with respect to the local variables.
pub(crate) type TermJacobian = SMatrix<Real, 6, MAX_LOCAL>;

/// Local variable slots of one side of a pair.
#[derive(Debug, Clone, Copy)]
struct SideVars {
    /// Slot of the tile's x (y and θ follow).
    base: usize,
    /// Slot of u_x (u_y follows) and k_u, when k_u ≠ 0.
    u: Option<(usize, Real)>,
    /// Slot of w_x (w_y follows) and k_w, when k_w ≠ 0.
    w: Option<(usize, Real)>,
}

/// The local variables of a pair: side 0 is tile `a` in the centre cell, side 1 tile `b` in
/// the cell at the pair's offset. When a == b the two sides share the tile's slots.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairVars {
    /// Global state index of every local slot.
    pub(crate) global: [usize; MAX_LOCAL],
    /// Number of local slots in use.
    pub(crate) len: usize,
    sides: [SideVars; 2],
}

impl PairVars {
    pub(crate) fn new(layout: StateLayout, pair: &CandidatePair) -> PairVars {
        let mut global = [0; MAX_LOCAL];
        let mut len = 0;
        let mut push = |g: usize, count: usize| {
            let slot = len;
            for k in 0..count {
                global[len] = g + k;
                len += 1;
            }
            slot
        };
        let base_a = push(layout.tile(pair.a), 3);
        let base_b = if pair.b == pair.a {
            base_a
        } else {
            push(layout.tile(pair.b), 3)
        };
        let [ku, kw] = pair.offset;
        let u = (ku != 0).then(|| (push(layout.u(), 2), Real::from(ku)));
        let w = (kw != 0).then(|| (push(layout.w(), 2), Real::from(kw)));
        let side_a = SideVars {
            base: base_a,
            u: None,
            w: None,
        };
        let side_b = SideVars { base: base_b, u, w };
        PairVars {
            global,
            len,
            sides: [side_a, side_b],
        }
    }

    /// Local slot of the θ of side `side`.
    pub(crate) fn theta_slot(&self, side: usize) -> usize {
        self.sides[side].base + 2
    }

    /// Writes ∂x/∂(local) of a vertex of side `side` with lever arm `arm` into rows
    /// `row`, `row + 1` of `jac` (which must be zero there).
    pub(crate) fn write_rows(&self, side: usize, arm: &Vec2, jac: &mut TermJacobian, row: usize) {
        let s = self.sides[side];
        let t = perp(arm);
        for d in 0..2 {
            jac[(row + d, s.base + d)] = 1.0;
            jac[(row + d, s.base + 2)] = t[d];
            if let Some((slot, k)) = s.u {
                jac[(row + d, slot + d)] = k;
            }
            if let Some((slot, k)) = s.w {
                jac[(row + d, slot + d)] = k;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn slots_are_shared_for_a_tile_and_its_translate() {
        let layout = StateLayout { tiles: 3 };
        let p = PairVars::new(
            layout,
            &CandidatePair {
                a: 1,
                b: 1,
                offset: [1, -1],
            },
        );
        assert_eq!(p.len, 7);
        assert_eq!(&p.global[..7], &[3, 4, 5, 9, 10, 11, 12]);
        assert_eq!(p.theta_slot(0), p.theta_slot(1));
        let q = PairVars::new(
            layout,
            &CandidatePair {
                a: 0,
                b: 2,
                offset: [0, 0],
            },
        );
        assert_eq!(&q.global[..q.len], &[0, 1, 2, 6, 7, 8]);
        let mut jac = TermJacobian::zeros();
        p.write_rows(1, &vec2(0.5, 0.25), &mut jac, 2);
        assert_eq!(jac[(2, 0)], 1.0);
        assert_eq!(jac[(2, 2)], -0.25);
        assert_eq!(jac[(3, 2)], 0.5);
        assert_eq!(jac[(2, 3)], 1.0);
        assert_eq!(jac[(3, 6)], -1.0);
    }
}

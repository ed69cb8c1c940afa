//! "Adjacent tiles actually separate along the motion" (paper §4.1, second eigen-analysis
//! check), as a first-order test on the closed state.
//!
//! For every unique edge of the cell — tile a in cell 0 and the copy of tile b at the edge's
//! cell offset, jointed or not — the relative velocity of the two tiles at each edge endpoint
//! P is d(P) = [v_b + k_u u̇ + k_w ẇ + ω_b (P − c_b′)^⊥] − [v_a + ω_a (P − c_a)^⊥], where c_b′ is
//! the centroid of b's copy. Its component along tile a's outward edge normal is the rate at
//! which the cut opens there (positive: b moves away from a); it is linear along the edge, so
//! the two endpoints bound it. These rates do not depend on which tile is held fixed (a rigid
//! motion superposed on both tiles cancels in d) and are measured on the unit motion vector of
//! the non-dimensional model (lengths in units of the mean edge length L).
//!
//! An edge is **moving** when |opening rate| > [`SEPARATION_TOL`] at one of its endpoints, and
//! **shut** otherwise (its two tiles at most slide along the cut). A jointed edge that is shut
//! holds its two tiles rigidly attached to first order (no relative rotation about the pin).
//! The filter is a [`SeparationRule`]:
//!
//! - [`SeparationRule::AnyEdge`]: some edge moves — some pair of neighbours moves apart under
//!   one of the two signs of the motion. Designs whose every cut only slides are dropped.
//! - [`SeparationRule::NoRigidJoint`] (the default): some edge moves *and* no jointed pair of
//!   tiles stays rigidly attached — the paper's "we discard designs where tiles remain rigidly
//!   attached". Such a design's motion is that of a design with the welded pair merged; its
//!   joint between them carries no motion and is interchangeable (A or B) at first order.
//! - [`SeparationRule::EveryEdge`]: every adjacent pair, jointed or not, moves.
//!
//! Also reported, never filtered on: for each sign of the motion whether no edge closes at
//! first order (no endpoint opening rate below −tol), a first-order hint of what deployment
//! will find (deployment with kerf and contact decides). Plain data in and out; no dedup, no
//! I/O.

use crate::cell::UnitCell;
use crate::kinematics::Mechanism;
use crate::math::{perp, DVec, Vec2};
use crate::topology::JointChoice;
use serde::Serialize;

/// An endpoint's opening rate (units of L per unit of the unit motion vector) counts as
/// non-zero above this. Motion vectors from the eigen-solver or the null-space projection are
/// accurate to ~1e-12 when the spectral gap is several decades.
pub const SEPARATION_TOL: f64 = 1e-6;

/// First-order relative motion across one unique edge.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EdgeRate {
    /// Opening rate (relative velocity along tile a's outward normal) at endpoints A and B.
    pub opening: [f64; 2],
    /// Relative velocity vectors d(P) at endpoints A and B.
    pub relative: [[f64; 2]; 2],
    /// Relative rotation rate ω_b − ω_a.
    pub rotation: f64,
}

/// Which motions count as separating (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum SeparationRule {
    /// Some edge moves.
    AnyEdge,
    /// Some edge moves and no jointed edge is shut.
    #[default]
    NoRigidJoint,
    /// Every edge moves.
    EveryEdge,
}

/// The separation verdict of one motion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Separation {
    /// Edges whose opening rate exceeds the tolerance in magnitude at an endpoint.
    pub moving_edges: usize,
    /// Edges that are not moving.
    pub shut_edges: usize,
    /// Jointed edges that are shut: tile pairs rigidly attached to first order.
    pub rigid_joints: usize,
    /// Largest |opening rate| over all edges and endpoints.
    pub max_rate: f64,
    /// For the motion as signed by `mobility` (+) and its reverse (−): true when no edge
    /// closes at first order.
    pub unblocked: [bool; 2],
}

/// Relative motion across every unique edge of `cell` along state velocity `v`. `mech` is any
/// mechanism of the same cell (only its tile shapes and closed state are used).
pub fn edge_rates(cell: &UnitCell, mech: &Mechanism, v: &DVec) -> Vec<EdgeRate> {
    let l = mech.layout;
    let vel = |i: usize| Vec2::new(v[l.tile(i)], v[l.tile(i) + 1]);
    let omega = |i: usize| v[l.tile(i) + 2];
    let du = Vec2::new(v[l.u()], v[l.u() + 1]);
    let dw = Vec2::new(v[l.w()], v[l.w() + 1]);
    cell.edges
        .iter()
        .map(|e| {
            let sa = &mech.tile_shapes[e.tile_a];
            let sb = &mech.tile_shapes[e.tile_b];
            let (na, nb) = (sa.len(), sb.len());
            // Endpoint A is vertex edge_a of tile a and vertex edge_b + 1 of tile b.
            let a_pts = [sa[e.edge_a], sa[(e.edge_a + 1) % na]];
            let b_pts = [sb[(e.edge_b + 1) % nb], sb[e.edge_b]];
            let t = a_pts[1] - a_pts[0];
            let normal = Vec2::new(t.y, -t.x) / t.norm().max(f64::MIN_POSITIVE);
            let base_b = vel(e.tile_b) + du * f64::from(e.offset[0]) + dw * f64::from(e.offset[1]);
            let rel = |k: usize| {
                let vb = base_b + perp(&b_pts[k]) * omega(e.tile_b);
                let va = vel(e.tile_a) + perp(&a_pts[k]) * omega(e.tile_a);
                vb - va
            };
            let (ra, rb) = (rel(0), rel(1));
            EdgeRate {
                opening: [ra.dot(&normal), rb.dot(&normal)],
                relative: [[ra.x, ra.y], [rb.x, rb.y]],
                rotation: omega(e.tile_b) - omega(e.tile_a),
            }
        })
        .collect()
}

/// Largest first-order closing rate over every edge endpoint of `rates`, for the motion as
/// signed (+) and its reverse (−); 0 when nothing closes. `None` when a rate is not finite.
pub fn closing_rates(rates: &[EdgeRate]) -> Option<[f64; 2]> {
    let mut close = [0.0f64; 2];
    for r in rates {
        for o in r.opening {
            close[0] = close[0].max(-o);
            close[1] = close[1].max(o);
        }
    }
    close.iter().all(|c| c.is_finite()).then_some(close)
}

impl Separation {
    /// True when the motion separates under `rule`.
    pub fn passes(&self, rule: SeparationRule) -> bool {
        match rule {
            SeparationRule::AnyEdge => self.moving_edges > 0,
            SeparationRule::NoRigidJoint => self.moving_edges > 0 && self.rigid_joints == 0,
            SeparationRule::EveryEdge => self.moving_edges > 0 && self.shut_edges == 0,
        }
    }
}

/// The separation verdict of motion `v` of the design with `joints` on `cell` (`mech`: any
/// mechanism of the cell; only its tile shapes and layout are used).
pub fn separation(
    cell: &UnitCell,
    mech: &Mechanism,
    joints: &[JointChoice],
    v: &DVec,
) -> Separation {
    summarize(&edge_rates(cell, mech, v), joints)
}

/// The verdict from precomputed edge rates (one per edge, in edge order, like `joints`).
pub fn summarize(rates: &[EdgeRate], joints: &[JointChoice]) -> Separation {
    let tol = SEPARATION_TOL;
    let mut out = Separation {
        moving_edges: 0,
        shut_edges: 0,
        rigid_joints: 0,
        max_rate: 0.0,
        unblocked: [true, true],
    };
    for (k, r) in rates.iter().enumerate() {
        let biggest = r.opening[0].abs().max(r.opening[1].abs());
        out.max_rate = out.max_rate.max(biggest);
        if biggest > tol {
            out.moving_edges += 1;
        } else {
            out.shut_edges += 1;
            if joints.get(k).is_some_and(|j| *j != JointChoice::None) {
                out.rigid_joints += 1;
            }
        }
        for &g in &r.opening {
            if g < -tol {
                out.unblocked[0] = false;
            }
            if g > tol {
                out.unblocked[1] = false;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mobility::{analyze, MobilitySettings};
    use crate::topology::Design;

    #[test]
    fn rotating_squares_open_at_every_edge() {
        let d = Design::resolve("rotating-squares").unwrap();
        let cell = d.cell().unwrap();
        let mech = Mechanism::new(&cell, &d.joints).unwrap();
        let mob = analyze(&mech, &mech.rest, MobilitySettings::default()).unwrap();
        let v = &mob.motion.as_ref().unwrap().vector;
        let rates = edge_rates(&cell, &mech, v);
        for (r, j) in rates.iter().zip(&d.joints) {
            // The hinged end stays shut, the free end moves.
            let (hinge, free) = match j {
                crate::topology::JointChoice::A => (0, 1),
                _ => (1, 0),
            };
            assert!(r.opening[hinge].abs() < 1e-9, "{r:?}");
            assert!(r.opening[free].abs() > 1e-3, "{r:?}");
            assert!(r.rotation.abs() > 1e-3);
        }
        let s = summarize(&rates, &d.joints);
        assert!(s.passes(SeparationRule::EveryEdge));
        assert_eq!((s.moving_edges, s.shut_edges, s.rigid_joints), (8, 0, 0));
        // The opening sign (area grows) opens every cut.
        assert_eq!(s.unblocked, [true, false]);
    }
}

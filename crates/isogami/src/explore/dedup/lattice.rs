//! The supercell lattice as the deduplication steps use it: integer coordinates of a point in
//! the basis (u, w), with a matching tolerance relative to the mean edge length.

use crate::cell::{End, UnitCell};
use crate::math::{cross, Vec2};

/// Geometric matching tolerance, relative to the mean edge length.
const GEOM_REL_TOL: f64 = 1e-6;

/// Lattice helper: coordinates of points in the basis (u, w) and membership tests.
pub(super) struct Lattice {
    pub(super) u: Vec2,
    pub(super) w: Vec2,
    det: f64,
    pub(super) tol: f64,
}

impl Lattice {
    pub(super) fn new(cell: &UnitCell) -> Lattice {
        Lattice {
            u: cell.u,
            w: cell.w,
            det: cross(&cell.u, &cell.w),
            tol: GEOM_REL_TOL * cell.mean_edge_length(),
        }
    }

    /// The integer lattice coordinates of `p`, if `p` is a lattice vector.
    pub(super) fn coords(&self, p: &Vec2) -> Option<[i32; 2]> {
        let a = (cross(p, &self.w) / self.det).round();
        let b = (cross(&self.u, p) / self.det).round();
        if (p - (self.u * a + self.w * b)).norm() <= self.tol && a.abs() < 1e6 && b.abs() < 1e6 {
            Some([a as i32, b as i32])
        } else {
            None
        }
    }
}

/// Both endpoints of every unique edge of the cell, in edge order.
pub(super) fn edge_ends(cell: &UnitCell) -> Vec<(Vec2, Vec2)> {
    (0..cell.edges.len())
        .map(|e| (cell.endpoint(e, End::A), cell.endpoint(e, End::B)))
        .collect()
}

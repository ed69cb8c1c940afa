//! Mechanism assembly, residuals and derivatives.

use super::error::KinematicsError;
use crate::cell::{End, UnitCell};
use crate::math::{perp, rotation, DMat, DVec, Real, Vec2};
use crate::topology::JointChoice;

/// Index arithmetic for the state vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StateLayout {
    /// Number of tiles.
    pub tiles: usize,
}

impl StateLayout {
    /// Length of q: 3n + 4.
    pub fn len(self) -> usize {
        3 * self.tiles + 4
    }

    /// Never empty (u and w are always there).
    pub fn is_empty(self) -> bool {
        false
    }

    /// Index of x_i (y_i and θ_i follow).
    pub fn tile(self, i: usize) -> usize {
        3 * i
    }

    /// Index of u_x (u_y, w_x, w_y follow).
    pub fn u(self) -> usize {
        3 * self.tiles
    }

    /// Index of w_x (w_y follows).
    pub fn w(self) -> usize {
        3 * self.tiles + 2
    }
}

/// One pin joint in tile-local, non-dimensional coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// The unique edge it sits on.
    pub edge: usize,
    /// Which end of that edge.
    pub end: End,
    /// First tile (cell 0).
    pub tile_a: usize,
    /// Joint point in tile a's frame (relative to its centroid, units of L).
    pub s_a: Vec2,
    /// Second tile.
    pub tile_b: usize,
    /// Joint point in tile b's frame.
    pub s_b: Vec2,
    /// Cell offset of tile b's copy.
    pub offset: [Real; 2],
}

/// Rigid tiles, pin joints and the periodic lattice of one design.
#[derive(Debug, Clone)]
pub struct Mechanism {
    /// Layout of the state vector.
    pub layout: StateLayout,
    /// The pin joints.
    pub joints: Vec<Joint>,
    /// Tile vertices in each tile's frame (non-dimensional), counter-clockwise.
    pub tile_shapes: Vec<Vec<Vec2>>,
    /// The length unit L (mean edge length of the cell, in the tiling's units).
    pub length_scale: Real,
    /// The closed state q⁰ (non-dimensional).
    pub rest: DVec,
}

impl Mechanism {
    /// Assembles the mechanism of `cell` with one joint choice per unique edge.
    pub fn new(cell: &UnitCell, joints: &[JointChoice]) -> Result<Mechanism, KinematicsError> {
        if joints.len() != cell.edges.len() {
            return Err(KinematicsError::JointCount {
                given: joints.len(),
                edges: cell.edges.len(),
            });
        }
        let scale = cell.mean_edge_length();
        let layout = StateLayout {
            tiles: cell.tiles.len(),
        };
        let local = |t: usize, v: Vec2| (v - cell.tiles[t].centroid) / scale;
        let tile_shapes = (0..cell.tiles.len())
            .map(|t| cell.tiles[t].polygon.iter().map(|&v| local(t, v)).collect())
            .collect();
        let mut list = Vec::new();
        for (k, choice) in joints.iter().enumerate() {
            let e = cell.edges[k];
            for &end in choice.ends() {
                let pa = cell.tiles[e.tile_a].polygon[cell.endpoint_index_on_a(k, end)];
                let pb = cell.tiles[e.tile_b].polygon[cell.endpoint_index_on_b(k, end)];
                list.push(Joint {
                    edge: k,
                    end,
                    tile_a: e.tile_a,
                    s_a: local(e.tile_a, pa),
                    tile_b: e.tile_b,
                    s_b: local(e.tile_b, pb),
                    offset: [Real::from(e.offset[0]), Real::from(e.offset[1])],
                });
            }
        }
        let mut rest = DVec::zeros(layout.len());
        for (i, t) in cell.tiles.iter().enumerate() {
            rest[layout.tile(i)] = t.centroid.x / scale;
            rest[layout.tile(i) + 1] = t.centroid.y / scale;
        }
        rest.fixed_rows_mut::<2>(layout.u())
            .copy_from(&(cell.u / scale));
        rest.fixed_rows_mut::<2>(layout.w())
            .copy_from(&(cell.w / scale));
        Ok(Mechanism {
            layout,
            joints: list,
            tile_shapes,
            length_scale: scale,
            rest,
        })
    }

    /// Number of tiles.
    pub fn tile_count(&self) -> usize {
        self.layout.tiles
    }

    /// Position and angle of tile `i`.
    pub fn pose(&self, q: &DVec, i: usize) -> (Vec2, Real) {
        let k = self.layout.tile(i);
        (Vec2::new(q[k], q[k + 1]), q[k + 2])
    }

    /// Tiling vectors u and w at state q.
    pub fn lattice(&self, q: &DVec) -> (Vec2, Vec2) {
        let (u, w) = (self.layout.u(), self.layout.w());
        (Vec2::new(q[u], q[u + 1]), Vec2::new(q[w], q[w + 1]))
    }

    /// Stacked joint residuals c(q) ∈ R^{2m}.
    pub fn residual(&self, q: &DVec) -> DVec {
        let (u, w) = self.lattice(q);
        let mut c = DVec::zeros(2 * self.joints.len());
        for (r, j) in self.joints.iter().enumerate() {
            let (pa, ta) = self.pose(q, j.tile_a);
            let (pb, tb) = self.pose(q, j.tile_b);
            let v = rotation(ta) * j.s_a + pa
                - (rotation(tb) * j.s_b + pb + u * j.offset[0] + w * j.offset[1]);
            c.fixed_rows_mut::<2>(2 * r).copy_from(&v);
        }
        c
    }

    /// Exact Jacobian ∂c/∂q (2m × (3n+4)).
    pub fn jacobian(&self, q: &DVec) -> DMat {
        let mut jac = DMat::zeros(2 * self.joints.len(), self.layout.len());
        let (iu, iw) = (self.layout.u(), self.layout.w());
        for (r, j) in self.joints.iter().enumerate() {
            let row = 2 * r;
            let (_, ta) = self.pose(q, j.tile_a);
            let (_, tb) = self.pose(q, j.tile_b);
            let da = rotation(ta) * perp(&j.s_a);
            let db = rotation(tb) * perp(&j.s_b);
            let (ka, kb) = (self.layout.tile(j.tile_a), self.layout.tile(j.tile_b));
            for d in 0..2 {
                jac[(row + d, ka + d)] += 1.0;
                jac[(row + d, kb + d)] -= 1.0;
                jac[(row + d, ka + 2)] += da[d];
                jac[(row + d, kb + 2)] -= db[d];
                jac[(row + d, iu + d)] -= j.offset[0];
                jac[(row + d, iw + d)] -= j.offset[1];
            }
        }
        jac
    }

    /// E_joints(q) = ½ |c(q)|².
    pub fn energy(&self, q: &DVec) -> Real {
        0.5 * self.residual(q).norm_squared()
    }

    /// ∇E_joints = Jᵀc.
    pub fn gradient(&self, q: &DVec) -> DVec {
        self.jacobian(q).transpose() * self.residual(q)
    }

    /// Exact Hessian of E_joints: JᵀJ + Σₖ cₖ ∇²cₖ. Only θθ second derivatives are non-zero:
    /// ∂²(R(θ)s)/∂θ² = −R(θ)s.
    pub fn hessian(&self, q: &DVec) -> DMat {
        let jac = self.jacobian(q);
        let c = self.residual(q);
        let mut h = jac.transpose() * &jac;
        for (r, j) in self.joints.iter().enumerate() {
            let cr = Vec2::new(c[2 * r], c[2 * r + 1]);
            let (_, ta) = self.pose(q, j.tile_a);
            let (_, tb) = self.pose(q, j.tile_b);
            let (ka, kb) = (
                self.layout.tile(j.tile_a) + 2,
                self.layout.tile(j.tile_b) + 2,
            );
            h[(ka, ka)] -= cr.dot(&(rotation(ta) * j.s_a));
            h[(kb, kb)] += cr.dot(&(rotation(tb) * j.s_b));
        }
        h
    }

    /// Tile `i`'s polygon at state q, in non-dimensional world coordinates, in cell `offset`.
    pub fn tile_polygon(&self, q: &DVec, i: usize, offset: [i32; 2]) -> Vec<Vec2> {
        let (p, th) = self.pose(q, i);
        let (u, w) = self.lattice(q);
        let shift = p + u * Real::from(offset[0]) + w * Real::from(offset[1]);
        let r = rotation(th);
        self.tile_shapes[i].iter().map(|s| r * s + shift).collect()
    }
}

//! The graded sheet: a finite sheet of a design whose closed-state vertices are free.
//!
//! The closed sheet is a tiling, so a vertex shared by several tiles is one *node* with one
//! position; each tile is a list of nodes. Nodes are found combinatorially: the two ends of
//! every cell edge between two tiles of the sheet are the same node (union–find over
//! (tile, vertex) pairs), never by comparing positions. The joints are the design's: a pin
//! between two tiles at a node they share. The opened state is one pose per tile (the
//! opened position of its first node and its rotation from the closed state), so opened
//! tiles are rigid copies of their closed shapes by construction.

use super::error::GradedError;
use crate::cell::{End, UnitCell};
use crate::disjoint_sets::DisjointSets;
use crate::finite::{FiniteSheet, Region, SheetTile};
use crate::kinematics::Mechanism;
use crate::math::{cross, rotation, Real, Vec2};
use serde::{Deserialize, Serialize};
use std::collections::HashSet;

/// One tile of a graded sheet.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GradedTile {
    /// Cell copy it came from (multiples of the design's u and w).
    pub cell: [i32; 2],
    /// Tile index in the design's cell.
    pub tile: usize,
    /// Its corners, counter-clockwise, as indices into [`GradedSheet::nodes`].
    pub nodes: Vec<usize>,
}

/// A pin between two tiles at a node they share in the closed state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct GradedJoint {
    /// Index of the first tile.
    pub a: usize,
    /// Index of the second tile.
    pub b: usize,
    /// The node they are pinned at.
    pub node: usize,
}

/// Pose of a tile in the opened state: where its first node is and how far it turned.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OpenedPose {
    /// Opened position of the tile's first node (units of the length scale).
    pub x: Real,
    /// See `x`.
    pub y: Real,
    /// Rotation from the closed state, radians counter-clockwise.
    pub theta: Real,
}

/// A finite sheet whose tiles each have their own shape, and its opened state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GradedSheet {
    /// The design it grades (canonical spec).
    pub design: String,
    /// Mean edge length of the design's cell: the unit of every coordinate here, in the
    /// design's own tiling units.
    pub length_scale: Real,
    /// Closed-state positions of the nodes (units of the length scale).
    pub nodes: Vec<[Real; 2]>,
    /// The tiles.
    pub tiles: Vec<GradedTile>,
    /// The pins.
    pub joints: Vec<GradedJoint>,
    /// The opened state, one pose per tile.
    pub opened: Vec<OpenedPose>,
    /// States part of the way open (the optimisation asks the pins to close in them too),
    /// least open first; each one pose per tile.
    #[serde(default)]
    pub path: Vec<Vec<OpenedPose>>,
}

impl GradedSheet {
    /// The ungraded sheet of `sheet`'s tiles: every tile the design's own shape at its place
    /// in the closed periodic sheet, opened to the periodic state `q` of `mech`.
    pub fn ungraded(
        design: &str,
        cell: &UnitCell,
        mech: &Mechanism,
        sheet: &FiniteSheet,
        q: &crate::math::DVec,
    ) -> Result<GradedSheet, GradedError> {
        if sheet.is_empty() {
            return Err(GradedError::BadRegion("the region holds no tile".into()));
        }
        let index: std::collections::HashMap<SheetTile, usize> = sheet
            .tiles
            .iter()
            .enumerate()
            .map(|(i, t)| (*t, i))
            .collect();
        // Union–find over (tile, vertex) slots.
        let offsets: Vec<usize> = sheet
            .tiles
            .iter()
            .scan(0, |acc, t| {
                let start = *acc;
                *acc += cell.tiles[t.tile].polygon.len();
                Some(start)
            })
            .collect();
        let slots =
            offsets.last().unwrap() + cell.tiles[sheet.tiles.last().unwrap().tile].polygon.len();
        let mut sets = DisjointSets::new(slots);
        for (a, ta) in sheet.tiles.iter().enumerate() {
            for (k, e) in cell.edges.iter().enumerate() {
                if e.tile_a != ta.tile {
                    continue;
                }
                let partner = SheetTile {
                    cell: [ta.cell[0] + e.offset[0], ta.cell[1] + e.offset[1]],
                    tile: e.tile_b,
                };
                let Some(&b) = index.get(&partner) else {
                    continue;
                };
                for end in [End::A, End::B] {
                    let sa = offsets[a] + cell.endpoint_index_on_a(k, end);
                    let sb = offsets[b] + cell.endpoint_index_on_b(k, end);
                    sets.union(sa, sb);
                }
            }
        }
        let mut node_of_root = vec![usize::MAX; slots];
        let mut nodes: Vec<[Real; 2]> = Vec::new();
        let mut tiles = Vec::with_capacity(sheet.len());
        for (i, t) in sheet.tiles.iter().enumerate() {
            let polygon = mech.tile_polygon(&mech.rest, t.tile, t.cell);
            let mut corners = Vec::with_capacity(polygon.len());
            for (v, p) in polygon.iter().enumerate() {
                let r = sets.find(offsets[i] + v);
                if node_of_root[r] == usize::MAX {
                    node_of_root[r] = nodes.len();
                    nodes.push([p.x, p.y]);
                }
                corners.push(node_of_root[r]);
            }
            tiles.push(GradedTile {
                cell: t.cell,
                tile: t.tile,
                nodes: corners,
            });
        }
        let joints = sheet
            .joints
            .iter()
            .map(|j| {
                let joint = &mech.joints[j.joint];
                let v = cell.endpoint_index_on_a(joint.edge, joint.end);
                GradedJoint {
                    a: j.a,
                    b: j.b,
                    node: tiles[j.a].nodes[v],
                }
            })
            .collect();
        let opened = periodic_poses(mech, sheet, q);
        let mut graded = GradedSheet {
            design: design.to_string(),
            length_scale: mech.length_scale,
            nodes,
            tiles,
            joints,
            opened,
            path: Vec::new(),
        };
        graded.centre_opened();
        Ok(graded)
    }

    /// The poses of this sheet's tiles at the periodic state `q` of `mech` (the sheet it was
    /// made from by [`GradedSheet::ungraded`]), centred like its opened state.
    pub fn periodic_state(
        &self,
        mech: &Mechanism,
        sheet: &FiniteSheet,
        q: &crate::math::DVec,
    ) -> Vec<OpenedPose> {
        let mut at = GradedSheet {
            opened: periodic_poses(mech, sheet, q),
            path: Vec::new(),
            ..self.clone()
        };
        at.centre_opened();
        at.opened
    }

    /// Closed position of node `n`.
    pub fn node(&self, n: usize) -> Vec2 {
        Vec2::new(self.nodes[n][0], self.nodes[n][1])
    }

    /// Closed polygon of tile `i`.
    pub fn closed_polygon(&self, i: usize) -> Vec<Vec2> {
        self.tiles[i].nodes.iter().map(|&n| self.node(n)).collect()
    }

    /// Opened polygon of tile `i`.
    pub fn opened_polygon(&self, i: usize) -> Vec<Vec2> {
        let t = &self.tiles[i];
        let pose = self.opened[i];
        let r = rotation(pose.theta);
        let first = self.node(t.nodes[0]);
        t.nodes
            .iter()
            .map(|&n| Vec2::new(pose.x, pose.y) + r * (self.node(n) - first))
            .collect()
    }

    /// Moves the opened state so the centroid of its corners is the origin.
    pub fn centre_opened(&mut self) {
        let mut sum = Vec2::zeros();
        let mut count = 0.0;
        for i in 0..self.tiles.len() {
            for p in self.opened_polygon(i) {
                sum += p;
                count += 1.0;
            }
        }
        let c = sum / count;
        for pose in &mut self.opened {
            pose.x -= c.x;
            pose.y -= c.y;
        }
    }

    /// The closed sheet's boundary: every (tile, corner index) on an edge that no other tile
    /// of the sheet shares, found from the node lists (an edge is shared when another tile
    /// has the same two nodes).
    pub fn boundary_corners(&self) -> Vec<(usize, usize)> {
        let mut count: std::collections::HashMap<(usize, usize), usize> =
            std::collections::HashMap::new();
        for t in &self.tiles {
            let n = t.nodes.len();
            for v in 0..n {
                let (p, q) = (t.nodes[v], t.nodes[(v + 1) % n]);
                *count.entry((p.min(q), p.max(q))).or_default() += 1;
            }
        }
        let mut out: HashSet<(usize, usize)> = HashSet::new();
        for (i, t) in self.tiles.iter().enumerate() {
            let n = t.nodes.len();
            for v in 0..n {
                let (p, q) = (t.nodes[v], t.nodes[(v + 1) % n]);
                if count[&(p.min(q), p.max(q))] == 1 {
                    out.insert((i, v));
                    out.insert((i, (v + 1) % n));
                }
            }
        }
        let mut out: Vec<_> = out.into_iter().collect();
        out.sort_unstable();
        out
    }

    /// Signed area of every closed tile (positive: counter-clockwise).
    pub fn closed_areas(&self) -> Vec<Real> {
        (0..self.tiles.len())
            .map(|i| crate::geometry::signed_area(&self.closed_polygon(i)))
            .collect()
    }

    /// Largest distance between the two opened positions of a pinned node (units of the
    /// length scale): zero for an opened state that is a configuration of the sheet.
    pub fn joint_gap(&self) -> Real {
        self.joints
            .iter()
            .map(|j| {
                let pa = self.opened_corner(j.a, j.node);
                let pb = self.opened_corner(j.b, j.node);
                (pa - pb).norm()
            })
            .fold(0.0, Real::max)
    }

    /// Opened position of node `node` as a corner of tile `i`.
    pub fn opened_corner(&self, i: usize, node: usize) -> Vec2 {
        let t = &self.tiles[i];
        let pose = self.opened[i];
        Vec2::new(pose.x, pose.y) + rotation(pose.theta) * (self.node(node) - self.node(t.nodes[0]))
    }

    /// Checks sizes, indices and finiteness (a sheet read from a file).
    pub fn validate(&self) -> Result<(), GradedError> {
        let bad = |m: String| Err(GradedError::BadSheet(m));
        if self.tiles.is_empty() {
            return bad("it has no tiles".into());
        }
        if self.opened.len() != self.tiles.len() {
            return bad(format!(
                "{} opened poses for {} tiles",
                self.opened.len(),
                self.tiles.len()
            ));
        }
        if !(self.length_scale.is_finite() && self.length_scale > 0.0) {
            return bad("its length scale is not a positive number".into());
        }
        if let Some(k) = self
            .nodes
            .iter()
            .position(|p| !p.iter().all(|v| v.is_finite()))
        {
            return bad(format!("node {k} is not finite"));
        }
        for poses in self.path.iter().chain(std::iter::once(&self.opened)) {
            if poses.len() != self.tiles.len() {
                return bad(format!(
                    "a state has {} poses for {} tiles",
                    poses.len(),
                    self.tiles.len()
                ));
            }
            if let Some(k) = poses
                .iter()
                .position(|p| !(p.x.is_finite() && p.y.is_finite() && p.theta.is_finite()))
            {
                return bad(format!("the pose of tile {k} is not finite"));
            }
        }
        for (i, t) in self.tiles.iter().enumerate() {
            if t.nodes.len() < 3 {
                return bad(format!("tile {i} has fewer than three corners"));
            }
            if let Some(&n) = t.nodes.iter().find(|&&n| n >= self.nodes.len()) {
                return bad(format!("tile {i} names node {n}, which does not exist"));
            }
        }
        for (k, j) in self.joints.iter().enumerate() {
            let tiles = self.tiles.len();
            if j.a >= tiles || j.b >= tiles || j.a == j.b {
                return bad(format!("joint {k} does not join two of the tiles"));
            }
            if !self.tiles[j.a].nodes.contains(&j.node) || !self.tiles[j.b].nodes.contains(&j.node)
            {
                return bad(format!(
                    "joint {k}'s node is not a corner of both its tiles"
                ));
            }
        }
        Ok(())
    }
}

/// The pose of every tile of `sheet` at the periodic state `q` of `mech`: the position of its
/// first corner and its rotation from the closed state.
fn periodic_poses(mech: &Mechanism, sheet: &FiniteSheet, q: &crate::math::DVec) -> Vec<OpenedPose> {
    sheet
        .tiles
        .iter()
        .map(|t| {
            let first = mech.tile_polygon(q, t.tile, t.cell)[0];
            let theta = mech.pose(q, t.tile).1 - mech.pose(&mech.rest, t.tile).1;
            OpenedPose {
                x: first.x,
                y: first.y,
                theta,
            }
        })
        .collect()
}

/// The finite sheet of `rows × cols` cells of a design.
pub fn region_sheet(
    cell: &UnitCell,
    mech: &Mechanism,
    rows: usize,
    cols: usize,
) -> Result<FiniteSheet, GradedError> {
    let tiles = Region::Cells { rows, cols }
        .tiles(mech, 1.0)
        .map_err(|e| GradedError::BadRegion(e.to_string()))?;
    Ok(FiniteSheet::new(cell, mech, tiles))
}

/// Twice the signed area of the triangle (prev, at, next): cross(next − at, prev − at).
pub(crate) fn corner_cross(prev: Vec2, at: Vec2, next: Vec2) -> Real {
    cross(&(next - at), &(prev - at))
}

/// Sine of the corner at `at` between its edges to `next` and `prev`, counter-clockwise
/// positive (a convex corner of a counter-clockwise polygon); 0 for a degenerate edge.
pub(crate) fn corner_sine(prev: Vec2, at: Vec2, next: Vec2) -> Real {
    let (a, b) = (next - at, prev - at);
    let lengths = a.norm() * b.norm();
    if lengths > 0.0 {
        cross(&a, &b) / lengths
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::resolve_design;

    fn ungraded_at_rest(spec: &str) -> GradedSheet {
        let design = resolve_design(spec).unwrap();
        let cell = design.cell().unwrap();
        let mech = Mechanism::new(&cell, &design.joints).unwrap();
        let sheet = region_sheet(&cell, &mech, 3, 3).unwrap();
        GradedSheet::ungraded(spec, &cell, &mech, &sheet, &mech.rest).unwrap()
    }

    /// Nodes, tile corners and pins come from the cell's combinatorics: a shape a hair away
    /// gives the same graded sheet, its nodes a hair away; every pin joins two tiles at a
    /// node both have, and shared nodes are shared by position too.
    #[test]
    fn a_shape_a_hair_away_is_the_same_graded_sheet() {
        let a = ungraded_at_rest("IH6:0.12239750492,0.5,0.225335752741,0.625,0.5:1x1:-a-aaaaaaa--");
        let b = ungraded_at_rest("IH6:0.12239750592,0.5,0.225335752741,0.625,0.5:1x1:-a-aaaaaaa--");
        assert!(a.validate().is_ok());
        assert_eq!(a.tiles, b.tiles);
        assert_eq!(a.joints, b.joints);
        assert_eq!(a.nodes.len(), b.nodes.len());
        for (p, q) in a.nodes.iter().zip(&b.nodes) {
            assert!(
                (p[0] - q[0]).abs() + (p[1] - q[1]).abs() < 1e-7,
                "{p:?} {q:?}"
            );
        }
        // Every tile's closed corner sits at its node: the closed polygons are the cell's.
        let design = resolve_design(&a.design).unwrap();
        let cell = design.cell().unwrap();
        let mech = Mechanism::new(&cell, &design.joints).unwrap();
        for (i, t) in a.tiles.iter().enumerate() {
            let poly = mech.tile_polygon(&mech.rest, t.tile, t.cell);
            for (p, q) in poly.iter().zip(a.closed_polygon(i)) {
                assert!((p - q).norm() < 1e-12);
            }
        }
        assert!(a.joint_gap() < 1e-12, "closed, every pin closes");
        assert!(a.nodes.len() < a.tiles.iter().map(|t| t.nodes.len()).sum::<usize>());
    }
}

//! A finite sheet: some tiles of the periodic sheet and only the joints between two of them.
//!
//! A tile of the infinite sheet is named combinatorially, by its tile index in the design's
//! cell and the integer cell it sits in ([`SheetTile`]); a joint of the sheet is one of the
//! mechanism's joints between two such tiles, found by integer arithmetic on the cell
//! edge's offset. Geometry never decides which tile or joint is which.

use crate::cell::UnitCell;
use crate::disjoint_sets::DisjointSets;
use crate::geometry::signed_area;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real, Vec2};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// One tile of the infinite sheet: tile `tile` of the design's cell, in the cell copy at
/// `cell[0]·u + cell[1]·w`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct SheetTile {
    /// Cell copy (multiples of u and w).
    pub cell: [i32; 2],
    /// Tile index in the cell.
    pub tile: usize,
}

/// A pin joint of the sheet.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct SheetJoint {
    /// Index in [`FiniteSheet::tiles`] of the tile on the cell edge's first side.
    pub a: usize,
    /// Index of the tile on the other side.
    pub b: usize,
    /// Index of the joint in the design's mechanism ([`Mechanism::joints`]).
    pub joint: usize,
}

/// Tiles of the periodic sheet and every joint between two of them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FiniteSheet {
    /// The tiles, sorted by cell (row by row: `cell[1]`, then `cell[0]`) then tile index.
    pub tiles: Vec<SheetTile>,
    /// Every joint of the design whose two tiles are both in the sheet.
    pub joints: Vec<SheetJoint>,
}

impl FiniteSheet {
    /// The sheet of `tiles` (duplicates dropped) with every joint of `mech` between two of
    /// them. `cell` is the cell `mech` was assembled from.
    pub fn new(
        cell: &UnitCell,
        mech: &Mechanism,
        tiles: impl IntoIterator<Item = SheetTile>,
    ) -> Self {
        let mut tiles: Vec<SheetTile> = tiles.into_iter().collect();
        tiles.sort_by_key(|t| (t.cell[1], t.cell[0], t.tile));
        tiles.dedup();
        let index: HashMap<SheetTile, usize> =
            tiles.iter().enumerate().map(|(i, t)| (*t, i)).collect();
        let mut joints = Vec::new();
        for (a, ta) in tiles.iter().enumerate() {
            for (j, joint) in mech.joints.iter().enumerate() {
                if joint.tile_a != ta.tile {
                    continue;
                }
                let o = cell.edges[joint.edge].offset;
                let partner = SheetTile {
                    cell: [ta.cell[0] + o[0], ta.cell[1] + o[1]],
                    tile: joint.tile_b,
                };
                if let Some(&b) = index.get(&partner) {
                    joints.push(SheetJoint { a, b, joint: j });
                }
            }
        }
        FiniteSheet { tiles, joints }
    }

    /// The sheet of the tiles whose `keep` flag is set (indexed like [`FiniteSheet::tiles`]).
    pub fn keep(&self, cell: &UnitCell, mech: &Mechanism, keep: &[bool]) -> FiniteSheet {
        FiniteSheet::new(
            cell,
            mech,
            self.tiles
                .iter()
                .zip(keep)
                .filter(|(_, &k)| k)
                .map(|(t, _)| *t),
        )
    }

    /// Number of tiles.
    pub fn len(&self) -> usize {
        self.tiles.len()
    }

    /// True when the sheet has no tiles.
    pub fn is_empty(&self) -> bool {
        self.tiles.is_empty()
    }

    /// Pins holding each tile.
    pub fn pins(&self) -> Vec<usize> {
        let mut pins = vec![0; self.tiles.len()];
        for j in &self.joints {
            pins[j.a] += 1;
            pins[j.b] += 1;
        }
        pins
    }

    /// The piece (connected component of the tile/joint graph) of every tile, numbered from
    /// 0 by the lowest tile index in it, and the number of pieces.
    pub fn pieces(&self) -> (Vec<usize>, usize) {
        let n = self.tiles.len();
        let mut sets = DisjointSets::new(n);
        for j in &self.joints {
            sets.union(j.a, j.b);
        }
        let mut label = vec![usize::MAX; n];
        let mut piece = vec![0; n];
        let mut count = 0;
        for (i, slot) in piece.iter_mut().enumerate() {
            let r = sets.find(i);
            if label[r] == usize::MAX {
                label[r] = count;
                count += 1;
            }
            *slot = label[r];
        }
        (piece, count)
    }

    /// Whether each tile is in the largest piece (the piece of the lowest tile on a tie).
    pub fn in_largest_piece(&self) -> Vec<bool> {
        let (piece, count) = self.pieces();
        let mut size = vec![0usize; count];
        for &p in &piece {
            size[p] += 1;
        }
        let largest = (0..count).max_by(|&a, &b| size[a].cmp(&size[b]).then(b.cmp(&a)));
        piece.iter().map(|&p| Some(p) == largest).collect()
    }

    /// Pose (position in units of L, angle) of every tile at the periodic state `q` of
    /// `mech`: tile k's pose moved by its cell's lattice translate.
    pub fn poses(&self, mech: &Mechanism, q: &DVec) -> Vec<(Vec2, Real)> {
        let (u, w) = mech.lattice(q);
        self.tiles
            .iter()
            .map(|t| {
                let (p, th) = mech.pose(q, t.tile);
                (
                    p + u * Real::from(t.cell[0]) + w * Real::from(t.cell[1]),
                    th,
                )
            })
            .collect()
    }

    /// Area of every tile (units of L²).
    pub fn areas(&self, mech: &Mechanism) -> Vec<Real> {
        self.tiles
            .iter()
            .map(|t| signed_area(&mech.tile_shapes[t.tile]).abs())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::resolve_design;

    #[test]
    fn a_rectangle_of_rotating_squares_has_every_inner_joint_once() {
        let design = resolve_design("rotating-squares").unwrap();
        let cell = design.cell().unwrap();
        let mech = Mechanism::new(&cell, &design.joints).unwrap();
        let n = cell.tiles.len();
        let tiles = (0..3).flat_map(|j| {
            (0..3).flat_map(move |i| {
                (0..n).map(move |k| SheetTile {
                    cell: [i, j],
                    tile: k,
                })
            })
        });
        let sheet = FiniteSheet::new(&cell, &mech, tiles);
        assert_eq!(sheet.len(), 9 * n);
        // Every pin of the periodic sheet joins two squares; a 6×6 block of squares has
        // 2·6·5 shared corners.
        assert_eq!(sheet.joints.len(), 60);
        let (_, pieces) = sheet.pieces();
        assert_eq!(pieces, 1);
        let pins = sheet.pins();
        assert_eq!(pins.iter().filter(|&&p| p == 2).count(), 4, "corners");
    }
}

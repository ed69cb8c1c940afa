//! The periodic tile–joint graph of a design, embedded in the plane by the tile geometry.
//!
//! Nodes are the tiles of the cell; a node stands for every translate of its tile. Each pin
//! joint gives two darts (one leaving each of its tiles) carrying the cell offset of the tile it
//! leads to. The darts leaving a tile are ordered counter-clockwise by where their joints sit on
//! the tile's boundary: that rotation system is the sheet's planar embedding, from which the
//! faces (holes) are traced.

use crate::cell::{End, UnitCell};
use crate::topology::JointChoice;
use std::collections::BTreeSet;

/// One side of a pin joint: from a tile to the tile it is pinned to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Dart {
    /// The tile it leaves.
    pub from: usize,
    /// The tile it leads to.
    pub to: usize,
    /// Cell offset of `to` relative to `from`.
    pub offset: [i32; 2],
    /// The unique edge of the cell the joint sits on.
    pub edge: usize,
    /// Which end of that edge.
    pub end: End,
    /// True for the side leaving the edge's `tile_a` (the cell edge's own orientation).
    pub forward: bool,
    /// Position of the joint on `from`'s boundary: 2·(edge index on `from`) + 0 at the edge's
    /// start vertex or + 1 at its end vertex. Increasing keys run counter-clockwise.
    pub key: usize,
    /// The opposite dart of the same joint.
    pub rev: usize,
}

/// The embedded periodic graph.
#[derive(Debug, Clone, Default)]
pub(crate) struct Sheet {
    /// The darts, in pairs (2k, 2k+1) for joint k.
    pub darts: Vec<Dart>,
    /// For each tile, the darts leaving it in counter-clockwise order.
    pub rotation: Vec<Vec<usize>>,
}

impl Sheet {
    /// Builds the graph of `cell` with `joints` (one choice per unique edge; the caller has
    /// checked the length). A `Both` edge gives two joints (a weld).
    pub fn new(cell: &UnitCell, joints: &[JointChoice]) -> Sheet {
        let mut darts = Vec::new();
        for (k, (e, choice)) in cell.edges.iter().zip(joints).enumerate() {
            for &end in choice.ends() {
                let (sa, sb) = match end {
                    End::A => (0, 1),
                    End::B => (1, 0),
                };
                let i = darts.len();
                darts.push(Dart {
                    from: e.tile_a,
                    to: e.tile_b,
                    offset: e.offset,
                    edge: k,
                    end,
                    forward: true,
                    key: 2 * e.edge_a + sa,
                    rev: i + 1,
                });
                darts.push(Dart {
                    from: e.tile_b,
                    to: e.tile_a,
                    offset: [-e.offset[0], -e.offset[1]],
                    edge: k,
                    end,
                    forward: false,
                    key: 2 * e.edge_b + sb,
                    rev: i,
                });
            }
        }
        Sheet::from_darts(cell.tiles.len(), darts)
    }

    /// Builds the rotation system from darts whose `key`s order them around each tile.
    pub fn from_darts(tiles: usize, darts: Vec<Dart>) -> Sheet {
        let mut rotation = vec![Vec::new(); tiles];
        for (i, d) in darts.iter().enumerate() {
            rotation[d.from].push(i);
        }
        for r in &mut rotation {
            r.sort_by_key(|&i| darts[i].key);
        }
        Sheet { darts, rotation }
    }

    /// Distinct neighbours (tile, relative cell offset) of every tile on the infinite sheet:
    /// parallel joints (a welded `Both` edge, or two edges shared with the same neighbour)
    /// count once.
    pub fn neighbours(&self) -> Vec<BTreeSet<(usize, [i32; 2])>> {
        let mut out = vec![BTreeSet::new(); self.rotation.len()];
        for d in &self.darts {
            out[d.from].insert((d.to, d.offset));
        }
        out
    }
}

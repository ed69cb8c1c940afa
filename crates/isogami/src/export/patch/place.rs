//! Placing a patch in millimetres: every tile by its frame's pose, the joints between the
//! placed tiles, and the sheet's outline.

use super::{PatchJoint, PatchTile};
use crate::cell::End;
use crate::deploy::FrameReport;
use crate::export::outline::chain_loops;
use crate::finite::{FiniteSheet, SheetTile};
use crate::math::Real;
use std::collections::HashMap;

/// Places the cell's tile shapes by a frame's poses at the sheet's tiles.
pub(super) struct Placer<'a> {
    shapes: &'a [Vec<[Real; 2]>],
    pub(super) tiles: &'a [SheetTile],
    index: HashMap<SheetTile, usize>,
}

impl<'a> Placer<'a> {
    pub(super) fn new(shapes: &'a [Vec<[Real; 2]>], tiles: &'a [SheetTile]) -> Self {
        let index = tiles.iter().enumerate().map(|(i, t)| (*t, i)).collect();
        Placer {
            shapes,
            tiles,
            index,
        }
    }

    /// Tile id of tile `tile` in `cell`, if it is in the sheet.
    pub(super) fn id(&self, cell: [i32; 2], tile: usize) -> Option<usize> {
        self.index.get(&SheetTile { cell, tile }).copied()
    }

    /// Translation of `cell` at a frame (tiling units).
    pub(super) fn shift(&self, frame: &FrameReport, cell: [i32; 2]) -> [Real; 2] {
        let (i, j) = (Real::from(cell[0]), Real::from(cell[1]));
        [
            i * frame.u[0] + j * frame.w[0],
            i * frame.u[1] + j * frame.w[1],
        ]
    }

    /// Every tile polygon of the sheet at a frame, by tile id (tiling units).
    pub(super) fn polygons(&self, frame: &FrameReport) -> Vec<Vec<[Real; 2]>> {
        self.tiles
            .iter()
            .map(|t| {
                let s = self.shift(frame, t.cell);
                let pose = &frame.tiles[t.tile];
                let (sin, cos) = pose.theta.sin_cos();
                self.shapes[t.tile]
                    .iter()
                    .map(|p| {
                        [
                            pose.x + cos * p[0] - sin * p[1] + s[0],
                            pose.y + sin * p[0] + cos * p[1] + s[1],
                        ]
                    })
                    .collect()
            })
            .collect()
    }
}

/// Lower and upper corners of the bounding box of polygons.
pub(super) fn bounds(polys: &[Vec<[Real; 2]>]) -> ([Real; 2], [Real; 2]) {
    let (mut lo, mut hi) = ([Real::INFINITY; 2], [Real::NEG_INFINITY; 2]);
    for v in polys.iter().flatten() {
        for d in 0..2 {
            lo[d] = lo[d].min(v[d]);
            hi[d] = hi[d].max(v[d]);
        }
    }
    (lo, hi)
}

pub(super) fn mm(v: [Real; 2], lo: [Real; 2], scale: Real) -> [Real; 2] {
    [(v[0] - lo[0]) * scale, (v[1] - lo[1]) * scale]
}

/// Every joint of the sheet, with its pin's place at the exported state.
pub(super) fn patch_joints(
    cell: &crate::cell::UnitCell,
    mech: &crate::kinematics::Mechanism,
    sheet: &FiniteSheet,
    tiles: &[PatchTile],
) -> Vec<PatchJoint> {
    sheet
        .joints
        .iter()
        .map(|j| {
            let joint = &mech.joints[j.joint];
            let vertex_a = cell.endpoint_index_on_a(joint.edge, joint.end);
            PatchJoint {
                a: j.a,
                b: j.b,
                point_mm: tiles[j.a].polygon_mm[vertex_a],
                edge: joint.edge,
                end: if joint.end == End::A { 'a' } else { 'b' },
                vertex_a,
                vertex_b: cell.endpoint_index_on_b(joint.edge, joint.end),
            }
        })
        .collect()
}

/// Boundary loops of the closed patch: tile edges whose neighbour is outside the patch.
pub(super) fn outline(
    cell: &crate::cell::UnitCell,
    place: &Placer<'_>,
    closed: &[Vec<[Real; 2]>],
    tol: Real,
) -> Vec<Vec<([Real; 2], [usize; 2])>> {
    outline_loops(
        closed,
        |id, k| {
            let SheetTile { cell: c, tile } = place.tiles[id];
            let e = &cell.edges[cell.tile_edges[tile][k]];
            let (other, offset) = if e.tile_a == tile && e.edge_a == k {
                (e.tile_b, e.offset)
            } else {
                (e.tile_a, [-e.offset[0], -e.offset[1]])
            };
            place
                .id([c[0] + offset[0], c[1] + offset[1]], other)
                .is_none()
        },
        tol,
    )
}

/// Boundary loops of closed tile polygons: edge `k` of tile `id` (from vertex k to k + 1) is
/// on the boundary when `on_boundary(id, k)`; those edges are chained into loops of (start,
/// [tile id, vertex index]) (see `chain_loops`).
pub(super) fn outline_loops(
    closed: &[Vec<[Real; 2]>],
    on_boundary: impl Fn(usize, usize) -> bool,
    tol: Real,
) -> Vec<Vec<([Real; 2], [usize; 2])>> {
    let mut edges = Vec::new();
    for (id, poly) in closed.iter().enumerate() {
        for k in 0..poly.len() {
            if on_boundary(id, k) {
                edges.push(([poly[k], poly[(k + 1) % poly.len()]], [id, k]));
            }
        }
    }
    chain_loops(&edges, tol)
}

/// Polygons scaled to millimetres, shifted so that their bounding box starts at (0, 0).
pub(super) fn polygons_mm(polys: &[Vec<[Real; 2]>], mm_per_unit: Real) -> Vec<Vec<[Real; 2]>> {
    let (lo, _) = bounds(polys);
    polys
        .iter()
        .map(|p| p.iter().map(|v| mm(*v, lo, mm_per_unit)).collect())
        .collect()
}

/// The loops' points and their [tile id, vertex index] labels, apart.
pub(super) type Loops = (Vec<Vec<[Real; 2]>>, Vec<Vec<[usize; 2]>>);

/// Splits outline loops into their points and their labels.
pub(super) fn split_loops(loops: &[Vec<([Real; 2], [usize; 2])>]) -> Loops {
    let points = loops
        .iter()
        .map(|l| l.iter().map(|(p, _)| *p).collect())
        .collect();
    let labels = loops
        .iter()
        .map(|l| l.iter().map(|(_, v)| *v).collect())
        .collect();
    (points, labels)
}

/// True when every coordinate of every polygon is finite.
pub(super) fn all_finite<'a>(polys: impl IntoIterator<Item = &'a Vec<[Real; 2]>>) -> bool {
    polys
        .into_iter()
        .all(|p| p.iter().flatten().all(|x| x.is_finite()))
}

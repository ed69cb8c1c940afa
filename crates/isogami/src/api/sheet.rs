//! What a front end needs to draw a design and edit its joints: each tile's polygon in its
//! own frame (placed by a report frame's [`TilePose`](crate::deploy::TilePose)), the cell's
//! unique edges with their closed-state endpoints and joint choices, and which linkages each
//! tile belongs to. Plain data, in the tiling's units like the deployment report.

use super::assemble;
use crate::cell::CellDims;
use crate::error::Result;
use crate::linkage::LinkageAnalysis;
use crate::math::Real;
use crate::topology::Design;
use serde::Serialize;

/// The drawable geometry of a design's cell in its closed state.
///
/// A tile copy in cell (i, j) of a deployment frame has its vertices at
/// `(pose.x, pose.y) + R(pose.theta)·p + i·u + j·w`, with p from [`SheetGeometry::tiles`] and u, w,
/// pose from the frame.
#[derive(Debug, Clone, Serialize)]
pub struct SheetGeometry {
    /// Family name, e.g. "IH28".
    pub family: String,
    /// Shape parameters.
    pub params: Vec<Real>,
    /// Supercell size [a, b].
    pub cell: CellDims,
    /// Mean edge length L (tiling units): kerfs and clearances are relative to it.
    pub length_scale: Real,
    /// Tiling vector u of the closed state (tiling units).
    pub u: [Real; 2],
    /// Tiling vector w of the closed state (tiling units).
    pub w: [Real; 2],
    /// Each tile's polygon about its centroid, in its own closed-state frame, counter-clockwise
    /// (tiling units).
    pub tiles: Vec<Vec<[Real; 2]>>,
    /// The cell's unique edges, in the order of the spec's joint string.
    pub edges: Vec<EdgeGeometry>,
}

/// One unique edge of the cell and its joint.
#[derive(Debug, Clone, Serialize)]
pub struct EdgeGeometry {
    /// Tile on one side (in cell 0).
    pub tile_a: usize,
    /// Edge index on `tile_a` (vertex `edge_a` → `edge_a + 1`).
    pub edge_a: usize,
    /// Tile on the other side.
    pub tile_b: usize,
    /// Edge index on `tile_b`.
    pub edge_b: usize,
    /// Cell offset (k_u, k_w) of `tile_b`'s copy.
    pub offset: [i32; 2],
    /// Endpoint A in the closed state (tiling units, `tile_a` in cell 0).
    pub a: [Real; 2],
    /// Endpoint B in the closed state.
    pub b: [Real; 2],
    /// Joint choice: `-` none, `a` or `b` a pin at that end, `x` both (welded).
    pub joint: char,
}

/// The drawable geometry of `design` (fails as deployment would on a design that does not
/// build: invalid parameters, unsupported cell, wrong joint count).
pub fn sheet_geometry(design: &Design) -> Result<SheetGeometry> {
    let (cell, mech) = assemble(design)?;
    let l = mech.length_scale;
    let tiles = mech
        .tile_shapes
        .iter()
        .map(|shape| shape.iter().map(|p| [p.x * l, p.y * l]).collect())
        .collect();
    let edges = cell
        .edges
        .iter()
        .zip(&design.joints)
        .enumerate()
        .map(|(k, (e, joint))| {
            let a = cell.endpoint(k, crate::cell::End::A);
            let b = cell.endpoint(k, crate::cell::End::B);
            EdgeGeometry {
                tile_a: e.tile_a,
                edge_a: e.edge_a,
                tile_b: e.tile_b,
                edge_b: e.edge_b,
                offset: e.offset,
                a: [a.x, a.y],
                b: [b.x, b.y],
                joint: joint.to_char(),
            }
        })
        .collect();
    Ok(SheetGeometry {
        family: design.family.to_string(),
        params: design.params.clone(),
        cell: design.dims,
        length_scale: l,
        u: [cell.u.x, cell.u.y],
        w: [cell.w.x, cell.w.y],
        tiles,
        edges,
    })
}

/// For each of the cell's `tiles` tiles, the indices in `analysis.linkages` of every linkage that
/// runs through one of its copies, ascending (empty when none does).
///
/// A tile is often a bar of several linkages (in `IH16:0.216506350946:1x1:-a-a-aaaa` every tile
/// is in all three 4-bars), so a tile's linkage is a set, not one index: front ends colour a
/// tile by its linkage only when the set has one element, and draw the linkages themselves as
/// loops through their joints (paper Fig. 6).
pub fn tile_linkages(analysis: &LinkageAnalysis, tiles: usize) -> Vec<Vec<usize>> {
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); tiles];
    for (index, linkage) in analysis.linkages.iter().enumerate() {
        for &(tile, _) in &linkage.nodes {
            if let Some(set) = out.get_mut(tile) {
                if set.last() != Some(&index) {
                    set.push(index);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::{deploy, linkages, resolve_design, DeployRequest};
    use crate::math::{rotation, Vec2};

    /// Placing each tile polygon by a frame's pose reproduces the cell's tiles: at the closed
    /// state exactly the closed tiles, and at every frame polygons whose pinned vertices meet.
    #[test]
    fn poses_place_the_polygons_where_the_cell_has_them() {
        for spec in crate::topology::SAMPLE_OPENING_DESIGNS.iter().take(4) {
            let design = resolve_design(spec).unwrap();
            let g = sheet_geometry(&design).unwrap();
            let cell = design.cell().unwrap();
            let run = deploy(&design, &DeployRequest::default(), &mut |_| true).unwrap();
            let place = |frame: usize, tile: usize, cellk: [i32; 2]| -> Vec<Vec2> {
                let f = &run.report.frames[frame];
                let pose = f.tiles[tile];
                let r = rotation(pose.theta);
                let shift = Vec2::new(f.u[0], f.u[1]) * Real::from(cellk[0])
                    + Vec2::new(f.w[0], f.w[1]) * Real::from(cellk[1]);
                g.tiles[tile]
                    .iter()
                    .map(|p| Vec2::new(pose.x, pose.y) + r * Vec2::new(p[0], p[1]) + shift)
                    .collect()
            };
            let tol = 1e-9 * g.length_scale;
            for (i, tile) in cell.tiles.iter().enumerate() {
                for (p, q) in place(0, i, [0, 0]).iter().zip(&tile.polygon) {
                    assert!((p - q).norm() < tol, "{spec}: tile {i} closed");
                }
            }
            let last = run.report.frames.len() - 1;
            assert!(run.report.frames[last].t > 0.5);
            for (k, e) in g.edges.iter().enumerate() {
                if e.joint != 'a' && e.joint != 'b' {
                    continue;
                }
                let end = if e.joint == 'a' {
                    crate::cell::End::A
                } else {
                    crate::cell::End::B
                };
                let ia = cell.endpoint_index_on_a(k, end);
                let ib = cell.endpoint_index_on_b(k, end);
                let pa = place(last, e.tile_a, [0, 0])[ia];
                let pb = place(last, e.tile_b, e.offset)[ib];
                assert!(
                    (pa - pb).norm() < 1e-6 * g.length_scale,
                    "{spec}: joint {k} open"
                );
            }
        }
    }

    #[test]
    fn every_tile_of_rotating_squares_is_in_a_four_bar() {
        let design = resolve_design("rotating-squares").unwrap();
        let analysis = linkages(&design).unwrap();
        let tiles = design.cell().unwrap().tiles.len();
        let by_tile = tile_linkages(&analysis, tiles);
        assert_eq!(by_tile.len(), tiles);
        for set in by_tile {
            assert!(!set.is_empty(), "every tile is in a linkage");
            for k in set {
                assert_eq!(analysis.linkages[k].bars, 4);
            }
        }
    }

    /// Issue 24 item 5: a tile in several linkages lists them all (the old answer, the smallest
    /// one, coloured every IH16 tile "linkage 0"), each listed linkage runs through the tile,
    /// and every linkage through a tile is listed.
    #[test]
    fn a_tile_lists_every_linkage_through_it() {
        let design = resolve_design("IH16:0.216506350946:1x1:-a-a-aaaa").unwrap();
        let analysis = linkages(&design).unwrap();
        assert_eq!(analysis.linkages.len(), 3);
        let tiles = design.cell().unwrap().tiles.len();
        let by_tile = tile_linkages(&analysis, tiles);
        for (tile, set) in by_tile.iter().enumerate() {
            let want: Vec<usize> = (0..analysis.linkages.len())
                .filter(|&k| analysis.linkages[k].nodes.iter().any(|n| n.0 == tile))
                .collect();
            assert_eq!(set, &want, "tile {tile}");
        }
        assert!(by_tile.iter().all(|set| set.len() == 3));
    }
}

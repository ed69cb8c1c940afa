//! Building a cell from a tiling: tile placement and geometric edge matching.

use super::dims::CellDims;
use super::error::{CellError, GeometryProblem};
use crate::geometry::{centroid, signed_area};
use crate::math::{cross, rotation, Real, Vec2};
use crate::tiling::{Family, Tiling};
use serde::Serialize;

/// Relative tolerance (times the mean edge length) for matching shared vertices.
const MATCH_REL_TOL: Real = 1e-7;

/// One tile of the cell in the closed state.
#[derive(Debug, Clone, Serialize)]
pub struct Tile {
    /// Which aspect of the minimal cell this tile is.
    pub aspect: usize,
    /// Which copy of the minimal cell inside the supercell (multiples of t1, t2).
    pub copy: [u8; 2],
    /// Vertices, counter-clockwise, in world coordinates of the closed state.
    pub polygon: Vec<Vec2>,
    /// Area centroid (the tile's reference point).
    pub centroid: Vec2,
    /// For each tile edge k (vertex k → k+1), the prototile edge it comes from.
    pub proto_edges: Vec<usize>,
}

/// Which end of an edge a joint sits on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
pub enum End {
    /// The edge's first vertex on tile `tile_a` (counter-clockwise order).
    A,
    /// The edge's second vertex on tile `tile_a`.
    B,
}

/// A unique edge of the cell: edge `edge_a` of tile `tile_a` (in cell 0) coincides with edge
/// `edge_b` of tile `tile_b` in the cell at `offset` (multiples of u and w).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct CellEdge {
    /// First tile (always in cell 0).
    pub tile_a: usize,
    /// Edge index on the first tile (vertex `edge_a` → `edge_a + 1`).
    pub edge_a: usize,
    /// Neighbouring tile.
    pub tile_b: usize,
    /// Edge index on the neighbour; it runs the other way round.
    pub edge_b: usize,
    /// Cell offset (k_u, k_w) of the neighbour's copy.
    pub offset: [i32; 2],
}

/// A unit cell or supercell in the closed state.
#[derive(Debug, Clone, Serialize)]
pub struct UnitCell {
    /// The tiling family.
    pub family: Family,
    /// Shape parameters.
    pub params: Vec<Real>,
    /// Supercell size.
    pub dims: CellDims,
    /// The tiles.
    pub tiles: Vec<Tile>,
    /// Unique edges, each once.
    pub edges: Vec<CellEdge>,
    /// First tiling vector (a·t1).
    pub u: Vec2,
    /// Second tiling vector (b·t2).
    pub w: Vec2,
    /// `tile_edges[i][k]` is the unique edge index of edge k of tile i.
    pub tile_edges: Vec<Vec<usize>>,
}

impl UnitCell {
    /// Builds the a×b supercell of `tiling` and matches its edges.
    pub fn new(tiling: &Tiling, dims: CellDims) -> Result<UnitCell, CellError> {
        let (t1, t2) = (tiling.t1(), tiling.t2());
        let proto = tiling.prototile();
        let nv = proto.len();
        let basis_det = cross(&t1, &t2);
        let mut minimal = Vec::new();
        for (k, asp) in tiling.aspects().iter().enumerate() {
            let mut poly: Vec<Vec2> = proto.iter().map(|p| asp.apply(p)).collect();
            let mut proto_edges: Vec<usize> = (0..nv).collect();
            if signed_area(&poly) < 0.0 {
                // Reverse to counter-clockwise: tile vertex k becomes prototile vertex −k, and
                // tile edge k (k → k+1) is prototile edge −k−1.
                poly = (0..nv).map(|i| poly[(nv - i) % nv]).collect();
                proto_edges = (0..nv).map(|i| (2 * nv - i - 1) % nv).collect();
            }
            // Shift the tile so that its centroid lies in the fundamental parallelogram.
            let c = centroid(&poly);
            let alpha = (cross(&c, &t2) / basis_det + 1e-9).floor();
            let beta = (cross(&t1, &c) / basis_det + 1e-9).floor();
            let shift = t1 * alpha + t2 * beta;
            for p in &mut poly {
                *p -= shift;
            }
            minimal.push((k, poly, proto_edges));
        }
        let mut tiles = Vec::new();
        for j in 0..dims.b() {
            for i in 0..dims.a() {
                let shift = t1 * Real::from(i) + t2 * Real::from(j);
                for (k, poly, proto_edges) in &minimal {
                    let polygon: Vec<Vec2> = poly.iter().map(|p| p + shift).collect();
                    tiles.push(Tile {
                        aspect: *k,
                        copy: [i, j],
                        centroid: centroid(&polygon),
                        polygon,
                        proto_edges: proto_edges.clone(),
                    });
                }
            }
        }
        let u = t1 * Real::from(dims.a());
        let w = t2 * Real::from(dims.b());
        let (edges, tile_edges) = match_edges(&tiles, u, w)?;
        Ok(UnitCell {
            family: tiling.family(),
            params: tiling.params().to_vec(),
            dims,
            tiles,
            edges,
            u,
            w,
            tile_edges,
        })
    }

    /// Position of a joint candidate in the closed state (world coordinates, cell 0).
    pub fn endpoint(&self, edge: usize, end: End) -> Vec2 {
        let e = &self.edges[edge];
        let poly = &self.tiles[e.tile_a].polygon;
        match end {
            End::A => poly[e.edge_a],
            End::B => poly[(e.edge_a + 1) % poly.len()],
        }
    }

    /// Index of the same vertex on the neighbouring tile `tile_b`.
    pub fn endpoint_index_on_b(&self, edge: usize, end: End) -> usize {
        let e = &self.edges[edge];
        let nb = self.tiles[e.tile_b].polygon.len();
        match end {
            End::A => (e.edge_b + 1) % nb,
            End::B => e.edge_b,
        }
    }

    /// Index of the joint candidate vertex on tile `tile_a`.
    pub fn endpoint_index_on_a(&self, edge: usize, end: End) -> usize {
        let e = &self.edges[edge];
        let na = self.tiles[e.tile_a].polygon.len();
        match end {
            End::A => e.edge_a,
            End::B => (e.edge_a + 1) % na,
        }
    }

    /// Mean length of all tile edges: the cell's length scale.
    pub fn mean_edge_length(&self) -> Real {
        let (sum, count) = self.tiles.iter().fold((0.0, 0usize), |(s, c), t| {
            let n = t.polygon.len();
            let len: Real = (0..n)
                .map(|k| (t.polygon[(k + 1) % n] - t.polygon[k]).norm())
                .sum();
            (s + len, c + n)
        });
        sum / count as Real
    }

    /// Translation of cell offset (k_u, k_w).
    pub fn offset_vector(&self, offset: [i32; 2]) -> Vec2 {
        self.u * Real::from(offset[0]) + self.w * Real::from(offset[1])
    }

    /// Polygon of tile `tile` in the cell at `offset`.
    pub fn tile_polygon_at(&self, tile: usize, offset: [i32; 2]) -> Vec<Vec2> {
        let shift = self.offset_vector(offset);
        self.tiles[tile].polygon.iter().map(|p| p + shift).collect()
    }

    /// The same cell scaled by `scale` and rotated by `angle` about the origin. Used to check
    /// that results do not depend on units or orientation.
    pub fn transformed(&self, scale: Real, angle: Real) -> UnitCell {
        let r = rotation(angle) * scale;
        let mut out = self.clone();
        for t in &mut out.tiles {
            for p in &mut t.polygon {
                *p = r * *p;
            }
            t.centroid = r * t.centroid;
        }
        out.u = r * self.u;
        out.w = r * self.w;
        out
    }
}

/// Finds, for every tile edge, the single edge of another tile (possibly in a neighbouring
/// cell) with the same endpoints in reverse order.
fn match_edges(
    tiles: &[Tile],
    u: Vec2,
    w: Vec2,
) -> Result<(Vec<CellEdge>, Vec<Vec<usize>>), CellError> {
    let det = cross(&u, &w);
    let mean_len = {
        let (s, c) = tiles.iter().fold((0.0, 0usize), |(s, c), t| {
            let n = t.polygon.len();
            let l: Real = (0..n)
                .map(|k| (t.polygon[(k + 1) % n] - t.polygon[k]).norm())
                .sum();
            (s + l, c + n)
        });
        s / c as Real
    };
    let tol = MATCH_REL_TOL * mean_len;
    let ends = |t: &Tile, k: usize| (t.polygon[k], t.polygon[(k + 1) % t.polygon.len()]);
    let mut tile_edges: Vec<Vec<usize>> = tiles
        .iter()
        .map(|t| vec![usize::MAX; t.polygon.len()])
        .collect();
    let mut edges = Vec::new();
    for (i, ti) in tiles.iter().enumerate() {
        for k in 0..ti.polygon.len() {
            let (p, q) = ends(ti, k);
            let mut found: Vec<(usize, usize, [i32; 2])> = Vec::new();
            for (j, tj) in tiles.iter().enumerate() {
                for l in 0..tj.polygon.len() {
                    if i == j && k == l {
                        continue;
                    }
                    let (r, s) = ends(tj, l);
                    // Need r + o = q and s + o = p for a lattice translation o.
                    let o = q - r;
                    if (s + o - p).norm() > tol {
                        continue;
                    }
                    let ku = cross(&o, &w) / det;
                    let kw = cross(&u, &o) / det;
                    let (ru, rw) = (ku.round(), kw.round());
                    if (o - (u * ru + w * rw)).norm() <= tol {
                        found.push((j, l, [ru as i32, rw as i32]));
                    }
                }
            }
            if found.len() != 1 {
                return Err(CellError::Geometry(GeometryProblem::PartnerCount {
                    tile: i,
                    edge: k,
                    partners: found.len(),
                }));
            }
            let (j, l, offset) = found[0];
            match (
                tile_edges[i][k] == usize::MAX,
                tile_edges[j][l] == usize::MAX,
            ) {
                (true, true) => {
                    tile_edges[i][k] = edges.len();
                    tile_edges[j][l] = edges.len();
                    edges.push(CellEdge {
                        tile_a: i,
                        edge_a: k,
                        tile_b: j,
                        edge_b: l,
                        offset,
                    });
                }
                (false, false) if tile_edges[i][k] == tile_edges[j][l] => {}
                _ => {
                    return Err(CellError::Geometry(GeometryProblem::InconsistentMatch {
                        a: (i, k),
                        b: (j, l),
                    }))
                }
            }
        }
    }
    Ok((edges, tile_edges))
}

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
    /// Builds the a×b supercell of `tiling`: every tile placed by the family's fixed
    /// [`Structure`], every unique edge from the minimal cell's fixed adjacency, and the
    /// geometry checked against that table (each edge's two sides coincide at this shape).
    pub fn new(tiling: &Tiling, dims: CellDims) -> Result<UnitCell, CellError> {
        let structure = Structure::of(tiling.family())?;
        let (t1, t2) = (tiling.t1(), tiling.t2());
        let minimal = structure.place(tiling);
        let aspects = minimal.len();
        let mut tiles = Vec::with_capacity(aspects * usize::from(dims.a() * dims.b()));
        for j in 0..dims.b() {
            for i in 0..dims.a() {
                let shift = t1 * Real::from(i) + t2 * Real::from(j);
                for (k, (poly, proto_edges)) in minimal.iter().enumerate() {
                    let polygon: Vec<Vec2> = poly.iter().map(|p| p + shift).collect();
                    tiles.push(Tile {
                        aspect: k,
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
        let (edges, tile_edges) = structure.edges(&tiles, dims)?;
        let cell = UnitCell {
            family: tiling.family(),
            params: tiling.params().to_vec(),
            dims,
            tiles,
            edges,
            u,
            w,
            tile_edges,
        };
        cell.check_edges_meet()?;
        Ok(cell)
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

/// The edge a tile edge meets: (partner aspect, partner edge, cell offset of the partner in
/// multiples of t1, t2).
type Partner = (usize, usize, [i32; 2]);

/// The combinatorial structure of a family's minimal cell, the same at every shape: how each
/// aspect is placed (an integer lattice translate and whether its vertex order is reversed to
/// make it counter-clockwise) and, for every edge of every aspect, the partner edge and the
/// integer cell offset (in multiples of t1, t2) of the tile it meets.
///
/// It is read once from the family's default shape: there the translate brings the aspect's
/// centroid into the fundamental parallelogram, and the adjacency is found by matching edge
/// endpoints. Choosing the translates at each shape instead would let a floor() of a moving
/// centroid decide which lattice copy is "tile i", so the edge table — and the meaning of a
/// joint string — would jump where a centroid crosses the parallelogram's side.
pub(super) struct Structure {
    /// Per aspect: the lattice translate (multiples of t1, t2) subtracted from its image.
    pub(super) shifts: Vec<[i32; 2]>,
    /// Per aspect: whether its vertex order is reversed.
    reversed: Vec<bool>,
    /// Per aspect and tile edge: its partner.
    partners: Vec<Vec<Partner>>,
}

impl Structure {
    /// The structure of `family`, read at its default shape.
    pub(super) fn of(family: Family) -> Result<Structure, CellError> {
        let reference = Tiling::default_for(family);
        let (t1, t2) = (reference.t1(), reference.t2());
        let basis_det = cross(&t1, &t2);
        let proto = reference.prototile();
        let (mut shifts, mut reversed) = (Vec::new(), Vec::new());
        for asp in reference.aspects() {
            let poly: Vec<Vec2> = proto.iter().map(|p| asp.apply(p)).collect();
            let c = centroid(&poly);
            let alpha = (cross(&c, &t2) / basis_det + 1e-9).floor();
            let beta = (cross(&t1, &c) / basis_det + 1e-9).floor();
            shifts.push([alpha as i32, beta as i32]);
            reversed.push(signed_area(&poly) < 0.0);
        }
        let mut structure = Structure {
            shifts,
            reversed,
            partners: Vec::new(),
        };
        let polys: Vec<Vec<Vec2>> = structure
            .place(&reference)
            .into_iter()
            .map(|(poly, _)| poly)
            .collect();
        structure.partners = match_partners(&polys, t1, t2)?;
        Ok(structure)
    }

    /// The minimal cell's tiles at `tiling`'s shape: each aspect's counter-clockwise polygon
    /// and, per tile edge, the prototile edge it comes from.
    fn place(&self, tiling: &Tiling) -> Vec<(Vec<Vec2>, Vec<usize>)> {
        let (t1, t2) = (tiling.t1(), tiling.t2());
        let proto = tiling.prototile();
        let nv = proto.len();
        tiling
            .aspects()
            .iter()
            .enumerate()
            .map(|(k, asp)| {
                let mut poly: Vec<Vec2> = proto.iter().map(|p| asp.apply(p)).collect();
                let mut proto_edges: Vec<usize> = (0..nv).collect();
                if self.reversed[k] {
                    // Tile vertex i becomes prototile vertex −i, and tile edge i (i → i+1) is
                    // prototile edge −i−1.
                    poly = (0..nv).map(|i| poly[(nv - i) % nv]).collect();
                    proto_edges = (0..nv).map(|i| (2 * nv - i - 1) % nv).collect();
                }
                let [alpha, beta] = self.shifts[k];
                let shift = t1 * Real::from(alpha) + t2 * Real::from(beta);
                for p in &mut poly {
                    *p -= shift;
                }
                (poly, proto_edges)
            })
            .collect()
    }

    /// The unique edges of the a×b supercell whose tiles are `tiles` (copy-major, aspects
    /// inner), in order of their first tile edge, and each tile edge's unique edge: the minimal
    /// adjacency moved to every copy, its offset split into a copy inside the supercell and a
    /// whole-supercell offset. Pure integer arithmetic.
    #[allow(clippy::type_complexity)]
    fn edges(
        &self,
        tiles: &[Tile],
        dims: CellDims,
    ) -> Result<(Vec<CellEdge>, Vec<Vec<usize>>), CellError> {
        let aspects = self.partners.len();
        let (a, b) = (i32::from(dims.a()), i32::from(dims.b()));
        let mut tile_edges: Vec<Vec<usize>> = tiles
            .iter()
            .map(|t| vec![usize::MAX; t.polygon.len()])
            .collect();
        let mut edges = Vec::new();
        for (i, ti) in tiles.iter().enumerate() {
            for k in 0..ti.polygon.len() {
                let (aspect, l, o) = self.partners[ti.aspect][k];
                let (x, y) = (i32::from(ti.copy[0]) + o[0], i32::from(ti.copy[1]) + o[1]);
                let copy = (x.rem_euclid(a), y.rem_euclid(b));
                let offset = [x.div_euclid(a), y.div_euclid(b)];
                let j = (copy.1 * a + copy.0) as usize * aspects + aspect;
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
}

impl UnitCell {
    /// Checks that both sides of every unique edge meet at this shape: edge `edge_a` of tile
    /// `tile_a` runs from the end of edge `edge_b` of tile `tile_b` (moved by the offset) to
    /// its start, within [`MATCH_REL_TOL`] of the mean edge length.
    fn check_edges_meet(&self) -> Result<(), CellError> {
        let tol = MATCH_REL_TOL * self.mean_edge_length();
        for e in &self.edges {
            let (pa, pb) = (&self.tiles[e.tile_a].polygon, &self.tiles[e.tile_b].polygon);
            let shift = self.offset_vector(e.offset);
            let (p, q) = (pa[e.edge_a], pa[(e.edge_a + 1) % pa.len()]);
            let (r, s) = (pb[e.edge_b] + shift, pb[(e.edge_b + 1) % pb.len()] + shift);
            if (p - s).norm() > tol || (q - r).norm() > tol {
                return Err(CellError::Geometry(GeometryProblem::EdgesApart {
                    tile: e.tile_a,
                    edge: e.edge_a,
                    partner: (e.tile_b, e.edge_b),
                }));
            }
        }
        Ok(())
    }
}

/// For every edge of every minimal-cell tile, the single edge of a tile (possibly in a
/// neighbouring cell) with the same endpoints in reverse order, and that cell's offset in
/// multiples of t1, t2. Used once per family, at its default shape.
fn match_partners(polys: &[Vec<Vec2>], t1: Vec2, t2: Vec2) -> Result<Vec<Vec<Partner>>, CellError> {
    let det = cross(&t1, &t2);
    let (sum, count) = polys.iter().fold((0.0, 0usize), |(s, c), poly| {
        let n = poly.len();
        let l: Real = (0..n).map(|k| (poly[(k + 1) % n] - poly[k]).norm()).sum();
        (s + l, c + n)
    });
    let tol = MATCH_REL_TOL * sum / count as Real;
    let ends = |poly: &[Vec2], k: usize| (poly[k], poly[(k + 1) % poly.len()]);
    polys
        .iter()
        .enumerate()
        .map(|(i, pi)| {
            (0..pi.len())
                .map(|k| {
                    let (p, q) = ends(pi, k);
                    let mut found = Vec::new();
                    for (j, pj) in polys.iter().enumerate() {
                        for l in 0..pj.len() {
                            let (r, s) = ends(pj, l);
                            // Need r + o = q and s + o = p for a lattice translation o.
                            let o = q - r;
                            if (s + o - p).norm() > tol {
                                continue;
                            }
                            let k1 = (cross(&o, &t2) / det).round();
                            let k2 = (cross(&t1, &o) / det).round();
                            if (o - (t1 * k1 + t2 * k2)).norm() <= tol && (i, k) != (j, l) {
                                found.push((j, l, [k1 as i32, k2 as i32]));
                            }
                        }
                    }
                    match found[..] {
                        [one] => Ok(one),
                        _ => Err(CellError::Geometry(GeometryProblem::PartnerCount {
                            tile: i,
                            edge: k,
                            partners: found.len(),
                        })),
                    }
                })
                .collect()
        })
        .collect()
}

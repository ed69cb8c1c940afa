//! The edge graph of a patch of tiles: shared vertices, edges shared by two tiles (or on the
//! boundary, with one), the joints placed on edge ends, and the star of edges round each
//! vertex. Built from plain polygons by matching coordinates, so it serves any tile list
//! that forms a tiling without T-junctions (each edge has the same two endpoints on both
//! of its tiles).

use super::error::LaserError;
use super::JointAt;
use crate::geometry::signed_area;
use crate::math::{Real, Vec2};
use std::collections::HashMap;

/// One edge of the patch, oriented as its first tile traverses it (that tile on its left).
#[derive(Debug, Clone)]
pub(crate) struct Edge {
    /// Vertex ids of its ends.
    pub v: [usize; 2],
    /// Tile on the left.
    pub left: usize,
    /// Tile on the right, `None` on the patch boundary.
    pub right: Option<usize>,
    /// A joint sits at end 0 / end 1.
    pub joint: [bool; 2],
}

/// Vertices, edges and vertex stars of a patch.
#[derive(Debug, Clone)]
pub(crate) struct PatchGraph {
    /// Vertex positions (mm).
    pub points: Vec<Vec2>,
    /// Edges, each once.
    pub edges: Vec<Edge>,
    /// Per vertex, the ids of the edges that end there.
    pub star: Vec<Vec<usize>>,
    /// Per tile, the id of each of its edges (edge k runs from vertex k to k + 1).
    pub tile_edges: Vec<Vec<usize>>,
}

impl PatchGraph {
    /// The graph of `tiles` (counter-clockwise polygons, mm) with `joints` placed on their
    /// edges.
    pub fn new(tiles: &[Vec<[Real; 2]>], joints: &[JointAt]) -> Result<PatchGraph, LaserError> {
        if tiles.is_empty() {
            return Err(LaserError::NoTiles);
        }
        let polys = check_tiles(tiles)?;
        let extent = polys
            .iter()
            .flatten()
            .fold(1.0 as Real, |m, p| m.max(p.x.abs()).max(p.y.abs()));
        let tol = 1e-7 * extent;
        let mut ids = VertexIds::new(tol);
        let tile_vertices: Vec<Vec<usize>> = polys
            .iter()
            .map(|poly| poly.iter().map(|p| ids.id(*p)).collect())
            .collect();
        let mut edges: Vec<Edge> = Vec::new();
        let mut by_ends: HashMap<(usize, usize), usize> = HashMap::new();
        let mut tile_edges: Vec<Vec<usize>> = Vec::with_capacity(tiles.len());
        for (tile, verts) in tile_vertices.iter().enumerate() {
            let n = verts.len();
            let mut ids_of_tile = Vec::with_capacity(n);
            for k in 0..n {
                let (a, b) = (verts[k], verts[(k + 1) % n]);
                if a == b {
                    return Err(LaserError::BadTile {
                        tile,
                        problem: format!("edge {k} has zero length"),
                    });
                }
                let key = (a.min(b), a.max(b));
                match by_ends.get(&key) {
                    None => {
                        by_ends.insert(key, edges.len());
                        ids_of_tile.push(edges.len());
                        edges.push(Edge {
                            v: [a, b],
                            left: tile,
                            right: None,
                            joint: [false; 2],
                        });
                    }
                    Some(&e) => {
                        let edge = &mut edges[e];
                        if edge.right.is_some() || edge.v != [b, a] {
                            return Err(LaserError::Overlap {
                                tiles: [edge.left, tile],
                            });
                        }
                        edge.right = Some(tile);
                        ids_of_tile.push(e);
                    }
                }
            }
            tile_edges.push(ids_of_tile);
        }
        let mut star = vec![Vec::new(); ids.points.len()];
        for (e, edge) in edges.iter().enumerate() {
            star[edge.v[0]].push(e);
            star[edge.v[1]].push(e);
        }
        for (j, joint) in joints.iter().enumerate() {
            for &tile in &joint.tiles {
                if tile >= tiles.len() {
                    return Err(LaserError::NoSuchTile {
                        joint: j,
                        tile,
                        tiles: tiles.len(),
                    });
                }
            }
            let not_on_edge = LaserError::JointNotOnEdge {
                joint: j,
                tiles: joint.tiles,
            };
            let p = Vec2::new(joint.point[0], joint.point[1]);
            let Some(v) = ids.find(p) else {
                return Err(not_on_edge);
            };
            let [ta, tb] = joint.tiles;
            let found = star[v].iter().copied().find(|&e| {
                let e = &edges[e];
                e.right
                    .is_some_and(|r| (e.left == ta && r == tb) || (e.left == tb && r == ta))
            });
            let Some(e) = found else {
                return Err(not_on_edge);
            };
            let edge = &mut edges[e];
            let end = usize::from(edge.v[1] == v);
            edge.joint[end] = true;
        }
        Ok(PatchGraph {
            points: ids.points,
            edges,
            star,
            tile_edges,
        })
    }

    /// Position of vertex `v`.
    pub fn point(&self, v: usize) -> Vec2 {
        self.points[v]
    }

    /// Unit direction of edge `e` leaving vertex `v` (one of its ends), and its length.
    pub fn leaving(&self, e: usize, v: usize) -> (Vec2, Real) {
        let edge = &self.edges[e];
        let other = if edge.v[0] == v { edge.v[1] } else { edge.v[0] };
        let d = self.points[other] - self.points[v];
        let len = d.norm();
        (d / len, len)
    }
}

/// Tiles as vectors after checking they are finite, counter-clockwise and have three or more
/// vertices.
fn check_tiles(tiles: &[Vec<[Real; 2]>]) -> Result<Vec<Vec<Vec2>>, LaserError> {
    let mut out = Vec::with_capacity(tiles.len());
    for (tile, poly) in tiles.iter().enumerate() {
        if poly.len() < 3 {
            return Err(LaserError::BadTile {
                tile,
                problem: format!("{} vertices, fewer than three", poly.len()),
            });
        }
        if let Some(bad) = poly.iter().flatten().find(|c| !c.is_finite()) {
            return Err(LaserError::NotFinite {
                name: "tile coordinate",
                value: *bad,
            });
        }
        let pts: Vec<Vec2> = poly.iter().map(|p| Vec2::new(p[0], p[1])).collect();
        if signed_area(&pts) <= 0.0 {
            return Err(LaserError::BadTile {
                tile,
                problem: "not counter-clockwise".into(),
            });
        }
        out.push(pts);
    }
    Ok(out)
}

/// Vertex ids by position: points closer than `tol` share an id (hash grid of cell `tol`).
struct VertexIds {
    tol: Real,
    points: Vec<Vec2>,
    grid: HashMap<(i64, i64), Vec<usize>>,
}

impl VertexIds {
    fn new(tol: Real) -> Self {
        VertexIds {
            tol,
            points: Vec::new(),
            grid: HashMap::new(),
        }
    }

    fn cell(&self, p: Vec2) -> (i64, i64) {
        // Finite coordinates of bounded size: the casts saturate at worst.
        (
            (p.x / self.tol).floor() as i64,
            (p.y / self.tol).floor() as i64,
        )
    }

    fn find(&self, p: Vec2) -> Option<usize> {
        let (cx, cy) = self.cell(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = self.grid.get(&(cx + dx, cy + dy)) {
                    if let Some(&id) = list
                        .iter()
                        .find(|&&i| (self.points[i] - p).norm() <= self.tol)
                    {
                        return Some(id);
                    }
                }
            }
        }
        None
    }

    fn id(&mut self, p: Vec2) -> usize {
        if let Some(id) = self.find(p) {
            return id;
        }
        let id = self.points.len();
        self.points.push(p);
        let c = self.cell(p);
        self.grid.entry(c).or_default().push(id);
        id
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: Real, y: Real) -> Vec<[Real; 2]> {
        vec![[x, y], [x + 1.0, y], [x + 1.0, y + 1.0], [x, y + 1.0]]
    }

    #[test]
    fn two_squares_share_one_edge_and_the_joint_lands_on_its_end() {
        let tiles = vec![square(0.0, 0.0), square(1.0, 0.0)];
        let joints = [JointAt {
            tiles: [1, 0],
            point: [1.0, 1.0],
        }];
        let g = PatchGraph::new(&tiles, &joints).unwrap();
        assert_eq!(g.points.len(), 6);
        assert_eq!(g.edges.len(), 7);
        let shared: Vec<&Edge> = g.edges.iter().filter(|e| e.right.is_some()).collect();
        assert_eq!(shared.len(), 1);
        let e = shared[0];
        let end = e.joint.iter().position(|&j| j).unwrap();
        // Edge 1 of tile 0 (its right side) is edge 3 of tile 1 (its left side).
        assert_eq!(g.tile_edges[0][1], g.tile_edges[1][3]);
        assert_eq!(g.edges[g.tile_edges[0][1]].right, Some(1));
        assert_eq!(g.tile_edges.iter().flatten().count(), 8);
        assert!((g.point(e.v[end]) - Vec2::new(1.0, 1.0)).norm() < 1e-12);
    }

    #[test]
    fn bad_inputs_are_refused() {
        let cw = vec![[0.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
        assert!(matches!(
            PatchGraph::new(&[cw], &[]),
            Err(LaserError::BadTile { tile: 0, .. })
        ));
        let twice = vec![square(0.0, 0.0), square(0.0, 0.0)];
        assert!(matches!(
            PatchGraph::new(&twice, &[]),
            Err(LaserError::Overlap { .. })
        ));
        let apart = vec![square(0.0, 0.0), square(3.0, 0.0)];
        let j = [JointAt {
            tiles: [0, 1],
            point: [1.0, 0.0],
        }];
        assert!(matches!(
            PatchGraph::new(&apart, &j),
            Err(LaserError::JointNotOnEdge { joint: 0, .. })
        ));
        let nan = vec![vec![[0.0, 0.0], [1.0, Real::NAN], [1.0, 1.0]]];
        assert!(matches!(
            PatchGraph::new(&nan, &[]),
            Err(LaserError::NotFinite { .. })
        ));
        assert!(matches!(
            PatchGraph::new(&[], &[]),
            Err(LaserError::NoTiles)
        ));
    }
}

//! The edge labels of isogami before issue 21, for translating old specs and databases.
//!
//! Earlier versions placed each aspect of the minimal cell at the lattice translate that
//! brought its centroid into the fundamental parallelogram *at the shape being built*, so the
//! same joint string named different joints on the two sides of a shape where a centroid
//! crossed the parallelogram's side. An old spec still names definite joints: the ones of the
//! cell that old code built at exactly that shape. This module rebuilds that labelling from
//! the current, fixed one (an old tile is a current tile of the same aspect moved by a whole
//! number of lattice steps) and says, for every old unique edge, which current edge it is.

use super::build::{Structure, UnitCell};
use super::dims::CellDims;
use super::error::CellError;
use crate::geometry::centroid;
use crate::math::{cross, Vec2};
use crate::tiling::Tiling;

/// One unique edge of the old labelling in the current one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LegacyEdge {
    /// The current unique edge.
    pub edge: usize,
    /// True when the old edge's first tile is the current edge's second one, so that the old
    /// endpoint A is the current endpoint B and the other way round.
    pub swapped: bool,
}

/// For every unique edge of the a×b cell as isogami before issue 21 labelled it at `tiling`'s
/// exact shape, the current edge and orientation. Equal to the identity wherever the old
/// placement agrees with the family's fixed one (at the default shape, and everywhere most
/// shapes are).
pub fn legacy_edges(tiling: &Tiling, dims: CellDims) -> Result<Vec<LegacyEdge>, CellError> {
    let current = UnitCell::new(tiling, dims)?;
    let fixed = Structure::of(tiling.family())?;
    let (t1, t2) = (tiling.t1(), tiling.t2());
    let det = cross(&t1, &t2);
    let proto = tiling.prototile();
    // Per aspect: old translate minus fixed translate, in lattice steps; the old tile (k, c)
    // is the current tile (k, c + delta_k) of the infinite sheet.
    let delta: Vec<[i32; 2]> = tiling
        .aspects()
        .iter()
        .zip(&fixed.shifts)
        .map(|(asp, shift)| {
            let poly: Vec<Vec2> = proto.iter().map(|p| asp.apply(p)).collect();
            let c = centroid(&poly);
            let alpha = (cross(&c, &t2) / det + 1e-9).floor() as i32;
            let beta = (cross(&t1, &c) / det + 1e-9).floor() as i32;
            [shift[0] - alpha, shift[1] - beta]
        })
        .collect();
    let aspects = delta.len();
    let (a, b) = (i32::from(dims.a()), i32::from(dims.b()));
    // The current tile that old tile `i` is (tiles are copy-major, aspects inner in both).
    let current_tile = |i: usize| {
        let k = i % aspects;
        let copy = i / aspects;
        let (x, y) = (copy as i32 % a + delta[k][0], copy as i32 / a + delta[k][1]);
        (y.rem_euclid(b) * a + x.rem_euclid(a)) as usize * aspects + k
    };
    let mut seen = vec![false; current.edges.len()];
    let mut out = Vec::with_capacity(current.edges.len());
    // Old edges were numbered by their first tile edge in (tile, edge) order.
    for (i, tile) in current.tiles.iter().enumerate() {
        let now = current_tile(i);
        for k in 0..tile.polygon.len() {
            let edge = current.tile_edges[now][k];
            if !seen[edge] {
                seen[edge] = true;
                let e = &current.edges[edge];
                out.push(LegacyEdge {
                    edge,
                    swapped: (e.tile_a, e.edge_a) != (now, k),
                });
            }
        }
    }
    Ok(out)
}

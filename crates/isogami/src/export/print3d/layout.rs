//! The plan of a printed sheet: the footprint of every tile and of every lamella hinge, in
//! the patch's millimetres. [`super::solid`] extrudes and unites them.
//!
//! * **Tiles.** Each tile of the largest piece the joints hold together (see
//!   `export::piece`) at the asked state, with every edge it shares with a
//!   neighbour moved inward by `gap/2` (mitred corners), so neighbours are `gap` apart; edges
//!   on the patch outline stay, so the sheet keeps the asked size.
//! * **Hinges.** A joint of tiles A and B at vertex V lies on the edge e they share. Its
//!   lamella is a slab across the gap over the span `[s0, s0 + hinge]` measured from V along
//!   e, reaching `w = gap/2 + gap` to either side of e, i.e. one gap deep into both tiles.
//!   `s0` is the least distance at which the slab keeps `c = gap/2` from the other edges of
//!   A and B at V (nothing from an outline edge, whose far side is empty): a slab corner at
//!   distance `s` along e and `w` across it is `s·sin φ − w·cos φ` from the line of an edge
//!   at angle φ < 180° to e, and the neck keeps c from V itself, so
//!   `s0 = max(c, (c + w·cos φ)/sin φ)` (a reflex corner of A or B wraps round the slab and
//!   sets nothing). A tile beyond that edge is another c away: the gap. The far end keeps the same clearance at
//!   the edge's other end (and leaves room for the other end's hinge if it has one). So a
//!   slab joins exactly its two tiles and stays a full gap from every other tile, and its
//!   neck in the gap is `hinge × gap`. At an opened state the two copies of e part by the
//!   joint's opening angle; the slab is then a band `hinge` wide normal to their bisector
//!   (see `Band`), so the neck stays `hinge` wide however far the joint opens, and the band
//!   enters each tile no nearer to V than `s0`. (The convex hull of the two closed halves
//!   that it replaces narrowed to 0.40–0.78 mm for a 0.8 mm hinge, issue 23 item 11.)
//!   A slab that does not fit on its edge is refused with the smallest `edge_mm` that fits.
//! * **Gaps everywhere.** After the inset, `super::separate` trims any tile that is still
//!   nearer than the gap to another (a slot ending at a reflex stretch of the outline, tiles
//!   meeting at an opened state's contacts).
//!
//! Every slab is then checked against every other tile and slab at the state: closer than
//! the gap (or overlapping another slab) is refused, never printed fused — except the slabs
//! of one pin point (a tile pinned to two others at one vertex: the three turn about that
//! point), which may meet and print as one lamella.

use super::band::{convex_hull, Band};
use super::clearance::check_clearances;
use super::error::PrintError;
use super::offset::inset_edges;
use super::separate::separate_tiles;
use super::settings::PrintSettings;
use crate::export::laser::graph::PatchGraph;
use crate::export::laser::JointAt;
use crate::export::piece::largest_piece;
use crate::export::Patch;
use crate::math::{cross, perp, Real, Vec2};

/// A lamella hinge: its footprint and the two tiles it joins.
#[derive(Debug, Clone, PartialEq)]
pub struct HingeSlab {
    /// Patch tile ids of the joint's two tiles.
    pub tiles: [usize; 2],
    /// Footprint, counter-clockwise, mm.
    pub polygon: Vec<[Real; 2]>,
}

/// Footprints of a printed sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct PrintLayout {
    /// Patch tile ids of the printed tiles (ascending).
    pub tile_ids: Vec<usize>,
    /// Their footprints (gap taken off shared edges), counter-clockwise, mm.
    pub tiles: Vec<Vec<[Real; 2]>>,
    /// One slab per joint between printed tiles.
    pub hinges: Vec<HingeSlab>,
    /// Tiles of the patch left off (not held to the largest piece by joints).
    pub dropped: usize,
}

/// The layout of `patch` at its state with `settings` (validated by the caller).
pub fn print_layout(patch: &Patch, settings: &PrintSettings) -> Result<PrintLayout, PrintError> {
    let bad = |reason: String| PrintError::BadPatch { reason };
    let n = patch.tiles.len();
    if patch.closed_polygons_mm.len() != n {
        return Err(bad("closed polygons and tiles differ in number".into()));
    }
    for (j, joint) in patch.joints.iter().enumerate() {
        if joint.a >= n || joint.b >= n {
            return Err(bad(format!("joint {j} names a tile outside the patch")));
        }
    }
    let ids = largest_piece(n, patch.joints.iter().map(|j| [j.a, j.b]));
    let mut index = vec![usize::MAX; n];
    for (k, &t) in ids.iter().enumerate() {
        index[t] = k;
    }
    let closed: Vec<Vec<[Real; 2]>> = ids
        .iter()
        .map(|&t| patch.closed_polygons_mm[t].clone())
        .collect();
    let joints: Vec<&crate::export::PatchJoint> = patch
        .joints
        .iter()
        .filter(|j| index[j.a] != usize::MAX)
        .collect();
    let mut joint_at = Vec::with_capacity(joints.len());
    for (j, joint) in joints.iter().enumerate() {
        let point = closed[index[joint.a]]
            .get(joint.vertex_a)
            .ok_or_else(|| bad(format!("joint {j} names a vertex its tile lacks")))?;
        joint_at.push(JointAt {
            tiles: [index[joint.a], index[joint.b]],
            point: *point,
        });
    }
    let graph = PatchGraph::new(&closed, &joint_at).map_err(|e| bad(e.to_string()))?;
    let c = 0.5 * settings.gap_mm;
    let shared = |t: usize, k: usize| graph.edges[graph.tile_edges[t][k]].right.is_some();

    let mut tiles = Vec::with_capacity(ids.len());
    for (k, &id) in ids.iter().enumerate() {
        let poly = to_vec(&patch.tiles[id].polygon_mm);
        let d: Vec<Real> = (0..poly.len())
            .map(|e| if shared(k, e) { c } else { 0.0 })
            .collect();
        let inset = inset_edges(&poly, &d).map_err(|p| PrintError::GapTooWide {
            gap_mm: settings.gap_mm,
            tile: id,
            problem: p.to_string(),
        })?;
        tiles.push(inset);
    }
    separate_tiles(&mut tiles, &ids, settings.gap_mm)?;

    let geo = Geometry {
        graph: &graph,
        closed: closed.iter().map(|p| to_vec(p)).collect(),
        state: ids
            .iter()
            .map(|&id| to_vec(&patch.tiles[id].polygon_mm))
            .collect(),
        c,
        w: c + settings.gap_mm,
        hinge: settings.hinge_mm,
    };
    let mut hinges = Vec::with_capacity(joints.len());
    let pin_of = pins(&joints, &index);
    let mut pin = Vec::with_capacity(joints.len());
    // The joint whose slab needs the most room for its edge's length: (needed / length, error).
    let mut worst: Option<(Real, PrintError)> = None;
    for (j, joint) in joints.iter().enumerate() {
        let (a, b) = (index[joint.a], index[joint.b]);
        match geo.slab(a, joint.vertex_a, b, joint.vertex_b, [joint.a, joint.b]) {
            Ok(slab) => {
                hinges.push((slab, [a, b]));
                pin.push(pin_of[j]);
            }
            Err(PrintError::HingeTooWide {
                hinge_mm,
                edge_mm,
                needed_mm,
                tiles,
            }) => {
                let ratio = needed_mm / edge_mm;
                if worst
                    .as_ref()
                    .is_none_or(|(r, _)| ratio > *r || ratio.is_nan())
                {
                    let e = too_small(patch.edge_mm, hinge_mm, edge_mm, needed_mm, tiles);
                    worst = Some((ratio, e));
                }
            }
            Err(e) => return Err(e),
        }
    }
    if let Some((_, e)) = worst {
        return Err(e);
    }
    check_clearances(&tiles, &hinges, &pin, &ids, settings.gap_mm)?;
    Ok(PrintLayout {
        tile_ids: ids.clone(),
        tiles: tiles.iter().map(|p| from_vec(p)).collect(),
        hinges: hinges
            .into_iter()
            .map(|(p, [a, b])| HingeSlab {
                tiles: [ids[a], ids[b]],
                polygon: from_vec(&p),
            })
            .collect(),
        dropped: n - ids.len(),
    })
}

/// The pin point of every joint, numbered: joints that share a vertex of a tile are one pin
/// (found from tile and vertex indices, never from positions). Where a tile is pinned to two
/// others at one vertex, those three turn about one point, so their slabs may meet there and
/// print as one lamella (IH31's and IH32's closed cells pin three tiles at a corner).
fn pins(joints: &[&crate::export::PatchJoint], index: &[usize]) -> Vec<usize> {
    use std::collections::HashMap;
    let mut parent: Vec<usize> = (0..joints.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut first: HashMap<(usize, usize), usize> = HashMap::new();
    for (j, joint) in joints.iter().enumerate() {
        for key in [
            (index[joint.a], joint.vertex_a),
            (index[joint.b], joint.vertex_b),
        ] {
            let other = *first.entry(key).or_insert(j);
            let (x, y) = (root(&mut parent, j), root(&mut parent, other));
            parent[x.max(y)] = x.min(y);
        }
    }
    (0..joints.len()).map(|j| root(&mut parent, j)).collect()
}

/// The refusal of a slab that does not fit on its edge: every length a slab needs is fixed in
/// mm (gap, hinge) or by angles, while the edge scales with the patch, so the patch's mean
/// edge `edge_mm` would have to grow by `needed / len`.
fn too_small(edge_mm: Real, hinge: Real, len: Real, needed: Real, tiles: [usize; 2]) -> PrintError {
    if !(needed.is_finite() && len > 0.0) {
        return PrintError::HingeTooWide {
            hinge_mm: hinge,
            edge_mm: len,
            needed_mm: needed,
            tiles,
        };
    }
    PrintError::PatchTooSmall {
        hinge_mm: hinge,
        edge_mm,
        min_edge_mm: crate::export::laser::min_edge_mm(edge_mm, needed, len),
        len_mm: len,
        needed_mm: needed,
        tiles,
    }
}

/// What the slab placement needs: the edge graph of the closed printed tiles, the closed and
/// state polygons (by printed index), the clearance c = gap/2, the slab's half-width w
/// across its edge, and the hinge width.
struct Geometry<'a> {
    graph: &'a PatchGraph,
    closed: Vec<Vec<Vec2>>,
    state: Vec<Vec<Vec2>>,
    c: Real,
    w: Real,
    hinge: Real,
}

/// The edge a tile shares with its joint partner at vertex `v`: `forward` when it is edge
/// `v` (from v to v + 1), else edge `v - 1` (ending at v).
#[derive(Clone, Copy)]
struct Side {
    tile: usize,
    vertex: usize,
    forward: bool,
}

impl Side {
    fn len(&self, g: &Geometry<'_>) -> usize {
        g.closed[self.tile].len()
    }

    /// Index of the shared edge.
    fn edge(&self, g: &Geometry<'_>) -> usize {
        let n = self.len(g);
        if self.forward {
            self.vertex
        } else {
            (self.vertex + n - 1) % n
        }
    }

    /// Index of the other end of the shared edge.
    fn far(&self, g: &Geometry<'_>) -> usize {
        let n = self.len(g);
        if self.forward {
            (self.vertex + 1) % n
        } else {
            (self.vertex + n - 1) % n
        }
    }
}

impl Geometry<'_> {
    /// Which of tile `t`'s edges at vertex `v` it shares with tile `other`.
    fn side(&self, t: usize, v: usize, other: usize) -> Option<Side> {
        let n = self.closed[t].len();
        if v >= n {
            return None;
        }
        let with_other = |k: usize| {
            let e = &self.graph.edges[self.graph.tile_edges[t][k]];
            e.right.is_some() && (e.left == other || e.right == Some(other))
        };
        if with_other(v) {
            Some(Side {
                tile: t,
                vertex: v,
                forward: true,
            })
        } else if with_other((v + n - 1) % n) {
            Some(Side {
                tile: t,
                vertex: v,
                forward: false,
            })
        } else {
            None
        }
    }

    /// Least distance from vertex `v` of tile `t` (closed) along the edge to `toward` at
    /// which a slab of half-width w keeps clear of the tile's other edge at `v`.
    fn start(&self, t: usize, v: usize, toward: usize) -> Real {
        let poly = &self.closed[t];
        let n = poly.len();
        let (prev, next) = ((v + n - 1) % n, (v + 1) % n);
        // Reflex corner: the tile wraps round the slab, the other edge is not in the way.
        if cross(&(poly[v] - poly[prev]), &(poly[next] - poly[v])) < 0.0 {
            return 0.0;
        }
        let (other, other_edge) = if toward == next {
            (prev, prev)
        } else {
            (next, v)
        };
        let d = (poly[toward] - poly[v]).normalize();
        let f = (poly[other] - poly[v]).normalize();
        let shared = self.graph.edges[self.graph.tile_edges[t][other_edge]]
            .right
            .is_some();
        // A hair (1 % of c) inside the tile rather than on its edge (the inset edge, or the
        // outline): a slab corner exactly on a tile edge that `separate` trimmed (new vertices
        // on a 1e-8 mm grid) leaves slivers that a float32 STL collapses.
        let c = if shared { self.c } else { 0.0 } + 0.01 * self.c;
        let (cos, sin) = (d.dot(&f), cross(&d, &f).abs());
        let need = c + self.w * cos;
        let corner = if need <= 0.0 {
            0.0
        } else if sin < 1e-9 {
            Real::INFINITY
        } else {
            need / sin
        };
        // Where another tile lies beyond the other edge, the neck also keeps c from V, so it
        // stays a full gap from that tile's corner.
        corner.max(c)
    }

    /// The slab of the joint of printed tiles `a` (at its vertex `va`) and `b` (at `vb`);
    /// `ids` are their patch ids, for messages.
    fn slab(
        &self,
        a: usize,
        va: usize,
        b: usize,
        vb: usize,
        ids: [usize; 2],
    ) -> Result<Vec<Vec2>, PrintError> {
        let (Some(sa), Some(sb)) = (self.side(a, va, b), self.side(b, vb, a)) else {
            return Err(PrintError::BadPatch {
                reason: format!("the joint of tiles {ids:?} is not on an edge they share"),
            });
        };
        let pa = &self.closed[a];
        let (fa, fb) = (sa.far(self), sb.far(self));
        let len = (pa[fa] - pa[va]).norm();
        let s0 = self.start(a, va, fa).max(self.start(b, vb, fb));
        let s_end = self.start(a, fa, va).max(self.start(b, fb, vb));
        let edge = &self.graph.edges[self.graph.tile_edges[a][sa.edge(self)]];
        let both_ends = edge.joint[0] && edge.joint[1];
        // Each tile's copy of the edge at the state: its vertex, direction and inward normal.
        let frame = |side: Side| -> (Vec2, Vec2, Vec2) {
            let p = &self.state[side.tile];
            let v = p[side.vertex];
            let d = (p[side.far(self)] - v).normalize();
            (v, d, if side.forward { perp(&d) } else { -perp(&d) })
        };
        let sides = [frame(sa), frame(sb)];
        let v = (sides[0].0 + sides[1].0) * 0.5;
        let band = Band::new(&sides, s0, self.w, self.hinge);
        let needed = band.reach + s_end + if both_ends { self.hinge } else { 0.0 };
        if needed.is_nan() || needed > len {
            return Err(PrintError::HingeTooWide {
                hinge_mm: self.hinge,
                edge_mm: len,
                needed_mm: needed,
                tiles: ids,
            });
        }
        let [a0, a1] = band.corners(v, &sides[0], s0);
        let [b0, b1] = band.corners(v, &sides[1], s0);
        Ok(convex_hull(&[a0, a1, b0, b1]))
    }
}

fn to_vec(poly: &[[Real; 2]]) -> Vec<Vec2> {
    poly.iter().map(|p| Vec2::new(p[0], p[1])).collect()
}

fn from_vec(poly: &[Vec2]) -> Vec<[Real; 2]> {
    poly.iter().map(|p| [p.x, p.y]).collect()
}

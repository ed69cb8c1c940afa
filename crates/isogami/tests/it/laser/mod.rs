//! Fixtures for the laser export tests: patches of designs in mm built here from the cell
//! (independently of the library's export code), and the independent check of cut paths
//! read back by other libraries' parsers: the material left after burning every path with
//! the kerf is rebuilt with `geo`'s buffers and booleans and compared with the design.
#![allow(dead_code)]

use geo::algorithm::buffer::{BufferStyle, LineCap, LineJoin};
use geo::algorithm::line_intersection::{line_intersection, LineIntersection};
use geo::{
    Area, BooleanOps, Buffer, Contains, Coord, Euclidean, InteriorPoint, Length, Line, LineString,
    MultiLineString, MultiPolygon, Polygon,
};
use isogami::api::{resolve_design, sheet_geometry};
use isogami::cell::End;
use isogami::export::laser::JointAt;
use std::collections::HashMap;

/// A patch of tiles in mm: closed-state polygons and joints.
pub struct TestPatch {
    pub tiles: Vec<Vec<[f64; 2]>>,
    pub joints: Vec<JointAt>,
}

/// The r×c patch of `spec` scaled so that the mean edge length is `edge_mm`.
pub fn patch(spec: &str, r: i32, c: i32, edge_mm: f64) -> TestPatch {
    let design = resolve_design(spec).unwrap();
    let cell = design.cell().unwrap();
    let s = edge_mm / sheet_geometry(&design).unwrap().length_scale;
    let n = cell.tiles.len();
    let index = |i: i32, j: i32, t: usize| ((i * c + j) as usize) * n + t;
    let shift = |i: i32, j: i32| cell.u * f64::from(i) + cell.w * f64::from(j);
    let mut tiles = Vec::new();
    for i in 0..r {
        for j in 0..c {
            for t in &cell.tiles {
                let d = shift(i, j);
                tiles.push(
                    t.polygon
                        .iter()
                        .map(|p| [(p.x + d.x) * s, (p.y + d.y) * s])
                        .collect(),
                );
            }
        }
    }
    let mut joints = Vec::new();
    for (k, e) in cell.edges.iter().enumerate() {
        let ends: &[End] = match design.joints[k].to_char() {
            'a' => &[End::A],
            'b' => &[End::B],
            'x' => &[End::A, End::B],
            _ => &[],
        };
        for i in 0..r {
            for j in 0..c {
                let (bi, bj) = (i + e.offset[0], j + e.offset[1]);
                if !(0..r).contains(&bi) || !(0..c).contains(&bj) {
                    continue;
                }
                for end in ends {
                    let p = cell.endpoint(k, *end) + shift(i, j);
                    joints.push(JointAt {
                        tiles: [index(i, j, e.tile_a), index(bi, bj, e.tile_b)],
                        point: [p.x * s, p.y * s],
                    });
                }
            }
        }
    }
    TestPatch { tiles, joints }
}

/// The patch reduced to the largest connected piece of its tile/joint graph (a rectangle of
/// cells can leave border tiles whose joints all lead out of it), tiles renumbered.
pub fn largest_piece(p: TestPatch) -> TestPatch {
    let root = roots(&p);
    let mut size = vec![0usize; p.tiles.len()];
    for &r in &root {
        size[r] += 1;
    }
    let best = (0..size.len()).max_by_key(|&r| size[r]).unwrap_or(0);
    let mut new_index = vec![usize::MAX; p.tiles.len()];
    let mut tiles = Vec::new();
    for (t, poly) in p.tiles.into_iter().enumerate() {
        if root[t] == best {
            new_index[t] = tiles.len();
            tiles.push(poly);
        }
    }
    let joints = p
        .joints
        .into_iter()
        .filter(|j| root[j.tiles[0]] == best)
        .map(|j| JointAt {
            tiles: j.tiles.map(|t| new_index[t]),
            point: j.point,
        })
        .collect();
    TestPatch { tiles, joints }
}

/// Per tile, a representative of its connected piece of the tile/joint graph.
fn roots(p: &TestPatch) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..p.tiles.len()).collect();
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for j in &p.joints {
        let (a, b) = (find(&mut parent, j.tiles[0]), find(&mut parent, j.tiles[1]));
        parent[a] = b;
    }
    (0..p.tiles.len()).map(|i| find(&mut parent, i)).collect()
}

/// True when some tile of the patch has a reflex corner.
pub fn has_concave_tile(p: &TestPatch) -> bool {
    p.tiles.iter().any(|t| {
        let n = t.len();
        (0..n).any(|k| {
            let (a, b, c) = (t[(k + n - 1) % n], t[k], t[(k + 1) % n]);
            (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) < -1e-9
        })
    })
}

/// Cut paths as read back from a file: straight segments and closed outline loops (mm, in
/// the patch's frame).
#[derive(Default, Debug)]
pub struct ReadBack {
    pub segments: Vec<[Coord; 2]>,
    pub loops: Vec<Vec<Coord>>,
    /// Engraved labels.
    pub labels: usize,
}

/// What the rebuilt material says.
#[derive(Debug)]
pub struct Verdict {
    /// Connected pieces of material (area above 1e-6 mm²).
    pub pieces: usize,
    /// Pieces left after removing a thin strip along every design edge (one per tile if the
    /// only connections are across edges).
    pub tile_pieces: usize,
    /// Tiles hit by exactly one of those pieces.
    pub tiles_hit_once: usize,
    /// Per shared design edge: tiles, joints on it, crossing pieces and their lengths (mm).
    pub crossings: Vec<([usize; 2], usize, Vec<f64>)>,
    /// Cut paths that cross another (proper crossings or collinear overlaps).
    pub crossing_cuts: usize,
}

/// An edge by its two rounded endpoints.
type EdgeKey = ((i64, i64), (i64, i64));

fn key(p: [f64; 2]) -> (i64, i64) {
    ((p[0] * 1e4).round() as i64, (p[1] * 1e4).round() as i64)
}

/// Rebuilds the material left after burning every path of `rb` with a kerf of `kerf` and
/// measures it against `patch`.
pub fn judge(rb: &ReadBack, patch: &TestPatch, kerf: f64) -> Verdict {
    let round = 2.0 * std::f64::consts::PI / 512.0;
    let style = BufferStyle::new(kerf / 2.0)
        .line_cap(LineCap::Round(round))
        .line_join(LineJoin::Round(round));
    // The sheet: inside the outline path (largest loop), minus the other loops (holes).
    let mut rings: Vec<LineString> = rb
        .loops
        .iter()
        .map(|l| {
            let mut ring = LineString::from(l.clone());
            ring.close();
            ring
        })
        .collect();
    rings.sort_by(|a, b| {
        let area = |r: &LineString| Polygon::new(r.clone(), vec![]).unsigned_area();
        area(b).total_cmp(&area(a))
    });
    let outer = rings.remove(0);
    let sheet = Polygon::new(outer.clone(), rings.clone());
    let mut paths: Vec<LineString> = rb
        .segments
        .iter()
        .map(|s| LineString::from(vec![s[0], s[1]]))
        .collect();
    // The beam's burn along a path is the union of its segments' round-capped strokes.
    for ring in std::iter::once(&outer).chain(&rings) {
        paths.extend(ring.lines().map(|l| LineString::from(vec![l.start, l.end])));
    }
    let burn: MultiPolygon = MultiLineString::new(paths).buffer_with_style(style);
    let material = sheet.difference(&burn);
    let pieces = material
        .0
        .iter()
        .filter(|p| p.unsigned_area() > 1e-6)
        .count();

    // Design edges shared by two tiles, and the joints on each.
    let mut edges: HashMap<EdgeKey, ([[f64; 2]; 2], Vec<usize>)> = HashMap::new();
    for (t, poly) in patch.tiles.iter().enumerate() {
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            let (ka, kb) = (key(a), key(b));
            let id = if ka < kb { (ka, kb) } else { (kb, ka) };
            edges.entry(id).or_insert(([a, b], Vec::new())).1.push(t);
        }
    }
    let mut crossings = Vec::new();
    let mut all_edges = Vec::new();
    for (id, (ends, tiles)) in edges.iter_mut() {
        all_edges.push(LineString::from(vec![ends[0], ends[1]]));
        if tiles.len() != 2 {
            continue;
        }
        let pair = [tiles[0].min(tiles[1]), tiles[0].max(tiles[1])];
        let on_it = patch
            .joints
            .iter()
            .filter(|j| {
                let jp = [j.tiles[0].min(j.tiles[1]), j.tiles[0].max(j.tiles[1])];
                let kj = key(j.point);
                jp == pair && (kj == id.0 || kj == id.1)
            })
            .count();
        let line = MultiLineString::new(vec![LineString::from(vec![ends[0], ends[1]])]);
        let inside = material.clip(&line, false);
        let lengths: Vec<f64> = inside
            .0
            .iter()
            .map(|l| Euclidean.length(l))
            .filter(|&l| l > 1e-6)
            .collect();
        crossings.push((pair, on_it, lengths));
    }

    // Without a thin strip along every design edge, the material falls into one piece per
    // tile when nothing but bridges across edges joins tiles.
    let strips: MultiPolygon = MultiLineString::new(all_edges).buffer(0.005);
    let split = material.difference(&strips);

    let big: Vec<&Polygon> = split
        .0
        .iter()
        .filter(|p| p.unsigned_area() > 1e-4)
        .collect();
    let tiles: Vec<Polygon> = patch
        .tiles
        .iter()
        .map(|t| Polygon::new(LineString::from(t.clone()), vec![]))
        .collect();
    let mut hits = vec![0usize; tiles.len()];
    for piece in &big {
        if let Some(p) = piece.interior_point() {
            for (t, tile) in tiles.iter().enumerate() {
                if tile.contains(&p) {
                    hits[t] += 1;
                }
            }
        }
    }
    Verdict {
        pieces,
        tile_pieces: big.len(),
        tiles_hit_once: hits.iter().filter(|&&h| h == 1).count(),
        crossings,
        crossing_cuts: crossing_cuts(rb),
    }
}

/// Number of pairs of cut segments (outline segments included) that cross or overlap.
fn crossing_cuts(rb: &ReadBack) -> usize {
    let mut lines: Vec<Line> = rb.segments.iter().map(|s| Line::new(s[0], s[1])).collect();
    for l in &rb.loops {
        for k in 0..l.len() {
            lines.push(Line::new(l[k], l[(k + 1) % l.len()]));
        }
    }
    lines.sort_by(|a, b| a.start.x.min(a.end.x).total_cmp(&b.start.x.min(b.end.x)));
    let mut count = 0;
    for i in 0..lines.len() {
        let xmax = lines[i].start.x.max(lines[i].end.x);
        for j in i + 1..lines.len() {
            if lines[j].start.x.min(lines[j].end.x) > xmax {
                break;
            }
            match line_intersection(lines[i], lines[j]) {
                Some(LineIntersection::SinglePoint {
                    is_proper: true, ..
                }) => count += 1,
                Some(LineIntersection::Collinear { intersection })
                    if Euclidean.length(&intersection) > 1e-9 =>
                {
                    count += 1
                }
                _ => {}
            }
        }
    }
    count
}

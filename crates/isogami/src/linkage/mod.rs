//! Linkage analysis (paper §5.1): the planar linkages a design's joints form, for telling
//! designs apart by their linkage types ("2×4-bar + 1×6-bar") and tile degrees.
//!
//! What it is for: a linkage is a closed loop of tiles (the bars) pinned one to the next, around
//! a hole of the sheet. Nodes of the tile–joint graph are tiles of the infinite periodic sheet,
//! written (tile index, cell offset); edges are pin joints. The linkages are the holes whose
//! boundary is a chordless (induced) cycle of at least three tiles, one per class of
//! translates by whole cells (a tileable unit cell of linkages), each given with its canonical
//! representative: the smallest node, in (tile, cell) order, first and in cell 0.
//!
//! How, and why not the literal paper recipe: the paper lists every chordless cycle of the
//! graph over the 3×3 patch of cells and removes periodic duplicates. Read literally that
//! over-reports: in rotating squares the ring of eight squares around any square is a chordless
//! cycle, but the square inside it makes it a ring of four holes, not a linkage; on a 4×4 cell
//! the number of such cycles grows exponentially. Here the holes are traced instead, exactly and
//! in linear time, from the planar embedding the tile geometry gives (the joints' order round
//! each tile's boundary), on the quotient graph of one cell while carrying cell offsets. That
//! yields each translation class once, finds linkages that wander beyond the 3×3 patch (joints
//! leaving the patch are not lost), and for a connected sheet gives exactly E − V holes per cell
//! (Euler on the torus). A hole is a linkage when its boundary is a chordless cycle, as in the
//! paper; holes whose boundary repeats a tile or has a chord, cycles of tiles that all share
//! one pin (nothing there can open), and unbounded faces are listed apart in
//! [`LinkageAnalysis::other_faces`].
//!
//! Conventions: a welded edge ([`JointChoice::Both`]) is one graph edge (its two pins bound a
//! slit, not a hole), and so are two joints between the same two tiles; a hole bounded by two
//! tiles only is such a weld and is not reported. The degree of a tile is its number of distinct
//! pinned neighbours (tile, cell offset) on the infinite sheet.
//!
//! What it must not do: no I/O, no kinematics (it reads only the closed-state cell and the joint
//! choices), no panics on bad input (a joint list of the wrong length is an error).

mod error;
mod faces;
mod sheet;

use crate::cell::{End, UnitCell};
use crate::math::Vec2;
use crate::topology::JointChoice;
use faces::{canonical_start, has_chord, is_simple, trace_faces, FaceWalk};
use serde::Serialize;
use sheet::Sheet;
use std::collections::BTreeMap;

pub use error::LinkageError;
pub use faces::Node;

/// A pin joint of a linkage: the design's joint on `edge` at `end`, in the copy of the edge
/// whose `tile_a` sits in `cell`. Its closed-state position is
/// `cell.endpoint(edge, end) + cell.offset_vector(cell)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct LinkageJoint {
    /// Unique edge index of the cell.
    pub edge: usize,
    /// Which end of the edge.
    pub end: End,
    /// Cell offset of the edge's `tile_a`.
    pub cell: [i32; 2],
}

/// One linkage: a chordless cycle of tiles around a hole.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct Linkage {
    /// Number of bars (tiles, equally joints) of the loop.
    pub bars: usize,
    /// The tiles in order round the hole (counter-clockwise), each as (tile, cell offset).
    pub nodes: Vec<Node>,
    /// `joints[i]` pins `nodes[i]` to `nodes[(i + 1) % bars]`.
    pub joints: Vec<LinkageJoint>,
}

/// Why a face of the sheet is not a linkage.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FaceIssue {
    /// The boundary passes the same tile twice (a tile hanging into the hole, a cut tile).
    RepeatedTile,
    /// Two tiles of the loop that are not neighbours along it are pinned together.
    Chord,
    /// All its joints sit at one point: the tiles share a single pin, and no hole can open.
    SinglePoint,
    /// The face is an infinite strip (the joints do not connect the sheet in two directions).
    Unbounded,
}

/// A face of the sheet that is not a linkage, with the tiles along its boundary (for an
/// unbounded face, one period of it).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct OtherFace {
    /// What disqualifies it.
    pub issue: FaceIssue,
    /// The boundary walk.
    pub nodes: Vec<Node>,
}

/// The linkages of a design.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, serde::Deserialize)]
pub struct LinkageAnalysis {
    /// One linkage per translation class, sorted by bar count, then nodes.
    pub linkages: Vec<Linkage>,
    /// Counts by bar number, e.g. "2×4-bar + 1×6-bar"; "none" without linkages.
    pub signature: String,
    /// Tile degree → number of tiles of the cell with that degree.
    pub degree_histogram: BTreeMap<usize, usize>,
    /// Faces that are not linkages (welds, and the outlines of finite clusters of tiles seen
    /// from outside, are not faces of interest and are left out).
    pub other_faces: Vec<OtherFace>,
}

/// Finds the linkages of `cell` with one joint choice per unique edge.
pub fn analyze_linkages(
    cell: &UnitCell,
    joints: &[JointChoice],
) -> Result<LinkageAnalysis, LinkageError> {
    if joints.len() != cell.edges.len() {
        return Err(LinkageError::JointCount {
            given: joints.len(),
            edges: cell.edges.len(),
        });
    }
    validate_cell(cell)?;
    let sheet = Sheet::new(cell, joints);
    let adjacent = sheet.neighbours();
    let min_area = cell
        .tiles
        .iter()
        .map(|t| crate::geometry::signed_area(&t.polygon).abs())
        .fold(f64::INFINITY, f64::min);
    let mut linkages = Vec::new();
    let mut other_faces = Vec::new();
    for face in trace_faces(&sheet) {
        if face.drift != [0, 0] {
            other_faces.push(OtherFace {
                issue: FaceIssue::Unbounded,
                nodes: face.nodes,
            });
            continue;
        }
        // Two-tile faces are welds; a clockwise walk is the outline of a finite cluster of
        // tiles seen from outside, not a hole (holes have zero area in the closed state, or
        // enclose free tiles).
        if face.nodes.len() <= 2 || walk_area(cell, &sheet, &face) < -0.5 * min_area {
            continue;
        }
        let issue = if !is_simple(&face.nodes) {
            Some(FaceIssue::RepeatedTile)
        } else if has_chord(&face.nodes, &adjacent) {
            Some(FaceIssue::Chord)
        } else {
            None
        };
        let (nodes, darts) = canonical(&face);
        let joints = linkage_joints(&sheet, &nodes, &darts);
        let issue = issue.or_else(|| single_point(cell, &joints).then_some(FaceIssue::SinglePoint));
        match issue {
            Some(issue) => other_faces.push(OtherFace { issue, nodes }),
            None => linkages.push(Linkage {
                bars: nodes.len(),
                joints,
                nodes,
            }),
        }
    }
    linkages.sort_by(|a, b| (a.bars, &a.nodes).cmp(&(b.bars, &b.nodes)));
    other_faces.sort_by(|a, b| (a.nodes.len(), &a.nodes).cmp(&(b.nodes.len(), &b.nodes)));
    let mut degree_histogram = BTreeMap::new();
    for nb in &adjacent {
        *degree_histogram.entry(nb.len()).or_insert(0) += 1;
    }
    Ok(LinkageAnalysis {
        signature: signature(&linkages),
        linkages,
        degree_histogram,
        other_faces,
    })
}

/// The signature of a list of linkages, e.g. "2×4-bar + 1×6-bar" (ascending bar count).
pub fn signature(linkages: &[Linkage]) -> String {
    let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
    for l in linkages {
        *counts.entry(l.bars).or_insert(0) += 1;
    }
    if counts.is_empty() {
        return "none".to_string();
    }
    counts
        .iter()
        .map(|(bars, n)| format!("{n}×{bars}-bar"))
        .collect::<Vec<_>>()
        .join(" + ")
}

/// Rejects cells whose edge records point at tiles or tile edges that do not exist, so that
/// the graph code can index freely.
fn validate_cell(cell: &UnitCell) -> Result<(), LinkageError> {
    let n = cell.tiles.len();
    for (k, e) in cell.edges.iter().enumerate() {
        let ok = e.tile_a < n
            && e.tile_b < n
            && e.edge_a < cell.tiles[e.tile_a].polygon.len()
            && e.edge_b < cell.tiles[e.tile_b].polygon.len();
        if !ok {
            return Err(LinkageError::EdgeRecord { edge: k });
        }
    }
    Ok(())
}

/// The joints between consecutive nodes of a canonical walk.
fn linkage_joints(sheet: &Sheet, nodes: &[Node], darts: &[usize]) -> Vec<LinkageJoint> {
    darts
        .iter()
        .zip(nodes)
        .map(|(&d, &(_, c))| {
            let dart = &sheet.darts[d];
            let cell = if dart.forward {
                c
            } else {
                [c[0] + dart.offset[0], c[1] + dart.offset[1]]
            };
            LinkageJoint {
                edge: dart.edge,
                end: dart.end,
                cell,
            }
        })
        .collect()
}

/// True when all joints coincide in the closed state (relative to the mean edge length).
fn single_point(cell: &UnitCell, joints: &[LinkageJoint]) -> bool {
    let tol = 1e-9 * cell.mean_edge_length();
    let pos = |j: &LinkageJoint| cell.endpoint(j.edge, j.end) + cell.offset_vector(j.cell);
    let first = joints.first().map(pos);
    first.is_some_and(|p| joints.iter().all(|j| (pos(j) - p).norm() <= tol))
}

/// Nodes and darts of a bounded face, rotated and translated to the canonical start.
fn canonical(face: &FaceWalk) -> (Vec<Node>, Vec<usize>) {
    let (start, shift) = canonical_start(&face.nodes);
    let k = face.nodes.len();
    (0..k)
        .map(|i| {
            let (t, c) = face.nodes[(start + i) % k];
            (
                (t, [c[0] + shift[0], c[1] + shift[1]]),
                face.darts[(start + i) % k],
            )
        })
        .unzip()
}

/// Signed area enclosed by a bounded face's walk along the tile boundaries in the closed state:
/// about zero (or the area of free tiles inside) for a hole, minus the area of a finite cluster
/// for the outline of that cluster.
fn walk_area(cell: &UnitCell, sheet: &Sheet, face: &FaceWalk) -> f64 {
    let k = face.darts.len();
    let mut pts: Vec<Vec2> = Vec::new();
    for i in 0..k {
        // Arrive at node i+1 through the joint of dart i, leave through dart i+1.
        let arrive = &sheet.darts[sheet.darts[face.darts[i]].rev];
        let leave = &sheet.darts[face.darts[(i + 1) % k]];
        let (tile, c) = face.nodes[(i + 1) % k];
        let poly = &cell.tiles[tile].polygon;
        let n = poly.len();
        let shift = cell.offset_vector(c);
        // Keys run counter-clockwise, two per tile edge; walk them clockwise from the arriving
        // joint to the leaving one (all the way round when they are the same joint).
        let steps = match (arrive.key + 2 * n - leave.key) % (2 * n) {
            0 => 2 * n,
            s => s,
        };
        for s in 0..=steps {
            let key = (arrive.key + 2 * n - s % (2 * n)) % (2 * n);
            let v = (key.div_ceil(2)) % n;
            let p = poly[v] + shift;
            if pts.last() != Some(&p) {
                pts.push(p);
            }
        }
    }
    crate::geometry::signed_area(&pts)
}

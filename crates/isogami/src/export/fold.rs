//! FOLD (JSON) of a patch, and a reader for the files it writes.
//!
//! FOLD 1.1 (github.com/edemaine/fold, `doc/spec.md`): every tile is a face with its own
//! vertices, so the cuts between tiles are boundary edges (`"B"`) with duplicated vertices,
//! the FOLD way of writing cuts that every reader understands (1.2's optional `"C"` is not
//! used). The key frame is the exported state; `file_frames` holds one frame per state of
//! [`Patch::states`] (closed first), each inheriting the mesh from the key frame
//! (`frame_parent` 0, `frame_inherit` true) and giving its own `vertices_coords`.
//! Coordinates are 2D, in millimetres (`frame_unit` `"mm"`).
//!
//! Custom properties (namespaced `isogami:` as the spec asks):
//! - `isogami:joints`: one `[v, w]` pair of vertex ids per pin joint: the two tiles' vertices
//!   that the pin holds together (they coincide in every frame).
//! - `faces_isogami:tile`: per face, `[i, j, tile]`: its cell and tile index in the cell.
//! - `isogami:design` (spec string), `isogami:t` (t of the frame), `isogami:edgeMm` (mean
//!   edge length).

use super::error::ExportError;
use super::patch::Patch;
use crate::math::Real;
use serde::{Deserialize, Serialize};

/// The FOLD version written.
pub const FOLD_SPEC: Real = 1.1;

/// The frame units the FOLD spec defines.
pub const FOLD_UNITS: &[&str] = &["unit", "in", "pt", "m", "cm", "mm", "um", "nm"];

/// The FOLD file of a patch, as compact JSON text (one line; pretty printing would put every
/// coordinate on a line of its own and more than double the size).
pub fn fold_text(patch: &Patch, creator: &str) -> Result<String, ExportError> {
    let file = fold_file(patch, creator);
    serde_json::to_string(&file).map_err(|e| ExportError::Encode {
        format: "FOLD",
        reason: e.to_string(),
    })
}

/// The FOLD file of a patch as data (see the module docs).
pub fn fold_file(patch: &Patch, creator: &str) -> FoldFile {
    let mut first = Vec::with_capacity(patch.tiles.len());
    let mut edges_vertices = Vec::new();
    let mut faces_vertices = Vec::with_capacity(patch.tiles.len());
    let mut v = 0;
    for t in &patch.tiles {
        let n = t.polygon_mm.len();
        first.push(v);
        faces_vertices.push((v..v + n).collect());
        edges_vertices.extend((0..n).map(|k| [v + k, v + (k + 1) % n]));
        v += n;
    }
    let coords = |polys: &mut dyn Iterator<Item = &Vec<[Real; 2]>>| -> Vec<[Real; 2]> {
        polys.flatten().copied().collect()
    };
    let joints = patch
        .joints
        .iter()
        .map(|j| [first[j.a] + j.vertex_a, first[j.b] + j.vertex_b])
        .collect();
    let frames = patch
        .states
        .iter()
        .map(|s| FoldFrame {
            frame_title: format!("t = {:.4}", s.t),
            frame_parent: 0,
            frame_inherit: true,
            vertices_coords: coords(&mut s.polygons_mm.iter()),
            t: s.t,
        })
        .collect();
    FoldFile {
        file_spec: FOLD_SPEC,
        file_creator: creator.to_string(),
        file_title: format!("{}x{} patch of {}", patch.rows, patch.cols, patch.design),
        file_classes: vec!["singleModel".into(), "animation".into()],
        frame_title: format!("t = {:.4}", patch.t),
        frame_classes: vec!["creasePattern".into()],
        frame_attributes: vec!["2D".into()],
        frame_unit: "mm".into(),
        vertices_coords: coords(&mut patch.tiles.iter().map(|t| &t.polygon_mm)),
        edges_assignment: vec!["B".into(); edges_vertices.len()],
        edges_vertices,
        faces_vertices,
        faces_tile: patch
            .tiles
            .iter()
            .map(|t| [i64::from(t.cell[0]), i64::from(t.cell[1]), t.tile as i64])
            .collect(),
        joints,
        design: patch.design.clone(),
        t: patch.t,
        edge_mm: patch.edge_mm,
        file_frames: frames,
    }
}

/// A FOLD file as this module writes it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FoldFile {
    /// FOLD version.
    pub file_spec: Real,
    /// Software that wrote it.
    pub file_creator: String,
    /// Title.
    pub file_title: String,
    /// File classes.
    pub file_classes: Vec<String>,
    /// Key frame title.
    pub frame_title: String,
    /// Key frame classes.
    pub frame_classes: Vec<String>,
    /// Key frame attributes.
    pub frame_attributes: Vec<String>,
    /// Unit of every coordinate.
    pub frame_unit: String,
    /// Vertex coordinates of the key frame.
    pub vertices_coords: Vec<[Real; 2]>,
    /// Edges as vertex pairs.
    pub edges_vertices: Vec<[usize; 2]>,
    /// `"B"` for every edge.
    pub edges_assignment: Vec<String>,
    /// Faces as counter-clockwise vertex lists.
    pub faces_vertices: Vec<Vec<usize>>,
    /// Per face: cell i, cell j, tile index.
    #[serde(rename = "faces_isogami:tile")]
    pub faces_tile: Vec<[i64; 3]>,
    /// Pin joints as vertex pairs.
    #[serde(rename = "isogami:joints")]
    pub joints: Vec<[usize; 2]>,
    /// Design spec string.
    #[serde(rename = "isogami:design")]
    pub design: String,
    /// t of the key frame.
    #[serde(rename = "isogami:t")]
    pub t: Real,
    /// Mean edge length, mm.
    #[serde(rename = "isogami:edgeMm")]
    pub edge_mm: Real,
    /// The deployment states.
    pub file_frames: Vec<FoldFrame>,
}

/// One further frame: new vertex coordinates over the key frame's mesh.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FoldFrame {
    /// Title (its t).
    pub frame_title: String,
    /// Always 0, the key frame.
    pub frame_parent: usize,
    /// Always true.
    pub frame_inherit: bool,
    /// Vertex coordinates at this state.
    pub vertices_coords: Vec<[Real; 2]>,
    /// t of the state.
    #[serde(rename = "isogami:t")]
    pub t: Real,
}

/// Reads a FOLD file written by [`fold_text`] and checks that it is consistent: every index
/// in range, one assignment per edge, every frame with a coordinate per vertex.
pub fn read_fold(text: &str) -> Result<FoldFile, ExportError> {
    let bad = |reason: String| ExportError::Read {
        format: "FOLD",
        reason,
    };
    let file: FoldFile = serde_json::from_str(text).map_err(|e| bad(e.to_string()))?;
    let nv = file.vertices_coords.len();
    let in_range = |v: &usize| *v < nv;
    if let Some(k) = file
        .edges_vertices
        .iter()
        .position(|e| !e.iter().all(in_range))
    {
        return Err(bad(format!("edge {k} names a vertex past {nv}")));
    }
    if let Some(k) = file
        .faces_vertices
        .iter()
        .position(|f| f.len() < 3 || !f.iter().all(in_range))
    {
        return Err(bad(format!("face {k} is not a polygon of known vertices")));
    }
    if let Some(k) = file.joints.iter().position(|j| !j.iter().all(in_range)) {
        return Err(bad(format!("joint {k} names a vertex past {nv}")));
    }
    if file.edges_assignment.len() != file.edges_vertices.len() {
        return Err(bad(
            "edges_assignment and edges_vertices differ in length".into()
        ));
    }
    if file.faces_tile.len() != file.faces_vertices.len() {
        return Err(bad(
            "faces_isogami:tile and faces_vertices differ in length".into(),
        ));
    }
    if let Some(k) = file
        .file_frames
        .iter()
        .position(|f| f.vertices_coords.len() != nv)
    {
        return Err(bad(format!(
            "frame {} has a vertex count other than {nv}",
            k + 1
        )));
    }
    let finite = |c: &[Real; 2]| c[0].is_finite() && c[1].is_finite();
    let mut all_coords = file
        .vertices_coords
        .iter()
        .chain(file.file_frames.iter().flat_map(|f| &f.vertices_coords));
    if !all_coords.all(finite) {
        return Err(bad("a coordinate is not a finite number".into()));
    }
    Ok(file)
}

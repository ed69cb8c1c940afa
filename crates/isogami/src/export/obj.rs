//! Wavefront OBJ of a patch at its exported state: one object (`o tile_ID`) per tile, its
//! vertices (`v x y 0`, mm, z = 0) and one polygon face listing them counter-clockwise, so
//! every face's normal is +z. Tiles have their own vertices (the cuts between tiles are real
//! gaps in the mesh). Concave tiles stay single n-gon faces, as OBJ allows; tools that need
//! triangles triangulate them.

use super::patch::Patch;
use std::fmt::Write;

/// The OBJ text of a patch.
pub fn obj_text(patch: &Patch, creator: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "# {creator}: {}x{} patch of {}",
        patch.rows, patch.cols, patch.design
    );
    let _ = writeln!(
        out,
        "# units mm; t = {}; mean edge {} mm; {} tiles",
        patch.t,
        patch.edge_mm,
        patch.tiles.len()
    );
    let mut next = 1usize;
    for t in &patch.tiles {
        let _ = writeln!(out, "o tile_{}", t.id);
        for v in &t.polygon_mm {
            let _ = writeln!(out, "v {} {} 0", v[0], v[1]);
        }
        out.push('f');
        for k in 0..t.polygon_mm.len() {
            let _ = write!(out, " {}", next + k);
        }
        out.push('\n');
        next += t.polygon_mm.len();
    }
    out
}

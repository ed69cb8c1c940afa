//! The printed sheet as one solid: every tile footprint extruded to the sheet thickness,
//! every hinge footprint to the lamella thickness (both from z = 0, the bottom face), united
//! by a mesh boolean of `manifold-rust` (a pure-Rust port of the Manifold library, whose
//! union returns a closed, manifold, consistently oriented mesh or an error status).
//!
//! The result is accepted only when the library reports no error and the mesh decomposes
//! into exactly one body; anything else is a typed error, never a file.

use super::error::PrintError;
use super::layout::PrintLayout;
use super::mesh::PrintMesh;
use super::settings::PrintSettings;
use crate::math::Real;
use crate::stop::KeepGoing;
use manifold_rust::linalg::Vec2 as MVec2;
use manifold_rust::manifold::Manifold;
use manifold_rust::types::Error as Status;

/// The united solid of `layout`. `keep_going` is polled before every tile's and slab's
/// prism and before the union ([`PrintError::Cancelled`] once it says stop).
pub fn print_solid(
    layout: &PrintLayout,
    settings: &PrintSettings,
    keep_going: KeepGoing<'_>,
) -> Result<PrintMesh, PrintError> {
    let tiles = prisms(layout.tiles.iter(), settings.thickness_mm, keep_going)?;
    let slabs = prisms(
        layout.hinges.iter().map(|h| &h.polygon),
        settings.lamella_mm,
        keep_going,
    )?;
    if !keep_going() {
        return Err(PrintError::Cancelled);
    }
    let body = Manifold::compose(&tiles).union(&Manifold::compose(&slabs));
    check(&body, "union")?;
    let bodies = body.decompose().len();
    if bodies != 1 {
        return Err(PrintError::NotOneSolid {
            reason: format!("{bodies} separate bodies"),
        });
    }
    let gl = body.get_mesh_gl64(-1);
    let stride = usize::try_from(gl.num_prop).unwrap_or(0).max(3);
    let positions: Vec<[Real; 3]> = gl
        .vert_properties
        .chunks_exact(stride)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    let index = |i: u64| {
        u32::try_from(i)
            .ok()
            .filter(|&i| (i as usize) < positions.len())
    };
    let mut triangles = Vec::with_capacity(gl.tri_verts.len() / 3);
    for t in gl.tri_verts.chunks_exact(3) {
        match (index(t[0]), index(t[1]), index(t[2])) {
            (Some(a), Some(b), Some(c)) => triangles.push([a, b, c]),
            _ => {
                return Err(PrintError::NotOneSolid {
                    reason: "the mesh has a triangle index out of range".into(),
                })
            }
        }
    }
    if positions.iter().flatten().any(|x| !x.is_finite()) {
        return Err(PrintError::NotOneSolid {
            reason: "the mesh has a non-finite vertex".into(),
        });
    }
    Ok(PrintMesh {
        positions,
        triangles,
    })
}

/// Each footprint extruded from z = 0 to `height`.
fn prisms<'a>(
    polygons: impl Iterator<Item = &'a Vec<[Real; 2]>>,
    height: Real,
    keep_going: KeepGoing<'_>,
) -> Result<Vec<Manifold>, PrintError> {
    polygons
        .map(|poly| {
            if !keep_going() {
                return Err(PrintError::Cancelled);
            }
            let outline: Vec<MVec2> = poly.iter().map(|p| MVec2::new(p[0], p[1])).collect();
            let prism = Manifold::extrude(&vec![outline], height, 0, 0.0, MVec2::new(1.0, 1.0));
            check(&prism, "extrusion")?;
            Ok(prism)
        })
        .collect()
}

fn check(m: &Manifold, step: &str) -> Result<(), PrintError> {
    match m.status() {
        Status::NoError => Ok(()),
        status => Err(PrintError::NotOneSolid {
            reason: format!("{step} failed ({status:?})"),
        }),
    }
}

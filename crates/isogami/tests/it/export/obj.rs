//! OBJ, read back with the tobj crate: one model per tile, one face with the tile's vertices.

use super::fixtures::{area, open, DESIGNS};
use isogami::export::obj::obj_text;

#[test]
fn obj_files_load_in_tobj_with_one_face_per_tile() {
    for (p, spec) in open().iter().zip(DESIGNS) {
        let text = obj_text(p, "isogami test");
        let options = tobj::LoadOptions {
            triangulate: false,
            single_index: true,
            ..Default::default()
        };
        let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .unwrap_or_else(|e| panic!("{spec}: {e}"));
        assert_eq!(models.len(), p.tiles.len(), "{spec}");
        let mut vertices = 0;
        for (m, t) in models.iter().zip(&p.tiles) {
            assert_eq!(m.name, format!("tile_{}", t.id));
            let n = t.polygon_mm.len();
            let mesh = &m.mesh;
            assert_eq!(mesh.positions.len(), 3 * n);
            assert_eq!(mesh.indices.len(), n);
            if n > 3 {
                assert_eq!(mesh.face_arities, vec![n as u32]);
            }
            let poly: Vec<[f64; 2]> = mesh
                .indices
                .iter()
                .map(|&i| {
                    let i = i as usize;
                    assert_eq!(mesh.positions[3 * i + 2], 0.0);
                    [
                        mesh.positions[3 * i] as f64,
                        mesh.positions[3 * i + 1] as f64,
                    ]
                })
                .collect();
            // tobj reads f32: compare at single precision.
            for (a, b) in poly.iter().zip(&t.polygon_mm) {
                assert!((a[0] - b[0]).abs() < 1e-3 && (a[1] - b[1]).abs() < 1e-3);
            }
            assert!(area(&poly) > 0.0, "counter-clockwise face, normal +z");
            vertices += n;
        }
        let v_lines = text.lines().filter(|l| l.starts_with("v ")).count();
        assert_eq!(v_lines, vertices);
        assert_eq!(
            text.lines().filter(|l| l.starts_with("f ")).count(),
            p.tiles.len()
        );
    }
}

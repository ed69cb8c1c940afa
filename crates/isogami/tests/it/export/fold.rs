//! FOLD: the spec's fields checked on the JSON value (not through our types), the round trip
//! through our reader, faces = tiles, one frame per state, joints coinciding in every frame.

use super::fixtures::{area, closed, dist, open, DESIGNS, EDGE_MM};
use isogami::export::fold::{fold_file, fold_text, read_fold};
use isogami::export::ExportError;
use serde_json::Value;

/// Property names FOLD 1.1 defines (doc/spec.md); any other key must be namespaced with ':'.
const SPEC_KEYS: &[&str] = &[
    "file_spec",
    "file_creator",
    "file_author",
    "file_title",
    "file_description",
    "file_classes",
    "file_frames",
    "frame_author",
    "frame_title",
    "frame_description",
    "frame_classes",
    "frame_attributes",
    "frame_unit",
    "frame_parent",
    "frame_inherit",
    "vertices_coords",
    "vertices_vertices",
    "vertices_faces",
    "vertices_edges",
    "edges_vertices",
    "edges_faces",
    "edges_assignment",
    "edges_foldAngle",
    "edges_length",
    "faces_vertices",
    "faces_edges",
    "faces_faces",
    "faceOrders",
    "edgeOrders",
];
const UNITS: &[&str] = &["unit", "in", "pt", "m", "cm", "mm", "um", "nm"];
const ASSIGNMENTS: &[&str] = &["B", "M", "V", "F", "U", "C", "J"];
const FILE_CLASSES: &[&str] = &["singleModel", "multiModel", "animation", "diagrams"];
const FRAME_CLASSES: &[&str] = &["creasePattern", "foldedForm", "graph", "linkage"];

fn coords(v: &Value) -> Vec<[f64; 2]> {
    v.as_array()
        .expect("vertices_coords is an array")
        .iter()
        .map(|c| {
            let c = c.as_array().expect("a coordinate array");
            assert!(c.len() == 2 || c.len() == 3);
            [c[0].as_f64().unwrap(), c[1].as_f64().unwrap()]
        })
        .collect()
}

/// Checks a FOLD value against the spec's rules; returns the vertex count.
fn check_spec(v: &Value) -> usize {
    let obj = v.as_object().expect("top level is a dictionary");
    for key in obj.keys() {
        assert!(
            SPEC_KEYS.contains(&key.as_str()) || key.contains(':'),
            "{key}"
        );
    }
    assert!(obj["file_spec"].is_number());
    assert!(obj["file_creator"].is_string());
    for c in obj["file_classes"].as_array().unwrap() {
        let c = c.as_str().unwrap();
        assert!(FILE_CLASSES.contains(&c) || c.contains(':'));
    }
    for c in obj["frame_classes"].as_array().unwrap() {
        let c = c.as_str().unwrap();
        assert!(FRAME_CLASSES.contains(&c) || c.contains(':'));
    }
    assert!(UNITS.contains(&obj["frame_unit"].as_str().unwrap()));
    let vc = coords(&obj["vertices_coords"]);
    let nv = vc.len();
    let ev = obj["edges_vertices"].as_array().unwrap();
    let ea = obj["edges_assignment"].as_array().unwrap();
    assert_eq!(ev.len(), ea.len());
    for (e, a) in ev.iter().zip(ea) {
        let e: Vec<u64> = e
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_u64().unwrap())
            .collect();
        assert_eq!(e.len(), 2);
        assert!(e[0] != e[1] && e.iter().all(|&x| (x as usize) < nv));
        assert!(ASSIGNMENTS.contains(&a.as_str().unwrap()));
    }
    for f in obj["faces_vertices"].as_array().unwrap() {
        let f: Vec<usize> = f
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_u64().unwrap() as usize)
            .collect();
        assert!(f.len() >= 3 && f.iter().all(|&x| x < nv));
        let poly: Vec<[f64; 2]> = f.iter().map(|&k| vc[k]).collect();
        assert!(area(&poly) > 0.0, "faces are counter-clockwise");
    }
    for (k, fr) in obj["file_frames"].as_array().unwrap().iter().enumerate() {
        let fr = fr.as_object().unwrap();
        for key in fr.keys() {
            assert!(!key.starts_with("file_"), "frame {k}: {key}");
            assert!(
                SPEC_KEYS.contains(&key.as_str()) || key.contains(':'),
                "{key}"
            );
        }
        assert!(fr["frame_inherit"].as_bool().unwrap());
        assert!((fr["frame_parent"].as_u64().unwrap() as usize) <= k);
        assert_eq!(coords(&fr["vertices_coords"]).len(), nv);
    }
    nv
}

#[test]
fn fold_files_follow_the_spec_and_round_trip() {
    for patches in [closed(), open()] {
        for (p, spec) in patches.iter().zip(DESIGNS) {
            let text = fold_text(p, "isogami test").unwrap();
            let value: Value = serde_json::from_str(&text).unwrap();
            let nv = check_spec(&value);
            assert_eq!(value["frame_unit"], "mm");
            let back = read_fold(&text).unwrap();
            assert_eq!(back, fold_file(p, "isogami test"), "{spec}");
            // Faces are the tiles, with their polygons; every tile has its own vertices.
            assert_eq!(back.faces_vertices.len(), p.tiles.len());
            let corners: usize = p.tiles.iter().map(|t| t.polygon_mm.len()).sum();
            assert_eq!(nv, corners);
            assert_eq!(back.edges_vertices.len(), corners);
            assert!(back.edges_assignment.iter().all(|a| a == "B"));
            for (f, t) in back.faces_vertices.iter().zip(&p.tiles) {
                for (&v, c) in f.iter().zip(&t.polygon_mm) {
                    assert_eq!(back.vertices_coords[v], *c);
                }
            }
            // One frame per state; joints are pairs of coinciding vertices in every frame.
            assert_eq!(back.file_frames.len(), p.states.len());
            assert_eq!(back.joints.len(), p.joints.len());
            let frames = std::iter::once(&back.vertices_coords)
                .chain(back.file_frames.iter().map(|f| &f.vertices_coords));
            for vc in frames {
                for [a, b] in &back.joints {
                    assert!(dist(vc[*a], vc[*b]) <= 1e-9 * EDGE_MM, "{spec}");
                }
            }
        }
    }
}

#[test]
fn the_fold_reader_refuses_inconsistent_files() {
    let p = &closed()[0];
    let mut value: Value = serde_json::from_str(&fold_text(p, "t").unwrap()).unwrap();
    let nv = value["vertices_coords"].as_array().unwrap().len();
    value["edges_vertices"][3][1] = Value::from(nv);
    let err = read_fold(&value.to_string()).unwrap_err();
    assert!(
        matches!(err, ExportError::Read { format: "FOLD", .. }),
        "{err}"
    );
    assert!(err.to_string().contains("edge 3"), "{err}");
    let mut value: Value = serde_json::from_str(&fold_text(p, "t").unwrap()).unwrap();
    value["file_frames"][1]["vertices_coords"]
        .as_array_mut()
        .unwrap()
        .pop();
    assert!(read_fold(&value.to_string()).is_err());
    assert!(read_fold("{\"file_spec\": 1.1}").is_err());
}

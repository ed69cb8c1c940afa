//! Laser export (issue 10): SVG and DXF sheets read back by parsers that are not ours (usvg,
//! the `dxf` crate), the material left after cutting rebuilt with `geo` and compared with
//! the design: one piece, tiles joined exactly at the design's joints, each bridge as wide as
//! asked, no cut crossing another. PNG renders of the sheets go to
//! `target/export-artifacts/` for looking at.

#[path = "laser/mod.rs"]
mod laser;

use geo::Coord;
use isogami::export::laser::{laser_dxf, laser_svg, LaserSettings, LaserSheet};
use isogami::render::{png_from_svg, Fonts};
use laser::{has_concave_tile, judge, largest_piece, patch, ReadBack, TestPatch};
use resvg::usvg;

/// The designs checked: rotating squares, samples of ten other families, and three designs
/// with concave tiles.
const DESIGNS: &[(&str, i32, i32)] = &[
    ("rotating-squares", 3, 3),
    (
        "IH1:0.12239750492,0.5,0.143395479017,0.625:2x1:--bbb-",
        3,
        3,
    ),
    (
        "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:a--aa-",
        3,
        3,
    ),
    ("IH40::1x1:bbabbbbba", 3, 3),
    ("IH44:0.5,0.102564102564:1x1:-aaa", 3, 3),
    ("IH53:0.5,0.102564102564,0.102564102564:1x1:bbaab-b-", 3, 3),
    ("IH61::1x1:aaaa", 3, 3),
    ("IH78:0.230769230769:1x1:bbaaab", 3, 3),
    ("IH85:0.5,0.196416770201:1x1:abbbbb", 3, 3),
    ("IH88::1x1:bbbaabbab", 3, 3),
    ("IH90::1x1:aaa", 3, 3),
    // Concave tiles (one degree of freedom at these shapes).
    ("IH1:0.25,0.35,0.15,0.5:2x1:--bbb-", 3, 3),
    ("IH2:0.25,0.8,0.25,0.25:1x1:a--aa-", 3, 3),
    ("IH44:0.35,0.15:1x1:-aaa", 3, 3),
    ("IH53:0.35,0.15,0.35:1x1:bbaab-b-", 3, 3),
];

fn sheet_of(p: &TestPatch, spec: &str, settings: &LaserSettings) -> LaserSheet {
    let meta = vec![("spec".to_string(), spec.to_string())];
    LaserSheet::new(p.tiles.clone(), &p.joints, settings.clone(), meta)
        .unwrap_or_else(|e| panic!("{spec}: {e}"))
}

/// Cut paths of an SVG as usvg parses them: paths stroked in `colour`, mapped back from
/// the canvas to user units (mm) and from the file's y-down frame to the patch's.
fn read_svg(svg: &str, colour: [u8; 3]) -> (ReadBack, usvg::Tree) {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).unwrap();
    // The viewBox (user units) → canvas (px) mapping that usvg applies above every node.
    let vb: Vec<f32> = svg
        .split("viewBox=\"")
        .nth(1)
        .and_then(|rest| rest.split('"').next())
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    let (sx, sy) = (tree.size().width() / vb[2], tree.size().height() / vb[3]);
    let to_user = usvg::Transform::from_row(sx, 0.0, 0.0, sy, -vb[0] * sx, -vb[1] * sy)
        .invert()
        .unwrap();
    let mut rb = ReadBack::default();
    fn walk(g: &usvg::Group, colour: [u8; 3], to_user: &usvg::Transform, rb: &mut ReadBack) {
        for node in g.children() {
            match node {
                usvg::Node::Group(g) => walk(g, colour, to_user, rb),
                usvg::Node::Path(p) => {
                    let Some(stroke) = p.stroke() else { continue };
                    let usvg::Paint::Color(c) = stroke.paint() else {
                        continue;
                    };
                    if [c.red, c.green, c.blue] != colour {
                        continue;
                    }
                    let ts = to_user.pre_concat(p.abs_transform());
                    let map = |pt: usvg::tiny_skia_path::Point| {
                        let mut q = pt;
                        ts.map_point(&mut q);
                        Coord {
                            x: f64::from(q.x),
                            y: -f64::from(q.y),
                        }
                    };
                    let mut current: Vec<Coord> = Vec::new();
                    let mut closed = false;
                    for seg in p.data().segments() {
                        use usvg::tiny_skia_path::PathSegment as S;
                        match seg {
                            S::MoveTo(pt) => current = vec![map(pt)],
                            S::LineTo(pt) => current.push(map(pt)),
                            S::Close => closed = true,
                            _ => panic!("curves in a laser path"),
                        }
                    }
                    if closed {
                        rb.loops.push(current);
                    } else {
                        for w in current.windows(2) {
                            rb.segments.push([w[0], w[1]]);
                        }
                    }
                }
                _ => {}
            }
        }
    }
    walk(tree.root(), colour, &to_user, &mut rb);
    (rb, tree)
}

/// Cut paths of a DXF as the `dxf` crate reads them: LINEs on CUT, closed POLYLINEs on
/// OUTLINE.
fn read_dxf(text: &str) -> (ReadBack, dxf::Drawing) {
    let drawing = dxf::Drawing::load(&mut std::io::Cursor::new(text.as_bytes())).unwrap();
    let mut rb = ReadBack::default();
    for e in drawing.entities() {
        match (&e.specific, e.common.layer.as_str()) {
            (dxf::entities::EntityType::Line(l), "CUT") => rb.segments.push([
                Coord {
                    x: l.p1.x,
                    y: l.p1.y,
                },
                Coord {
                    x: l.p2.x,
                    y: l.p2.y,
                },
            ]),
            (dxf::entities::EntityType::Polyline(p), "OUTLINE") => {
                assert!(p.is_closed());
                rb.loops.push(
                    p.vertices()
                        .map(|v| Coord {
                            x: v.location.x,
                            y: v.location.y,
                        })
                        .collect(),
                );
            }
            (dxf::entities::EntityType::Text(_), "ENGRAVE") => rb.labels += 1,
            (_, layer) => panic!("unexpected entity on layer {layer}"),
        }
    }
    (rb, drawing)
}

/// Every check of the issue on one read-back.
fn assert_sound(spec: &str, what: &str, rb: &ReadBack, p: &TestPatch, s: &LaserSettings) {
    let v = judge(rb, p, s.kerf_mm);
    assert_eq!(
        v.pieces, 1,
        "{spec} {what}: material in {} pieces",
        v.pieces
    );
    assert_eq!(v.crossing_cuts, 0, "{spec} {what}: cuts cross");
    assert_eq!(
        (v.tile_pieces, v.tiles_hit_once),
        (p.tiles.len(), p.tiles.len()),
        "{spec} {what}: tiles joined other than across their edges"
    );
    let mut bridged = 0;
    for (tiles, joints, lengths) in &v.crossings {
        assert_eq!(
            lengths.len(),
            *joints,
            "{spec} {what}: edge {tiles:?} with {joints} joints crossed by {lengths:?}"
        );
        for l in lengths {
            assert!(
                (l - s.hinge_mm).abs() <= 0.01 * s.hinge_mm,
                "{spec} {what}: bridge {tiles:?} is {l} mm, asked {}",
                s.hinge_mm
            );
        }
        bridged += joints;
    }
    assert_eq!(
        bridged,
        p.joints.len(),
        "{spec} {what}: joints off shared edges"
    );
}

fn artefact_dir() -> std::path::PathBuf {
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/export-artifacts");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn laser_sheets_read_back_as_one_piece_joined_exactly_at_the_joints() {
    let settings = LaserSettings {
        labels: true,
        ..LaserSettings::default()
    };
    let fonts = Fonts::system();
    let mut concave = 0;
    for (spec, r, c) in DESIGNS {
        let p = largest_piece(patch(spec, *r, *c, 20.0));
        let started = std::time::Instant::now();
        concave += usize::from(has_concave_tile(&p));
        let sheet = sheet_of(&p, spec, &settings);
        let svg = laser_svg(&sheet);
        let (rb, tree) = read_svg(&svg, [0, 0, 0]);
        assert_sound(spec, "svg", &rb, &p, &settings);
        // Page size in mm: usvg converts mm to px at 96 per inch.
        let width_mm = f64::from(tree.size().width()) * 25.4 / 96.0;
        let xs = rb.loops.iter().flatten().map(|c| c.x);
        let (lo, hi) = xs.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
        assert!(
            (width_mm - (hi - lo + 2.0 * settings.margin_mm)).abs() < 1e-3,
            "{spec}"
        );

        let dxf_text = laser_dxf(&sheet);
        let (rb, drawing) = read_dxf(&dxf_text);
        assert_eq!(
            drawing.header.default_drawing_units,
            dxf::enums::Units::Millimeters
        );
        let layers: Vec<&str> = drawing.layers().map(|l| l.name.as_str()).collect();
        for l in ["CUT", "SCORE", "OUTLINE"] {
            assert!(layers.contains(&l), "{spec}: no layer {l} in {layers:?}");
        }
        assert_sound(spec, "dxf", &rb, &p, &settings);
        assert_eq!(rb.labels, p.tiles.len(), "{spec}: one label per tile");

        eprintln!(
            "{spec}: {} tiles, {} joints, concave {}, svg {} B, dxf {} B, {:?}",
            p.tiles.len(),
            p.joints.len(),
            has_concave_tile(&p),
            svg.len(),
            dxf_text.len(),
            started.elapsed()
        );
        let png = png_from_svg(&svg, 1200, &fonts).unwrap();
        let name: String = spec
            .chars()
            .map(|ch| if ch.is_ascii_alphanumeric() { ch } else { '_' })
            .collect();
        let dir = artefact_dir();
        std::fs::write(dir.join(format!("laser-{name}.png")), png).unwrap();
        std::fs::write(dir.join(format!("laser-{name}.svg")), &svg).unwrap();
        std::fs::write(dir.join(format!("laser-{name}.dxf")), &dxf_text).unwrap();
    }
    assert!(
        concave >= 3,
        "only {concave} designs with concave tiles checked"
    );
}

/// The oracle is not blind: a sheet laid out without one of the design's joints is seen as
/// missing that bridge (the edge is crossed by no material), and a sheet cut with a wider
/// hinge than asked is seen as too wide.
#[test]
fn the_read_back_check_sees_a_missing_joint_and_a_wrong_width() {
    let p = largest_piece(patch("rotating-squares", 2, 2, 20.0));
    let settings = LaserSettings::default();
    let fewer = TestPatch {
        tiles: p.tiles.clone(),
        joints: p.joints[1..].to_vec(),
    };
    let sheet = sheet_of(&fewer, "rotating-squares", &settings);
    let (rb, _) = read_dxf(&laser_dxf(&sheet));
    let v = judge(&rb, &p, settings.kerf_mm);
    let wrong = v.crossings.iter().filter(|(_, j, l)| l.len() != *j).count();
    assert_eq!(wrong, 1);

    let wide = LaserSettings {
        hinge_mm: 1.6,
        ..settings.clone()
    };
    let (rb, _) = read_dxf(&laser_dxf(&sheet_of(&p, "rotating-squares", &wide)));
    let v = judge(&rb, &p, settings.kerf_mm);
    for (_, _, lengths) in &v.crossings {
        for l in lengths {
            assert!((l - 1.6).abs() < 0.016 && (l - settings.hinge_mm).abs() > 0.015);
        }
    }
}

/// Bad values are refused with one line naming them.
#[test]
fn bad_laser_values_are_refused() {
    let p = patch("rotating-squares", 2, 2, 20.0);
    let try_with = |s: LaserSettings| {
        LaserSheet::new(p.tiles.clone(), &p.joints, s, Vec::new())
            .map(|_| ())
            .unwrap_err()
            .to_string()
    };
    let e = try_with(LaserSettings {
        hinge_mm: 25.0,
        ..LaserSettings::default()
    });
    assert!(e.contains("does not fit") && !e.contains('\n'), "{e}");
    let e = try_with(LaserSettings {
        kerf_mm: 0.0,
        ..LaserSettings::default()
    });
    assert!(e.contains("kerf_mm must be positive"), "{e}");
    let e = try_with(LaserSettings {
        hinge_mm: f64::INFINITY,
        ..LaserSettings::default()
    });
    assert!(e.contains("finite"), "{e}");
    let e = try_with(LaserSettings {
        kerf_mm: 21.0,
        hinge_mm: 0.5,
        ..LaserSettings::default()
    });
    assert!(e.contains("kerf") || e.contains("does not fit"), "{e}");
}

/// The library path the CLI takes: `patch_at` (the export Patch, deployed) then
/// `laser_sheet`, read back and judged on the patch's own closed polygons and joints.
#[test]
fn sheets_of_export_patches_read_back_sound() {
    use isogami::export::laser::laser_sheet;
    use isogami::export::{patch_at, PatchRequest};
    let settings = LaserSettings::default();
    // The completed sheets (the default) of rotating squares and IH44, and the rectangle of
    // IH53, which is locked by contact (no completion: it does not open).
    for (spec, complete) in [
        ("rotating-squares", true),
        ("IH44:0.5,0.027564102564:1x2:-aaabbaa", true),
        ("IH53:0.35,0.15,0.35:1x1:bbaab-b-", false),
    ] {
        let design = isogami::api::resolve_design(spec).unwrap();
        let request = PatchRequest {
            rows: 3,
            cols: 3,
            complete,
            ..PatchRequest::default()
        };
        let patch = patch_at(&design, &request).unwrap();
        let sheet = laser_sheet(&patch, settings.clone()).unwrap();
        let whole = TestPatch {
            tiles: patch.closed_polygons_mm.clone(),
            joints: patch
                .joints
                .iter()
                .map(|j| isogami::export::laser::JointAt {
                    tiles: [j.a, j.b],
                    point: patch.closed_polygons_mm[j.a][j.vertex_a],
                })
                .collect(),
        };
        let p = largest_piece(whole);
        assert_eq!(sheet.tiles.len(), p.tiles.len(), "{spec}");
        let (rb, _) = read_svg(&laser_svg(&sheet), [0, 0, 0]);
        assert_sound(spec, "patch svg", &rb, &p, &settings);
        let (rb, _) = read_dxf(&laser_dxf(&sheet));
        assert_sound(spec, "patch dxf", &rb, &p, &settings);
        let svg = laser_svg(&sheet);
        assert!(
            svg.contains(&format!("spec: {design}")) && svg.contains("hinge_mm: 1.5"),
            "metadata names the design and settings"
        );
    }
}

#[test]
fn engraved_labels_are_the_tiles_ids_in_the_other_files() {
    // A raw 2x2 patch with one tile held by no joint: the laser sheet leaves it off, and the
    // labels of the tiles after it must still be their ids in the tile table, FOLD, OBJ and
    // kirigami_sim files (issue 23 item 13: label k sat on tile id k + 1).
    use isogami::api::resolve_design;
    use isogami::export::laser::laser_sheet;
    use isogami::export::{patch_at, PatchRequest};
    let design = resolve_design("IH21:0.104512294489,0.65:1x1:--aaab----bbaba").unwrap();
    let request = PatchRequest {
        rows: 2,
        cols: 2,
        complete: false,
        ..PatchRequest::default()
    };
    let patch = patch_at(&design, &request).unwrap();
    let settings = LaserSettings {
        labels: true,
        ..LaserSettings::default()
    };
    let sheet = laser_sheet(&patch, settings).unwrap();
    assert!(sheet.tiles.len() < patch.tiles.len(), "a tile is left off");
    for (k, &id) in sheet.tile_ids.iter().enumerate() {
        // The kept tile k is the patch's tile `id`, closed polygon for closed polygon.
        assert_eq!(sheet.tiles[k], patch.closed_polygons_mm[id], "tile {k}");
        assert_eq!(patch.tiles[id].id, id);
    }
    assert!(sheet.tile_ids.iter().enumerate().any(|(k, &id)| id != k));
    // The SVG engraves exactly those numbers, and the DXF too.
    let svg = laser_svg(&sheet);
    let mut engraved: Vec<usize> = svg
        .split("<text ")
        .skip(1)
        .map(|t| t.split('>').nth(1).unwrap().split('<').next().unwrap())
        .map(|n| n.parse().unwrap())
        .collect();
    engraved.sort_unstable();
    let mut ids = sheet.tile_ids.clone();
    ids.sort_unstable();
    assert_eq!(engraved, ids);
    let dxf = laser_dxf(&sheet);
    for id in &ids {
        assert!(
            dxf.contains(&format!("\n  1\n{id}\n")),
            "DXF lacks label {id}"
        );
    }
}

//! `isogami export --sheet`: a graded sheet (issue 25) written in every format, checked
//! against the sheet's own numbers (its closed nodes, its optimised poses, its pins) rather
//! than against the library's patch; bad sheet files refused in one line with exit code 2
//! and no file written.

use crate::common;
use common::{isogami, scratch};
use isogami::api::{graded_sheet, GradedRun};
use isogami::graded::{GradedRequest, GradedSheet, SolveSettings};
use resvg::usvg;
use std::collections::HashMap;
use std::path::Path;
use std::sync::OnceLock;

type P = [f64; 2];

/// One small graded sheet (2×2 cells of rotating squares, 16 tiles) for every test here,
/// graded once.
fn graded() -> &'static GradedRun {
    static RUN: OnceLock<GradedRun> = OnceLock::new();
    RUN.get_or_init(|| {
        let request = GradedRequest {
            design: "rotating-squares".into(),
            rows: 2,
            cols: 2,
            states: 4,
            solve: SolveSettings {
                max_iterations: 80,
                ..Default::default()
            },
            ..Default::default()
        };
        graded_sheet(&request, &mut |_| true, isogami::stop::NEVER).expect("grades")
    })
}

/// Writes the run as `isogami graded --out` does and returns its path.
fn run_file(dir: &Path) -> String {
    let path = dir.join("sheet.json");
    std::fs::write(&path, serde_json::to_string(graded()).unwrap()).unwrap();
    path.to_string_lossy().into_owned()
}

/// Runs `isogami export --sheet` (must succeed) and returns what it printed.
fn export(sheet: &str, format: &str, out: &Path, extra: &[&str]) -> String {
    let out = out.to_string_lossy();
    let args = [
        &[
            "export", "--sheet", sheet, "--format", format, "--out", &out,
        ][..],
        extra,
    ]
    .concat();
    let o = isogami(&args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Plain 2D helpers, so the checks do not borrow the library's geometry.
mod plane {
    use super::P;
    pub fn dist(a: P, b: P) -> f64 {
        (a[0] - b[0]).hypot(a[1] - b[1])
    }
    pub fn area(poly: &[P]) -> f64 {
        let n = poly.len();
        0.5 * (0..n)
            .map(|i| {
                let (p, q) = (poly[i], poly[(i + 1) % n]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum::<f64>()
    }
    /// Distance from p to the segment ab.
    pub fn to_segment(p: P, a: P, b: P) -> f64 {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
        dist(p, [a[0] + t * dx, a[1] + t * dy])
    }
    pub fn lower(polys: &[Vec<P>]) -> P {
        polys
            .iter()
            .flatten()
            .fold([f64::MAX; 2], |m, p| [m[0].min(p[0]), m[1].min(p[1])])
    }
}
use plane::{area, dist, lower, to_segment};

fn closed(sheet: &GradedSheet) -> Vec<Vec<P>> {
    (0..sheet.tiles.len())
        .map(|i| sheet.closed_polygon(i).iter().map(|v| [v.x, v.y]).collect())
        .collect()
}

fn opened(sheet: &GradedSheet) -> Vec<Vec<P>> {
    (0..sheet.tiles.len())
        .map(|i| sheet.opened_polygon(i).iter().map(|v| [v.x, v.y]).collect())
        .collect()
}

/// The closed sheet's edges (node pairs), each once, with how many tiles have them.
fn edges(sheet: &GradedSheet) -> HashMap<(usize, usize), usize> {
    let mut e = HashMap::new();
    for t in &sheet.tiles {
        let n = t.nodes.len();
        for k in 0..n {
            let (p, q) = (t.nodes[k], t.nodes[(k + 1) % n]);
            *e.entry((p.min(q), p.max(q))).or_insert(0) += 1;
        }
    }
    e
}

/// Millimetres per sheet unit at a mean edge of `edge_mm` (mean over the closed edges,
/// each once).
fn scale(sheet: &GradedSheet, edge_mm: f64) -> f64 {
    let e = edges(sheet);
    let total: f64 = e
        .keys()
        .map(|&(p, q)| dist(sheet.nodes[p], sheet.nodes[q]))
        .sum();
    edge_mm / (total / e.len() as f64)
}

/// Polygons scaled by `s` and shifted so that their bounding box starts at (0, 0): where
/// the export puts every set of polygons.
fn placed(polys: &[Vec<P>], s: f64) -> Vec<Vec<P>> {
    let lo = lower(polys);
    polys
        .iter()
        .map(|p| {
            p.iter()
                .map(|v| [(v[0] - lo[0]) * s, (v[1] - lo[1]) * s])
                .collect()
        })
        .collect()
}

fn close(a: &[Vec<P>], b: &[Vec<P>], tol: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: tile count");
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        assert_eq!(p.len(), q.len(), "{what}: tile {i}");
        for (k, (u, v)) in p.iter().zip(q).enumerate() {
            assert!(
                dist(*u, *v) <= tol,
                "{what}: tile {i} corner {k}: {u:?} vs {v:?}"
            );
        }
    }
}

/// Every pin's node at the same place on both its tiles, within `tol` mm.
fn pins_meet(sheet: &GradedSheet, polys: &[Vec<P>], tol: f64, what: &str) {
    for (k, j) in sheet.joints.iter().enumerate() {
        let at = |t: usize| {
            let v = sheet.tiles[t]
                .nodes
                .iter()
                .position(|&n| n == j.node)
                .unwrap();
            polys[t][v]
        };
        let gap = dist(at(j.a), at(j.b));
        assert!(gap <= tol, "{what}: pin {k} open by {gap} mm");
    }
}

/// Every tile the closed tile moved rigidly: same edge lengths (scaled).
fn rigid(closed_mm: &[Vec<P>], polys: &[Vec<P>], what: &str) {
    for (i, (c, p)) in closed_mm.iter().zip(polys).enumerate() {
        let n = c.len();
        for k in 0..n {
            let (a, b) = (dist(c[k], c[(k + 1) % n]), dist(p[k], p[(k + 1) % n]));
            assert!(
                (a - b).abs() <= 1e-6 * a,
                "{what}: tile {i} edge {k}: {a} vs {b}"
            );
        }
    }
}

/// The laser SVG (read by usvg, a hair of kerf) cuts along exactly the closed sheet's shared
/// edges, short of a bridge at the pins (and relief cuts at outline corners where tiles
/// meet), and its outline encloses exactly the tiles' closed area at the asked mean edge
/// length.
#[test]
fn the_laser_svg_cuts_the_graded_closed_sheet() {
    let dir = scratch("graded-svg");
    let sheet = &graded().sheet;
    let file = run_file(dir.path());
    let svg = dir.path().join("s.svg");
    let kerf = 0.001;
    let said = export(
        &file,
        "svg",
        &svg,
        &["--edge-mm", "20", "--kerf-mm", &kerf.to_string()],
    );
    assert!(said.contains("16 tiles, 24 joints"), "{said}");
    let tree = usvg::Tree::from_str(
        &std::fs::read_to_string(&svg).unwrap(),
        &usvg::Options::default(),
    )
    .unwrap();
    // usvg works in px at 96 per inch, y down; back to mm with y up.
    let mm = 25.4 / 96.0;
    let mut outline: Vec<Vec<P>> = Vec::new();
    let mut cuts: Vec<[P; 2]> = Vec::new();
    fn walk(g: &usvg::Group, out: &mut Vec<(String, Vec<P>)>, mm: f64) {
        for node in g.children() {
            match node {
                usvg::Node::Group(g) => walk(g, out, mm),
                usvg::Node::Path(p) => {
                    let t = p.abs_transform();
                    let mut pts = Vec::new();
                    for seg in p.data().segments() {
                        use usvg::tiny_skia_path::PathSegment;
                        if let PathSegment::MoveTo(mut q) | PathSegment::LineTo(mut q) = seg {
                            t.map_point(&mut q);
                            pts.push([f64::from(q.x) * mm, -f64::from(q.y) * mm]);
                        }
                    }
                    out.push((p.id().to_string(), pts));
                }
                _ => {}
            }
        }
    }
    let mut paths = Vec::new();
    walk(tree.root(), &mut paths, mm);
    for (id, pts) in paths {
        if id.starts_with("outline-") {
            outline.push(pts);
        } else if id.starts_with("cut-") {
            assert_eq!(pts.len(), 2, "{id}");
            cuts.push([pts[0], pts[1]]);
        }
    }
    assert_eq!(
        outline.len(),
        1,
        "one outline loop round a sheet without holes"
    );
    let s = scale(sheet, 20.0);
    let closed_mm = closed(sheet);
    let tiles_area: f64 = closed_mm.iter().map(|p| area(p)).sum::<f64>() * s * s;
    // The outline runs kerf/2 outside the tiles.
    let ring = &outline[0];
    let perimeter: f64 = (0..ring.len())
        .map(|k| dist(ring[k], ring[(k + 1) % ring.len()]))
        .sum();
    let outline_area = area(ring).abs() - 0.5 * kerf * perimeter;
    assert!(
        (outline_area - tiles_area).abs() < 1e-5 * tiles_area,
        "outline {outline_area} mm² vs tiles {tiles_area} mm²"
    );
    // The SVG's coordinates are the closed sheet's moved: match the outline's lower corner.
    let lo_svg = lower(&outline);
    let closed_mm = placed(&closed_mm, s);
    let cuts: Vec<[P; 2]> = cuts
        .iter()
        .map(|c| c.map(|p| [p[0] - lo_svg[0], p[1] - lo_svg[1]]))
        .collect();
    let node_at = |n: usize| {
        let (t, v) = sheet
            .tiles
            .iter()
            .enumerate()
            .find_map(|(t, tile)| tile.nodes.iter().position(|&m| m == n).map(|v| (t, v)))
            .unwrap();
        closed_mm[t][v]
    };
    let shared: Vec<(P, P)> = edges(sheet)
        .into_iter()
        .filter(|&(_, count)| count == 2)
        .map(|((p, q), _)| (node_at(p), node_at(q)))
        .collect();
    let tol = 2e-3;
    // Relief cuts (see `export::laser::cuts`): where two or more tiles meet at a corner of the
    // outline, a cut from that node out to the outline path, kerf/2 away (more at a sharp
    // mitre); the graded sheet's outline has such corners.
    let edge_count = edges(sheet);
    let reliefs: Vec<P> = (0..sheet.nodes.len())
        .filter(|&n| {
            let tiles = sheet.tiles.iter().filter(|t| t.nodes.contains(&n)).count();
            let on_outline = edge_count
                .iter()
                .any(|(&(p, q), &count)| count == 1 && (p == n || q == n));
            tiles >= 2 && on_outline
        })
        .map(node_at)
        .collect();
    let mut cut_on = vec![0.0; shared.len()];
    for c in &cuts {
        match shared
            .iter()
            .position(|&(a, b)| to_segment(c[0], a, b) < tol && to_segment(c[1], a, b) < tol)
        {
            Some(k) => cut_on[k] += dist(c[0], c[1]),
            None => assert!(
                dist(c[0], c[1]) < 5.0 * kerf
                    && reliefs
                        .iter()
                        .any(|&v| dist(c[0], v) < tol || dist(c[1], v) < tol),
                "cut {c:?} is on no shared edge of the closed sheet and is no relief cut"
            ),
        }
    }
    let hinge = 1.5;
    for (k, &(a, b)) in shared.iter().enumerate() {
        let len = dist(a, b);
        assert!(
            cut_on[k] <= len + tol && cut_on[k] >= len - 2.0 * hinge - tol,
            "edge {k} ({len} mm) cut over {} mm",
            cut_on[k]
        );
    }
}

/// The opened state (`--t open`) puts every tile at its optimised pose, at the asked scale;
/// the pins meet; the closed state (`--t 0`) is the closed nodes; both in the tile table.
#[test]
fn the_tile_table_places_tiles_at_the_optimised_and_the_closed_poses() {
    let dir = scratch("graded-table");
    let run = graded();
    let sheet = &run.sheet;
    let file = run_file(dir.path());
    let read = |t: &str, name: &str| -> serde_json::Value {
        let out = dir.path().join(name);
        export(&file, "tiles-json", &out, &["--t", t, "--edge-mm", "15"]);
        serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap()
    };
    let polys = |v: &serde_json::Value| -> Vec<Vec<P>> {
        v["tiles"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| serde_json::from_value(r["polygon_mm"].clone()).unwrap())
            .collect()
    };
    let s = scale(sheet, 15.0);
    let closed_mm = placed(&closed(sheet), s);
    let open = read("open", "open.json");
    assert_eq!(open["t"], 1.0);
    assert!((open["edge_mm"].as_f64().unwrap() - 15.0).abs() < 1e-9);
    let open_mm = polys(&open);
    close(&open_mm, &placed(&opened(sheet), s), 1e-9, "opened");
    rigid(&closed_mm, &open_mm, "opened");
    pins_meet(sheet, &open_mm, run.report.joint_gap * s + 1e-9, "opened");
    for (row, pose) in open["tiles"].as_array().unwrap().iter().zip(&sheet.opened) {
        assert_eq!(row["pose"]["theta"].as_f64().unwrap(), pose.theta);
    }
    let shut = read("0", "closed.json");
    let shut_mm = polys(&shut);
    close(&shut_mm, &closed_mm, 1e-9, "closed");
    pins_meet(sheet, &shut_mm, 1e-9, "closed");
    for (i, p) in shut_mm.iter().enumerate() {
        let want = area(&closed(sheet)[i]) * s * s;
        assert!((area(p) - want).abs() < 1e-9 * want, "tile {i}");
    }
}

/// FOLD: the closed sheet as key frame, then the path check's states from closed to the
/// optimised opened state; in every frame every tile is its closed shape moved rigidly and
/// the pins meet (to the path check's own gap).
#[test]
fn fold_frames_follow_the_path_from_closed_to_opened() {
    let dir = scratch("graded-fold");
    let run = graded();
    let sheet = &run.sheet;
    let file = run_file(dir.path());
    let out = dir.path().join("s.fold");
    export(&file, "fold", &out, &["--frames", "5"]);
    let fold: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(fold["frame_unit"], "mm");
    let faces: Vec<Vec<usize>> = serde_json::from_value(fold["faces_vertices"].clone()).unwrap();
    assert_eq!(faces.len(), sheet.tiles.len());
    let as_polys = |coords: &serde_json::Value| -> Vec<Vec<P>> {
        let v: Vec<P> = serde_json::from_value(coords.clone()).unwrap();
        faces
            .iter()
            .map(|f| f.iter().map(|&k| v[k]).collect())
            .collect()
    };
    let s = scale(sheet, 20.0);
    let closed_mm = placed(&closed(sheet), s);
    close(
        &as_polys(&fold["vertices_coords"]),
        &closed_mm,
        1e-9,
        "key frame",
    );
    let frames = fold["file_frames"].as_array().unwrap();
    let t: Vec<f64> = frames
        .iter()
        .map(|f| f["isogami:t"].as_f64().unwrap())
        .collect();
    // The path check's 21 states (openings 1, 0.95, …, 0) thinned to 5, evenly spaced.
    assert_eq!(t.len(), 5, "{t:?}");
    for (want, got) in [0.0, 0.25, 0.5, 0.75, 1.0].iter().zip(&t) {
        assert!((want - got).abs() < 1e-12, "{t:?}");
    }
    let gap = run
        .path
        .states
        .iter()
        .map(|s| s.joint_gap)
        .fold(run.report.joint_gap, f64::max);
    for (k, f) in frames.iter().enumerate() {
        let polys = as_polys(&f["vertices_coords"]);
        rigid(&closed_mm, &polys, &format!("frame {k}"));
        pins_meet(sheet, &polys, gap * s + 1e-9, &format!("frame {k}"));
    }
    close(
        &as_polys(&frames[0]["vertices_coords"]),
        &closed_mm,
        1e-9,
        "first frame",
    );
    let open_mm = placed(&opened(sheet), s);
    close(
        &as_polys(&frames[4]["vertices_coords"]),
        &open_mm,
        1e-9,
        "last frame",
    );
    // FOLD's own pin pairs are the sheet's pins.
    assert_eq!(
        fold["isogami:joints"].as_array().unwrap().len(),
        sheet.joints.len()
    );
}

/// The remaining formats: DXF read by the dxf crate (CUT and OUTLINE layers, as many cut
/// lines as the SVG), OBJ one object per tile, CSV one row per tile, kirigami_sim one line
/// per tile and per pin, STL and 3MF a mesh in millimetres.
#[test]
fn every_other_format_writes_the_graded_sheet() {
    let dir = scratch("graded-formats");
    let sheet = &graded().sheet;
    let (tiles, pins) = (sheet.tiles.len(), sheet.joints.len());
    let file = run_file(dir.path());
    let path = |name: &str| dir.path().join(name);

    export(&file, "svg", &path("s.svg"), &[]);
    let svg_cuts = std::fs::read_to_string(path("s.svg"))
        .unwrap()
        .matches("id=\"cut-")
        .count();
    export(&file, "dxf", &path("s.dxf"), &[]);
    let drawing = dxf::Drawing::load_file(path("s.dxf").to_str().unwrap()).unwrap();
    let layers: Vec<String> = drawing.layers().map(|l| l.name.clone()).collect();
    assert!(layers.iter().any(|l| l == "CUT") && layers.iter().any(|l| l == "OUTLINE"));
    let dxf_cuts = drawing
        .entities()
        .filter(|e| {
            e.common.layer == "CUT" && matches!(e.specific, dxf::entities::EntityType::Line(_))
        })
        .count();
    assert_eq!(dxf_cuts, svg_cuts);

    export(&file, "obj", &path("s.obj"), &["--t", "open"]);
    let obj = std::fs::read_to_string(path("s.obj")).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("o ")).count(), tiles);

    export(&file, "tiles-csv", &path("s.csv"), &[]);
    let csv = std::fs::read_to_string(path("s.csv")).unwrap();
    assert_eq!(csv.lines().count(), tiles + 1);

    export(&file, "kirigami-sim", &path("sim"), &[]);
    let lines = |name: &str| {
        std::fs::read_to_string(path("sim").join(name))
            .unwrap()
            .lines()
            .count()
    };
    assert_eq!(lines("vertices.txt"), tiles);
    assert_eq!(lines("constraints.txt"), pins);
    assert!(lines("hull_vertices.txt") >= 3);

    export(&file, "stl", &path("s.stl"), &[]);
    let stl = std::fs::read(path("s.stl")).unwrap();
    let triangles = u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize;
    assert!(triangles > 0 && stl.len() == 84 + 50 * triangles);

    let said = export(&file, "3mf", &path("s.3mf"), &["--t", "open"]);
    assert!(said.contains("t = 1.0000"), "{said}");
    let mut zip = zip::ZipArchive::new(std::fs::File::open(path("s.3mf")).unwrap()).unwrap();
    let mut model = String::new();
    std::io::Read::read_to_string(&mut zip.by_name("3D/3dmodel.model").unwrap(), &mut model)
        .unwrap();
    assert!(model.contains("unit=\"millimeter\""));
}

/// A bare graded sheet (no path check) is read too: its own path's states between the
/// closed and the opened one.
#[test]
fn a_bare_graded_sheet_is_exported_with_its_own_path() {
    let dir = scratch("graded-bare");
    let sheet = &graded().sheet;
    let file = dir.path().join("bare.json");
    std::fs::write(&file, serde_json::to_string(sheet).unwrap()).unwrap();
    let out = dir.path().join("s.fold");
    export(file.to_str().unwrap(), "fold", &out, &["--frames", "100"]);
    let fold: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let t: Vec<f64> = fold["file_frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["isogami:t"].as_f64().unwrap())
        .collect();
    assert_eq!(t.len(), sheet.path.len() + 2, "{t:?}");
    assert_eq!((t[0], *t.last().unwrap()), (0.0, 1.0));
    assert!(t.windows(2).all(|w| w[0] < w[1]), "{t:?}");
}

/// Every bad sheet file fails in one line naming the problem, exit code 2, and writes
/// nothing.
#[test]
fn bad_sheet_files_are_refused_in_one_line_and_write_nothing() {
    let dir = scratch("graded-bad");
    let good = serde_json::to_string(graded()).unwrap();
    let mut short: serde_json::Value = serde_json::from_str(&good).unwrap();
    short["sheet"]["opened"].as_array_mut().unwrap().pop();
    let mut stray: serde_json::Value = serde_json::from_str(&good).unwrap();
    stray["sheet"]["joints"][0]["node"] = 10_000.into();
    let nan = good.replacen("\"length_scale\":1.0", "\"length_scale\":NaN", 1);
    assert_ne!(nan, good, "the run's length scale is written as 1.0");
    let cases: [(&str, Option<String>, &str); 7] = [
        ("missing", None, "cannot read"),
        ("text", Some("a graded sheet, honestly".into()), "not JSON"),
        ("nan", Some(nan), "not JSON"),
        ("list", Some("[1, 2]".into()), "not a graded sheet"),
        (
            "other",
            Some("{\"design\": \"rotating-squares\"}".into()),
            "not a graded sheet",
        ),
        (
            "short",
            Some(short.to_string()),
            "15 opened poses for 16 tiles",
        ),
        ("stray", Some(stray.to_string()), "joint 0's node"),
    ];
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    for (name, text, says) in cases {
        let file = dir.path().join(format!("{name}.json"));
        if let Some(text) = text {
            std::fs::write(&file, text).unwrap();
        }
        for format in ["svg", "fold"] {
            let target = out.join(format!("x.{format}"));
            let o = isogami(&[
                "export",
                "--sheet",
                file.to_str().unwrap(),
                "--format",
                format,
                "--out",
                target.to_str().unwrap(),
            ]);
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
            assert_eq!(stderr.lines().count(), 1, "{name}: {stderr}");
            assert!(
                stderr.starts_with("error: --sheet") && stderr.contains(says),
                "{name}: {stderr}"
            );
        }
    }
    // --sheet is instead of --design, and takes none of a design's patch flags.
    let file = run_file(dir.path());
    let target = out.join("x.svg");
    for extra in [
        &["--design", "rotating-squares"][..],
        &["--patch", "2x2"],
        &["--raw"],
    ] {
        let args = [
            &["export", "--sheet", &file, "--format", "svg"][..],
            &["--out", target.to_str().unwrap()],
            extra,
        ]
        .concat();
        let o = isogami(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{extra:?}: {stderr}");
    }
    assert_eq!(
        std::fs::read_dir(&out).unwrap().count(),
        0,
        "nothing written"
    );
}

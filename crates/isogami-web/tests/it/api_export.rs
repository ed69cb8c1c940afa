//! The export endpoints: the formats list is the library's; every download is the library's
//! export of the same request, byte for byte, with its media type and a file name of the
//! design, patch and extension; an SVG is read back by usvg with its page size in mm; a
//! folder format arrives as a zip of its files; every bad value is a 400 with the library's
//! one-line message; deployments past the time limit are 422 `timeout` and stop when their
//! client goes away; a read-only server still exports.

use crate::common;

use axum::body::Body;
use axum::http::{header, Request, StatusCode};
use common::{app, app_with, assert_error, catalogue, enc, get, summaries, Reply};
use http_body_util::BodyExt;
use isogami::api::resolve_design;
use isogami::export::laser::{LaserSettings, Material};
use isogami::export::{
    export_design, ExportFiles, ExportOptions, Format, PatchRequest, Scale, State,
};
use isogami_web::{slug, ServerSettings};
use resvg::usvg;
use serde_json::Value;
use std::io::Read;
use std::time::{Duration, Instant};
use tower::ServiceExt;

/// A design with two degrees of freedom that takes about 1500 small steps at kerf 1e-4 (as in
/// api_limits.rs).
const LONG: &str = "IH84:0.5,0.196416770201:1x1:aa-";
const LONG_KERF: f64 = 1e-4;

/// `GET uri` with its Content-Disposition header.
async fn download(app: &axum::Router, uri: &str) -> (Reply, String) {
    let response = app
        .clone()
        .oneshot(Request::builder().uri(uri).body(Body::empty()).unwrap())
        .await
        .unwrap();
    let disposition = response
        .headers()
        .get(header::CONTENT_DISPOSITION)
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let status = response.status();
    let content_type = response
        .headers()
        .get(header::CONTENT_TYPE)
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let body = response
        .into_body()
        .collect()
        .await
        .unwrap()
        .to_bytes()
        .to_vec();
    (
        Reply {
            status,
            content_type,
            body,
        },
        disposition,
    )
}

/// What the library writes for `design` with `request`, `format` and `options`.
fn library(
    design: &str,
    request: &PatchRequest,
    format: Format,
    options: &ExportOptions,
) -> ExportFiles {
    let design = resolve_design(design).unwrap();
    export_design(&design, request, format, options, &mut |_| true)
        .unwrap()
        .1
}

fn spec_of(design: &str) -> String {
    resolve_design(design).unwrap().to_string()
}

#[tokio::test]
async fn the_formats_list_is_the_librarys() {
    let v = get(&app(), "/api/export/formats").await.ok();
    let formats = v["formats"].as_array().unwrap();
    let names: Vec<&str> = formats
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, Format::ALL.map(Format::name));
    for (f, entry) in Format::ALL.iter().zip(formats) {
        assert_eq!(entry["description"], f.description());
        assert_eq!(entry["media_type"], f.media_type());
        assert_eq!(entry["extension"].as_str(), f.extension());
        assert_eq!(entry["folder"], f.extension().is_none());
        let laser = entry["settings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|s| s == "laser");
        assert_eq!(laser, f.uses_laser_settings(), "{f}");
        assert_eq!(entry["uses_state"], f.uses_state(), "{f}");
    }
    // The limits the page checks rows × columns against before asking.
    assert_eq!(v["limits"]["max_patch"], isogami::export::MAX_PATCH);
    assert_eq!(
        v["limits"]["max_tiles"],
        isogami_web::export::MAX_EXPORT_TILES
    );
    // The laser group's fields carry the library's defaults and presets.
    let group = v["settings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["name"] == "laser")
        .unwrap();
    let field = |name: &str| {
        group["fields"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["name"] == name)
            .unwrap_or_else(|| panic!("no field {name}"))
            .clone()
    };
    let d = LaserSettings::default();
    assert_eq!(field("hinge_mm")["default"], d.hinge_mm);
    assert_eq!(field("kerf_mm")["default"], d.kerf_mm);
    assert_eq!(field("labels")["kind"], "flag");
    let presets = field("material")["choices"].as_array().unwrap().clone();
    assert_eq!(presets.len(), Material::ALL.len());
    for (m, p) in Material::ALL.iter().zip(&presets) {
        assert_eq!(p["value"], m.name());
        assert_eq!(p["sets"]["hinge_mm"], m.numbers().hinge_mm);
    }
    let defaults = PatchRequest::default();
    assert_eq!(v["defaults"]["rows"], defaults.rows);
    assert_eq!(v["defaults"]["frames"], defaults.frames);
    assert_eq!(v["limits"]["max_patch"], isogami::export::MAX_PATCH);
}

#[tokio::test]
async fn every_format_downloads_the_librarys_bytes_with_its_type_and_name() {
    let app = app();
    let design = &summaries(&catalogue().db)[0].spec;
    let spec = spec_of(design);
    let request = PatchRequest {
        rows: 2,
        cols: 3,
        scale: Scale::EdgeMm(12.5),
        state: State::T(0.5),
        kerf: 0.02,
        frames: 4,
        complete: false,
        region: None,
    };
    for format in Format::ALL {
        let uri = format!(
            "/api/export?design={}&format={format}&patch=2x3&edge_mm=12.5&t=0.5&kerf=0.02&frames=4&raw=true",
            enc(design)
        );
        let (reply, disposition) = download(&app, &uri).await;
        assert_eq!(reply.status, StatusCode::OK, "{format}: {}", reply.text());
        let stem = format!("{}-2x3", slug(&spec));
        match library(design, &request, format, &ExportOptions::default()) {
            ExportFiles::One(bytes) => {
                assert_eq!(reply.content_type, format.media_type(), "{format}");
                let ext = format.extension().unwrap();
                assert_eq!(
                    disposition,
                    format!("attachment; filename=\"{stem}.{ext}\"")
                );
                assert!(reply.body == bytes, "{format}: not the library's bytes");
            }
            ExportFiles::Folder(files) => {
                assert_eq!(reply.content_type, "application/zip", "{format}");
                assert_eq!(
                    disposition,
                    format!("attachment; filename=\"{stem}.{format}.zip\"")
                );
                let mut zip = zip::ZipArchive::new(std::io::Cursor::new(&reply.body)).unwrap();
                assert_eq!(zip.len(), files.len());
                for (k, (name, bytes)) in files.iter().enumerate() {
                    let mut entry = zip.by_index(k).unwrap();
                    assert_eq!(entry.name(), *name);
                    let mut read = Vec::new();
                    entry.read_to_end(&mut read).unwrap();
                    assert!(read == *bytes, "{format}/{name} differs");
                }
            }
        }
    }
}

#[tokio::test]
async fn the_kirigami_sim_zip_holds_its_four_files() {
    let (reply, _) = download(
        &app(),
        "/api/export?design=rotating-squares&format=kirigami-sim&patch=3x2",
    )
    .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.text());
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(&reply.body)).unwrap();
    let mut names: Vec<String> = zip.file_names().map(String::from).collect();
    names.sort();
    assert_eq!(
        names,
        [
            "constraints.txt",
            "hull_tiles.txt",
            "hull_vertices.txt",
            "vertices.txt"
        ]
    );
    // One constraint line per pin of the patch: the library's patch says how many.
    let request = PatchRequest {
        rows: 3,
        cols: 2,
        ..PatchRequest::default()
    };
    let design = resolve_design("rotating-squares").unwrap();
    let (patch, _) = export_design(
        &design,
        &request,
        Format::Fold,
        &ExportOptions::default(),
        &mut |_| true,
    )
    .unwrap();
    let mut text = String::new();
    zip.by_name("constraints.txt")
        .unwrap()
        .read_to_string(&mut text)
        .unwrap();
    let lines = text.lines().filter(|l| !l.trim().is_empty()).count();
    assert_eq!(lines, patch.joints.len());
    assert!(lines > 0);
}

/// `width` and `height` of the root element as written.
fn page_size(svg: &str) -> (String, String) {
    let tag = &svg[svg.find("<svg").unwrap()..];
    let tag = &tag[..tag.find('>').unwrap()];
    let attr = |name: &str| {
        let at = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        tag[at..at + tag[at..].find('"').unwrap()].to_string()
    };
    (attr("width"), attr("height"))
}

#[tokio::test]
async fn an_svg_reads_back_with_its_page_in_millimetres() {
    let (w, margin, kerf) = (120.0, 4.0, 0.3);
    let uri = format!(
        "/api/export?design=rotating-squares&format=svg&patch=2x3&width_mm={w}&margin_mm={margin}\
         &kerf_mm={kerf}&material=felt&labels=true"
    );
    let (reply, disposition) = download(&app(), &uri).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.text());
    assert_eq!(reply.content_type, "image/svg+xml");
    assert!(disposition.starts_with("attachment; filename=\""));
    assert!(disposition.ends_with("-2x3.svg\""), "{disposition}");
    let text = reply.text();
    let (width, height) = page_size(&text);
    let mm = |s: &str| -> f64 {
        s.strip_suffix("mm")
            .unwrap_or_else(|| panic!("{s} is not in mm"))
            .parse()
            .unwrap()
    };
    let tree = usvg::Tree::from_str(&text, &usvg::Options::default()).unwrap();
    // usvg turns mm into px at 96 per inch.
    let px = |v: f64| v * 96.0 / 25.4;
    assert!((f64::from(tree.size().width()) - px(mm(&width))).abs() < 1e-2);
    assert!((f64::from(tree.size().height()) - px(mm(&height))).abs() < 1e-2);
    // The closed rotating-squares patch is a rectangle `w` wide; the outline is cut kerf/2
    // outside it and the page adds the margin on both sides.
    assert!(
        (mm(&width) - (w + kerf + 2.0 * margin)).abs() < 1e-3,
        "page width {width}"
    );
    // A cut group of paths and the engraved labels asked for.
    let cut = text.find("<g id=\"cut\"").expect("a cut group");
    assert!(text[cut..].contains("<path "));
    assert!(text.contains("<text"), "labels=true engraves tile numbers");
    let mut strokes = 0;
    fn walk(g: &usvg::Group, n: &mut usize) {
        for node in g.children() {
            match node {
                usvg::Node::Group(g) => walk(g, n),
                usvg::Node::Path(p) if p.stroke().is_some() => *n += 1,
                _ => {}
            }
        }
    }
    walk(tree.root(), &mut strokes);
    assert!(strokes > 6, "{strokes} stroked paths");
    // felt's thickness, the margin and kerf given, in the metadata.
    assert!(text.contains("material: felt"));
    assert!(text.contains(&format!("kerf_mm: {kerf}")));
}

#[tokio::test]
async fn bad_values_are_400_with_the_librarys_message() {
    let app = app();
    let base = "/api/export?design=rotating-squares";
    let lib = |r: PatchRequest| r.validate().unwrap_err().to_string();
    let d = PatchRequest::default();
    let cases: Vec<(String, String)> = vec![
        (
            format!("{base}&format=step"),
            "step".parse::<Format>().unwrap_err().to_string(),
        ),
        (
            format!("{base}&format=svg&patch=41x41"),
            lib(PatchRequest {
                rows: 41,
                cols: 41,
                ..d.clone()
            }),
        ),
        (
            format!("{base}&format=svg&t=1.5"),
            lib(PatchRequest {
                state: State::T(1.5),
                ..d.clone()
            }),
        ),
        (
            format!("{base}&format=fold&edge_mm=-3"),
            lib(PatchRequest {
                scale: Scale::EdgeMm(-3.0),
                ..d.clone()
            }),
        ),
        (
            format!("{base}&format=obj&width_mm=0"),
            lib(PatchRequest {
                scale: Scale::WidthMm(0.0),
                ..d.clone()
            }),
        ),
        (
            format!("{base}&format=svg&hinge_mm=-1"),
            LaserSettings {
                hinge_mm: -1.0,
                ..LaserSettings::default()
            }
            .validate()
            .unwrap_err()
            .to_string(),
        ),
        (
            format!("{base}&format=dxf&thickness_mm=0"),
            LaserSettings {
                thickness_mm: 0.0,
                ..LaserSettings::default()
            }
            .validate()
            .unwrap_err()
            .to_string(),
        ),
    ];
    for (uri, message) in &cases {
        let reply = get(&app, uri).await;
        assert_eq!(
            assert_error(&reply, StatusCode::BAD_REQUEST, uri),
            "bad_parameter"
        );
        assert_eq!(reply.json()["error"], message.as_str(), "{uri}");
    }
    // A hinge wider than the edges it sits on is found while laying out the sheet.
    let uri = format!("{base}&format=svg&patch=2x2&hinge_mm=1000");
    let reply = get(&app, &uri).await;
    assert_error(&reply, StatusCode::BAD_REQUEST, &uri);
    let message = reply.json()["error"].as_str().unwrap().to_string();
    assert!(
        message.starts_with("hinge 1000 mm does not fit"),
        "{message}"
    );
    // Designs that cannot be read.
    for design in ["nope", "IH1:0.1:1x1:a", "{\"family\":", "IH999:1:1x1:-"] {
        let uri = format!("/api/export?design={}&format=svg", enc(design));
        let kind = assert_error(&get(&app, &uri).await, StatusCode::BAD_REQUEST, &uri);
        assert!(
            kind == "bad_design" || kind == "ill_shaped",
            "{uri}: {kind}"
        );
    }
    // Malformed or unknown keys, missing ones, repeated ones.
    for uri in [
        "/api/export".to_string(),
        base.to_string(),
        "/api/export?format=svg".to_string(),
        format!("{base}&format=svg&patch=6"),
        format!("{base}&format=svg&t=soon"),
        format!("{base}&format=svg&edge_mm=1&width_mm=1"),
        format!("{base}&format=svg&hinge_mm=wide"),
        format!("{base}&format=svg&material=wood"),
        format!("{base}&format=svg&labels=yes%20please"),
        format!("{base}&format=svg&colour=red"),
        format!("{base}&format=svg&format=dxf"),
        format!("{base}&format=svg&frames=1000"),
        format!("{base}&format=fold&patch=40x40&frames=100"),
        format!("{base}&format=svg&kerf=NaN"),
        format!("/api/export?design={}&format=svg", "x".repeat(17 * 1024)),
    ] {
        assert_error(&get(&app, &uri).await, StatusCode::BAD_REQUEST, &uri);
    }
    // The export is a GET: a POST is 405.
    let reply = common::post(&app, "/api/export?design=x&format=svg", "").await;
    assert_error(&reply, StatusCode::METHOD_NOT_ALLOWED, "POST /api/export");
}

#[tokio::test]
async fn rigid_designs_are_explained_as_for_live_deployment() {
    // rotating-squares with every joint welded cannot move.
    let spec = spec_of("rotating-squares");
    let mut parts: Vec<&str> = spec.split(':').collect();
    let welded = "x".repeat(parts.last().unwrap().len());
    *parts.last_mut().unwrap() = &welded;
    let uri = format!("/api/export?design={}&format=fold", enc(&parts.join(":")));
    let kind = assert_error(
        &get(&app(), &uri).await,
        StatusCode::UNPROCESSABLE_ENTITY,
        &uri,
    );
    assert_eq!(kind, "rigid");
}

#[tokio::test]
async fn exports_past_the_time_limit_are_422_timeout_and_read_only_servers_export() {
    let quick = app_with(
        &catalogue().db,
        ServerSettings {
            sim_timeout: Duration::from_millis(5),
            ..ServerSettings::default()
        },
    );
    let uri = format!(
        "/api/export?design={}&format=fold&kerf={LONG_KERF}",
        enc(LONG)
    );
    let started = Instant::now();
    let reply = get(&quick, &uri).await;
    assert_eq!(
        assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, &uri),
        "timeout"
    );
    assert!(started.elapsed() < Duration::from_secs(5));

    let read_only = app_with(
        &catalogue().db,
        ServerSettings {
            allow_save: false,
            ..ServerSettings::default()
        },
    );
    let reply = get(
        &read_only,
        "/api/export?design=rotating-squares&format=tiles-csv",
    )
    .await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.text());
    assert!(reply.content_type.starts_with("text/csv"));
}

/// While a long export runs the server answers other requests; when its client goes away the
/// deployment stops soon after (dropping the runtime waits for the blocking task).
#[test]
fn an_export_stops_when_its_client_leaves() {
    let design = resolve_design(LONG).unwrap();
    // The rectangle as it is: this design has no one-DOF completion.
    let request = PatchRequest {
        rows: 1,
        cols: 1,
        kerf: LONG_KERF,
        complete: false,
        ..PatchRequest::default()
    };
    let start = Instant::now();
    export_design(
        &design,
        &request,
        Format::Fold,
        &ExportOptions::default(),
        &mut |_| true,
    )
    .unwrap();
    let full = start.elapsed();

    let app = app_with(
        &catalogue().db,
        ServerSettings {
            sim_timeout: Duration::from_secs(600),
            ..ServerSettings::default()
        },
    );
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let start = Instant::now();
    runtime.block_on(async {
        let long = {
            let app = app.clone();
            let uri = format!(
                "/api/export?design={}&format=fold&patch=1x1&kerf={LONG_KERF}&raw=true",
                enc(LONG)
            );
            tokio::spawn(async move { get(&app, &uri).await })
        };
        let reply = get(&app, "/api/export/formats").await;
        assert_eq!(reply.status, StatusCode::OK);
        assert!(
            !long.is_finished(),
            "the formats list waited for the export"
        );
        tokio::time::sleep(full / 10).await;
        assert!(!long.is_finished());
        long.abort();
    });
    drop(runtime);
    let stopped = start.elapsed();
    assert!(
        stopped < full * 2 / 5,
        "the export ran on for {stopped:?} after its client left (a full run takes {full:?})"
    );
}

#[tokio::test]
async fn the_static_site_lists_the_same_formats() {
    let dir = common::Scratch::new("export-site");
    let out = dir.path().join("site");
    isogami_web::write_site(&catalogue().db, &out, &mut |_, _| {}).unwrap();
    let site: Value =
        serde_json::from_slice(&std::fs::read(out.join("data/site.json")).unwrap()).unwrap();
    let served = get(&app(), "/api/export/formats").await.ok();
    assert_eq!(site["export"], served);
}

#[tokio::test]
async fn print_formats_take_the_print_group_and_refuse_a_hinge_below_the_nozzle() {
    use isogami::export::print3d::PrintSettings;
    let app = app();
    let v = get(&app, "/api/export/formats").await.ok();
    let group = v["settings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["name"] == "print")
        .expect("a print group")
        .clone();
    let d = PrintSettings::default();
    let default_of = |name: &str| {
        group["fields"]
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["name"] == name)
            .unwrap_or_else(|| panic!("no field {name}"))["default"]
            .clone()
    };
    assert_eq!(default_of("hinge_mm"), d.hinge_mm);
    assert_eq!(default_of("lamella_mm"), d.lamella_mm);
    assert_eq!(default_of("nozzle_mm"), d.nozzle_mm);
    for f in Format::ALL {
        let entry = v["formats"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["name"] == f.name())
            .unwrap();
        let print = entry["settings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|s| s == "print");
        assert_eq!(print, matches!(f, Format::Stl | Format::ThreeMf), "{f}");
    }

    // The query's print values reach the library: the STL equals the library's with them.
    let request = PatchRequest {
        rows: 2,
        cols: 2,
        ..PatchRequest::default()
    };
    let options = ExportOptions {
        print: PrintSettings {
            thickness_mm: 3.0,
            hinge_mm: 1.2,
            lamella_mm: 0.6,
            gap_mm: 0.5,
            nozzle_mm: 0.4,
        },
        ..ExportOptions::default()
    };
    let uri = "/api/export?design=rotating-squares&format=stl&patch=2x2&thickness_mm=3\
               &hinge_mm=1.2&lamella_mm=0.6&gap_mm=0.5&nozzle_mm=0.4";
    let (reply, _) = download(&app, uri).await;
    assert_eq!(reply.status, StatusCode::OK);
    let ExportFiles::One(expected) = library("rotating-squares", &request, Format::Stl, &options)
    else {
        panic!("STL is one file")
    };
    assert_eq!(reply.body, expected);
    let (default_reply, _) = download(
        &app,
        "/api/export?design=rotating-squares&format=stl&patch=2x2",
    )
    .await;
    assert_ne!(
        default_reply.body, reply.body,
        "the print values changed nothing"
    );

    // A hinge below the nozzle: the library's message, as a 400.
    let bad = ExportOptions {
        print: PrintSettings {
            hinge_mm: 0.3,
            ..PrintSettings::default()
        },
        ..ExportOptions::default()
    };
    let message = bad.validate(Format::Stl).unwrap_err().to_string();
    let reply = get(
        &app,
        "/api/export?design=rotating-squares&format=3mf&hinge_mm=0.3",
    )
    .await;
    assert_error(&reply, StatusCode::BAD_REQUEST, "hinge 0.3");
    assert_eq!(reply.json()["error"], message.as_str());
    assert!(message.contains("nozzle"), "{message}");
}

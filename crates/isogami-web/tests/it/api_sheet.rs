//! The finite-sheet endpoint (`GET /api/sheet`): its analysis and deployment are the library's
//! (`finite_sheet`, `deploy_sheet`) for the same request, value for value; its drawing places
//! every tile so that the two tiles of each pin meet at it; a completion that is refused comes
//! back as the library's reason beside the raw region; bad values are 400 with one line;
//! simulations past the time limit are 422 `timeout`. The export's default is the completed
//! sheet, `raw=true` (or `complete=false`) the rectangle, and a rectangle without a completion
//! is 422 with the library's reason and a hint to export it raw.

use crate::common;

use axum::body::Body;
use axum::http::{Request, StatusCode};
use common::{app_with, assert_error, catalogue, enc, get, numbers};
use isogami::api::{deploy_sheet, finite_sheet, resolve_design, SheetDeployRequest, SheetRequest};
use isogami::contact::ContactSettings;
use isogami::export::{export_design, ExportFiles, ExportOptions, Format, PatchRequest};
use isogami::finite::Region;
use isogami::kinematics::Mechanism;
use isogami::math::{rotation, Vec2};
use isogami_web::ServerSettings;
use serde_json::Value;
use std::time::{Duration, Instant};
use tower::ServiceExt;

/// A design whose raw 6×6 region flops and whose completion keeps 79.2 % of it, growing the
/// ring and pruning (the README's example).
const FLOPPY: &str = "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-";
/// A design whose cell is isostatic (2 tiles, 3 pins): no finite region of it has one DOF.
const ISOSTATIC: &str = "IH22:0.155769230769,0.35,0.150335752741:1x1:aa-a-";
/// A design with two degrees of freedom that takes about 1500 small steps at kerf 1e-4 (as in
/// api_limits.rs).
const LONG: &str = "IH84:0.5,0.196416770201:1x1:aa-";

/// The router with a time limit no test run reaches (debug builds on a busy machine).
fn app() -> axum::Router {
    app_with(
        &catalogue().db,
        ServerSettings {
            sim_timeout: Duration::from_secs(600),
            ..ServerSettings::default()
        },
    )
}

fn request(region: &str) -> SheetRequest {
    SheetRequest {
        region: region.parse().unwrap(),
        ..SheetRequest::default()
    }
}

/// Every tile of the drawing's sheet `poses` (of `tiles`, the analysis's list) placed: each pin
/// of the sheet is a vertex of both its tiles' drawn polygons, at the same point.
fn assert_pins_meet(design: &str, drawing: &Value, sheet: &Value, poses: &Value) {
    let design = resolve_design(design).unwrap();
    let cell = design.cell().unwrap();
    let mech = Mechanism::new(&cell, &design.joints).unwrap();
    let l = drawing["length_scale"].as_f64().unwrap();
    let tiles = sheet["tiles"].as_array().unwrap();
    let poses = poses.as_array().unwrap();
    assert_eq!(tiles.len(), poses.len());
    let polygons: Vec<Vec<Vec2>> = drawing["tiles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            p.as_array()
                .unwrap()
                .iter()
                .map(|v| Vec2::new(v[0].as_f64().unwrap(), v[1].as_f64().unwrap()))
                .collect()
        })
        .collect();
    let place = |n: usize, p: Vec2| {
        let pose = &poses[n];
        let at = Vec2::new(pose["x"].as_f64().unwrap(), pose["y"].as_f64().unwrap());
        at + rotation(pose["theta"].as_f64().unwrap()) * p
    };
    let joints = sheet["joints"].as_array().unwrap();
    assert!(!joints.is_empty());
    for j in joints {
        let (a, b) = (
            j["a"].as_u64().unwrap() as usize,
            j["b"].as_u64().unwrap() as usize,
        );
        let joint = &mech.joints[j["joint"].as_u64().unwrap() as usize];
        let (sa, sb) = (joint.s_a * l, joint.s_b * l);
        for (n, s) in [(a, sa), (b, sb)] {
            let k = tiles[n]["tile"].as_u64().unwrap() as usize;
            assert!(
                polygons[k].iter().any(|v| (v - s).norm() < 1e-9 * l),
                "the pin is a vertex of tile {k}'s polygon"
            );
        }
        let gap = (place(a, sa) - place(b, sb)).norm();
        assert!(gap < 1e-9 * l, "pin {j} opens by {gap}");
    }
}

#[tokio::test]
async fn the_analysis_is_the_librarys_and_the_drawing_joins_every_pin() {
    let app = app();
    let reply = get(
        &app,
        &format!("/api/sheet?design={}&region=6x6", enc(FLOPPY)),
    )
    .await;
    let v = reply.ok();
    let design = resolve_design(FLOPPY).unwrap();
    let library = finite_sheet(&design, &request("6x6"), &mut |_| true).unwrap();
    assert_eq!(v["analysis"], serde_json::to_value(&library).unwrap());
    assert!(v["refused"].is_null() && v["deployment"].is_null() && v["not_deployed"].is_null());
    // The raw region flops; the completion is one DOF and differs from it.
    let raw = &library.raw_mobility;
    assert!(raw.dof > 1 && !raw.floppy.is_empty(), "{} DOF", raw.dof);
    let c = library.completion.as_ref().unwrap();
    assert_eq!(c.mobility.dof, 1);
    assert!(!c.report.removed.is_empty() && !c.report.added.is_empty());
    let drawing = &v["drawing"];
    assert_pins_meet(FLOPPY, drawing, &v["analysis"]["raw"], &drawing["raw"]);
    assert_pins_meet(
        FLOPPY,
        drawing,
        &v["analysis"]["completion"]["sheet"],
        &drawing["completed"],
    );
    let mut all = Vec::new();
    numbers(&v, String::new(), &mut all);
    for (path, n) in all {
        assert!(!n.is_f64() || n.as_f64().unwrap().is_finite(), "{path}");
    }
}

#[tokio::test]
async fn a_deployment_is_the_librarys_without_repeating_the_analysis() {
    let app = app();
    let v = get(
        &app,
        "/api/sheet?design=rotating-squares&region=3x2&deploy=true&frames=5&kerf=0.02",
    )
    .await
    .ok();
    let design = resolve_design("rotating-squares").unwrap();
    let mut sheet = request("3x2");
    sheet.settings.contact = ContactSettings::with_kerf(0.02);
    let library = deploy_sheet(
        &design,
        &SheetDeployRequest {
            sheet,
            frames: 5,
            ..SheetDeployRequest::default()
        },
        &mut |_| true,
    )
    .unwrap();
    let mut want = serde_json::to_value(&library).unwrap();
    let analysis = want.as_object_mut().unwrap().remove("analysis").unwrap();
    assert_eq!(v["analysis"], analysis);
    assert_eq!(v["deployment"], want);
    let frames = v["deployment"]["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 5);
    let tiles = v["analysis"]["completion"]["sheet"]["tiles"]
        .as_array()
        .unwrap()
        .len();
    assert!(frames
        .iter()
        .all(|f| f["poses"].as_array().unwrap().len() == tiles));
    // The first frame is the closed sheet the drawing shows.
    let closed = &frames[0]["poses"];
    for (a, b) in closed
        .as_array()
        .unwrap()
        .iter()
        .zip(v["drawing"]["completed"].as_array().unwrap())
    {
        for key in ["x", "y", "theta"] {
            let (a, b) = (a[key].as_f64().unwrap(), b[key].as_f64().unwrap());
            assert!((a - b).abs() < 1e-9, "{key}: {a} vs {b}");
        }
    }
    // It opens: the hull grows on the way and the tiles leave their closed poses.
    assert!(v["deployment"]["max_hull_area_ratio"].as_f64().unwrap() > 1.1);
    let turned = frames[4]["poses"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["theta"].as_f64().unwrap().abs())
        .fold(0.0, f64::max);
    assert!(turned > 0.1, "largest tile rotation {turned}");
}

#[tokio::test]
async fn a_refused_completion_is_the_librarys_reason_beside_the_raw_region() {
    let app = app();
    let design = resolve_design(FLOPPY).unwrap();
    // Asking for all of the region refuses the completion that keeps 79 %.
    let strict = SheetRequest {
        min_covered: 1.0,
        ..request("6x6")
    };
    let e = finite_sheet(&design, &strict, &mut |_| true).unwrap_err();
    let raw = finite_sheet(
        &design,
        &SheetRequest {
            complete: false,
            ..strict.clone()
        },
        &mut |_| true,
    )
    .unwrap();
    for deploy in ["", "&deploy=true"] {
        let uri = format!(
            "/api/sheet?design={}&region=6x6&min_cover=100{deploy}",
            enc(FLOPPY)
        );
        let v = get(&app, &uri).await.ok();
        assert_eq!(v["refused"], e.to_string(), "{uri}");
        assert!(v["refused"]
            .as_str()
            .unwrap()
            .starts_with("no one-DOF sheet"));
        // The raw region's analysis, which carries the refusal too.
        let mut expected = serde_json::to_value(&raw).unwrap();
        expected["refusal"] = v["refused"].clone();
        assert_eq!(v["analysis"], expected);
        assert!(v["analysis"]["completion"].is_null() && v["drawing"]["completed"].is_null());
        assert!(v["deployment"].is_null());
        assert_eq!(v["not_deployed"].is_null(), deploy.is_empty(), "{uri}");
    }
    // A raw region that flops is analysed, and not deployed, with the library's reason.
    let uri = format!(
        "/api/sheet?design={}&region=6x6&raw=true&deploy=true",
        enc(FLOPPY)
    );
    let v = get(&app, &uri).await.ok();
    assert!(v["refused"].is_null());
    assert!(v["analysis"]["completion"].is_null());
    assert!(v["not_deployed"].as_str().unwrap().contains("complete it"));
}

#[tokio::test]
async fn bad_values_are_400_with_one_line() {
    let app = app();
    let lib_region = |text: &str| text.parse::<Region>().unwrap_err().to_string();
    for (query, needle) in [
        (
            "region=6x6".to_string(),
            "missing parameter design".to_string(),
        ),
        (
            "design=rotating-squares&region=hexagon".into(),
            lib_region("hexagon"),
        ),
        (
            "design=rotating-squares&region=0x4".into(),
            lib_region("0x4"),
        ),
        (
            "design=rotating-squares&region=polygon:0,0;1,0;0,1;1,1".into(),
            lib_region("polygon:0,0;1,0;0,1;1,1"),
        ),
        (
            "design=rotating-squares&region=20x20".into(),
            "at most 12x12".into(),
        ),
        (
            "design=rotating-squares&region=disc:1000".into(),
            "across".into(),
        ),
        ("design=rotating-squares&t=0".into(), "(0, 1]".into()),
        (
            "design=rotating-squares&min_cover=-5".into(),
            "covered fraction".into(),
        ),
        (
            "design=rotating-squares&deploy=true&frames=1".into(),
            "frames 1".into(),
        ),
        ("design=rotating-squares&kerf=NaN".into(), "kerf".into()),
        (
            "design=rotating-squares&spec=x".into(),
            "unknown parameter".into(),
        ),
        ("design=IH999:1:1x1:a".into(), "IH999".into()),
    ] {
        let uri = format!("/api/sheet?{query}");
        let reply = get(&app, &uri).await;
        assert_error(&reply, StatusCode::BAD_REQUEST, &uri);
        let message = reply.json()["error"].as_str().unwrap().to_string();
        assert!(message.contains(&needle), "{uri}: {message} lacks {needle}");
    }
    // A region in mm that holds no tile is the library's refusal, also 400.
    let reply = get(&app, "/api/sheet?design=rotating-squares&region=disc:0.01").await;
    assert_error(&reply, StatusCode::BAD_REQUEST, "tiny disc");
}

#[tokio::test]
async fn sheets_past_the_time_limit_are_422_timeout() {
    let quick = app_with(
        &catalogue().db,
        ServerSettings {
            sim_timeout: Duration::from_millis(5),
            ..ServerSettings::default()
        },
    );
    for extra in ["", "&deploy=true"] {
        let uri = format!(
            "/api/sheet?design={}&kerf=0.0001&region=2x2{extra}",
            enc(LONG)
        );
        let started = Instant::now();
        let reply = get(&quick, &uri).await;
        assert_eq!(
            assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, &uri),
            "timeout"
        );
        assert!(started.elapsed() < Duration::from_secs(5));
    }
}

/// Issue 42: 20 concurrent 12×12 deployments ran as 20 threads and answered after 10–12 s
/// against a 2 s limit. Sheets now take the heavy-job permits exports take and are answered
/// by their deadline: every one of a burst is answered within the limit and its grace (with
/// a margin for a loaded machine), as `timeout`, `busy` or a result.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_burst_of_big_sheets_is_answered_by_the_deadline() {
    let limit = Duration::from_millis(800);
    let app = app_with(
        &catalogue().db,
        ServerSettings {
            sim_timeout: limit,
            heavy_jobs: 2,
            ..ServerSettings::default()
        },
    );
    let uri = "/api/sheet?design=rotating-squares&region=12x12&deploy=true&frames=200";
    let started = Instant::now();
    let replies = futures_join_all((0..12).map(|_| {
        let app = app.clone();
        async move {
            let reply = get(&app, uri).await;
            (reply, started.elapsed())
        }
    }))
    .await;
    let mut kinds = Vec::new();
    for (reply, answered) in &replies {
        assert!(
            *answered < limit * 2 + Duration::from_millis(1500),
            "answered after {answered:?} with a {limit:?} limit: {}",
            reply.text()
        );
        if reply.status != 200 {
            kinds.push(reply.json()["kind"].as_str().unwrap_or("?").to_string());
        }
    }
    assert!(
        kinds.iter().all(|k| k == "timeout" || k == "busy"),
        "{kinds:?}"
    );
}

/// Runs every future at once, each as its own task.
async fn futures_join_all<F, T>(futures: impl Iterator<Item = F>) -> Vec<T>
where
    F: std::future::Future<Output = T> + Send + 'static,
    T: Send + 'static,
{
    let handles: Vec<_> = futures.map(tokio::spawn).collect();
    let mut out = Vec::new();
    for h in handles {
        out.push(h.await.unwrap());
    }
    out
}

/// What the library writes for `design` as a tiles CSV.
fn tiles_csv(design: &str, request: &PatchRequest) -> Vec<u8> {
    let design = resolve_design(design).unwrap();
    match export_design(
        &design,
        request,
        Format::TilesCsv,
        &ExportOptions::default(),
        &mut |_| true,
    )
    .unwrap()
    .1
    {
        ExportFiles::One(bytes) => bytes,
        ExportFiles::Folder(_) => unreachable!("a tiles CSV is one file"),
    }
}

#[tokio::test]
async fn exports_write_the_completed_sheet_unless_raw_is_asked() {
    let app = app();
    let base = format!(
        "/api/export?design={}&format=tiles-csv&patch=6x6",
        enc(FLOPPY)
    );
    let rect = PatchRequest {
        rows: 6,
        cols: 6,
        complete: false,
        ..PatchRequest::default()
    };
    let completed = tiles_csv(
        FLOPPY,
        &PatchRequest {
            complete: true,
            ..rect.clone()
        },
    );
    let raw = tiles_csv(FLOPPY, &rect);
    assert_ne!(completed, raw);
    for (query, want) in [
        ("", &completed),
        ("&raw=false", &completed),
        ("&complete=true", &completed),
        ("&raw=true", &raw),
        ("&complete=false", &raw),
    ] {
        let reply = get(&app, &format!("{base}{query}")).await;
        assert_eq!(reply.status, StatusCode::OK, "{query}: {}", reply.text());
        assert!(reply.body == *want, "{query}: not the library's file");
    }
    let reply = get(&app, &format!("{base}&raw=true&complete=true")).await;
    assert_error(&reply, StatusCode::BAD_REQUEST, "raw and complete");
    // The raw rectangle comes with the library's warning naming its DOF; the completion not.
    let warning = |query: &str| {
        let app = app.clone();
        let uri = format!("{base}{query}");
        async move {
            let response = app
                .oneshot(Request::builder().uri(uri).body(Body::empty()).unwrap())
                .await
                .unwrap();
            response.headers().get("x-isogami-warning").map(|v| {
                form_urlencoded::parse(format!("w={}", v.to_str().unwrap()).as_bytes())
                    .next()
                    .unwrap()
                    .1
                    .into_owned()
            })
        }
    };
    let design = resolve_design(FLOPPY).unwrap();
    let raw_dof = finite_sheet(&design, &request("6x6"), &mut |_| true)
        .unwrap()
        .raw_mobility
        .dof;
    let said = warning("&raw=true")
        .await
        .expect("a warning for the raw rectangle");
    assert!(
        said.contains(&format!("{raw_dof} degrees of freedom")),
        "{said}"
    );
    assert_eq!(warning("").await, None);
}

#[tokio::test]
async fn a_rectangle_without_a_completion_is_422_with_the_reason_and_the_raw_hint() {
    let app = app();
    // An isostatic cell (3 tiles' worth of freedom = 2 per pin): every finite sheet flops.
    let design = resolve_design(ISOSTATIC).unwrap();
    let e = finite_sheet(&design, &request("2x2"), &mut |_| true).unwrap_err();
    let uri = format!(
        "/api/export?design={}&format=fold&patch=2x2",
        enc(ISOSTATIC)
    );
    let reply = get(&app, &uri).await;
    assert_eq!(
        assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, &uri),
        "no_one_dof_sheet"
    );
    let v = reply.json();
    assert!(v["error"].as_str().unwrap().contains(&e.to_string()), "{v}");
    assert!(v["hint"].as_str().unwrap().contains("raw=true"), "{v}");
    let reply = get(&app, &format!("{uri}&raw=true")).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.text());
}

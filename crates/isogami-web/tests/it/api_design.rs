//! The design endpoints: stored design views (report, geometry and linkages agree with each
//! other and with the catalogue row), thumbnails read by a real SVG parser and renderer
//! (usvg/resvg), GIFs read by a GIF decoder, live deployments, and saving user designs.

use crate::common;

use axum::http::StatusCode;
use common::{
    app, app_with, assert_error, catalogue, enc, get, numbers, post_design, private_db, summaries,
};
use isogami_store::{Check, DesignSummary, Store};
use isogami_web::ServerSettings;
use serde_json::{json, Value};
use std::path::Path;

/// The spec of `s` with its joints replaced.
fn with_joints(s: &DesignSummary, joints: &str) -> String {
    let mut parts: Vec<&str> = s.spec.split(':').collect();
    *parts.last_mut().unwrap() = joints;
    parts.join(":")
}

/// `s` with its first shape parameter moved by `delta`: a design not in the database.
fn nudged(s: &DesignSummary, delta: f64) -> String {
    let mut params = s.params.clone();
    params[0] += delta;
    let params: Vec<String> = params.iter().map(f64::to_string).collect();
    format!("{}:{}:{}:{}", s.family, params.join(","), s.cell, s.joints)
}

/// Checks that a design view's parts agree with each other.
fn check_view(view: &Value, what: &str) {
    let geometry = &view["geometry"];
    let report = &view["report"];
    let tiles = geometry["tiles"].as_array().unwrap().len();
    assert!(tiles >= 1, "{what}");
    let spec = view["spec"].as_str().unwrap();
    let joints = spec.rsplit(':').next().unwrap();
    let edges = geometry["edges"].as_array().unwrap();
    assert_eq!(
        edges.len(),
        joints.chars().count(),
        "{what}: one edge per joint"
    );
    for (e, j) in edges.iter().zip(joints.chars()) {
        assert_eq!(e["joint"].as_str(), Some(j.to_string().as_str()), "{what}");
        for side in ["tile_a", "tile_b"] {
            assert!((e[side].as_u64().unwrap() as usize) < tiles, "{what}");
        }
    }
    assert_eq!(report["design"].as_str(), Some(spec), "{what}");
    let frames = report["frames"].as_array().unwrap();
    assert!(frames.len() >= 2, "{what}: {} frames", frames.len());
    let mut last_t = -1.0;
    for f in frames {
        assert_eq!(f["tiles"].as_array().unwrap().len(), tiles, "{what}");
        assert_eq!(
            f["measures"]["tile_rotations"].as_array().unwrap().len(),
            tiles,
            "{what}"
        );
        let t = f["t"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&t) && t >= last_t, "{what}: t = {t}");
        last_t = t;
        // Summaries are over the accepted states; a state inserted between two of them (more
        // frames asked for than states) may lie a little beyond them.
        let area = f["measures"]["area_ratio"].as_f64().unwrap();
        if f.get("inserted").is_none() {
            assert!(area <= report["max_area_ratio"].as_f64().unwrap() + 1e-12);
        }
    }
    // Every number of the frames and geometry is a number (NaN would be null).
    let mut leaves = Vec::new();
    numbers(&report["frames"], "frames".into(), &mut leaves);
    numbers(geometry, "geometry".into(), &mut leaves);
    for (path, v) in leaves {
        assert!(
            v.is_number()
                || v.is_string()
                || (path.ends_with(".inserted") && v.as_bool() == Some(true)),
            "{what}: {path} = {v}"
        );
    }
    for key in [
        "kerf",
        "max_expansion",
        "min_expansion",
        "max_area_ratio",
        "arc_length",
    ] {
        assert!(
            report[key].is_number(),
            "{what}: report.{key} = {}",
            report[key]
        );
    }
    let tile_linkages = view["tile_linkages"].as_array().unwrap();
    assert_eq!(tile_linkages.len(), tiles, "{what}");
    let linkages = view["linkages"]["linkages"].as_array();
    for (tile, set) in tile_linkages.iter().enumerate() {
        for l in set.as_array().unwrap() {
            let l = l.as_u64().unwrap() as usize;
            let linkage = &linkages.expect("a tile lists a linkage only when there are some")[l];
            let through = linkage["nodes"]
                .as_array()
                .unwrap()
                .iter()
                .any(|n| n[0].as_u64() == Some(tile as u64));
            assert!(
                through,
                "{what}: tile {tile} lists linkage {l}, which misses it"
            );
        }
    }
}

/// A cell twin's spec opens the design it is stored with, which lists it among its other
/// cells; every stored design lists exactly its twins.
#[tokio::test]
async fn a_twin_spec_opens_its_stored_design_with_its_other_cells() {
    let app = app();
    let store = Store::open_read(&catalogue().db, Check::Full).unwrap();
    let twins = store.cell_twins().unwrap();
    assert!(!twins.is_empty(), "the fixture holds cell twins");
    for (twin, kept) in &twins {
        let view = get(&app, &format!("/api/design?spec={}", enc(twin)))
            .await
            .ok();
        assert_eq!(view["spec"], kept.as_str());
        let others: Vec<&str> = view["other_cells"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap())
            .collect();
        assert!(others.contains(&twin.as_str()), "{twin}: {others:?}");
    }
    for s in summaries(&catalogue().db) {
        let view = get(&app, &format!("/api/design?spec={}", enc(&s.spec)))
            .await
            .ok();
        let want: Vec<&String> = twins
            .iter()
            .filter(|(_, k)| *k == s.spec)
            .map(|(t, _)| t)
            .collect();
        assert_eq!(view["other_cells"].as_array().unwrap().len(), want.len());
    }
}

#[tokio::test]
async fn stored_views_agree_with_their_catalogue_rows() {
    let app = app();
    for s in summaries(&catalogue().db) {
        let view = get(&app, &format!("/api/design?spec={}", enc(&s.spec)))
            .await
            .ok();
        check_view(&view, &s.spec);
        assert_eq!(view["spec"], s.spec.as_str());
        assert_eq!(view["origin"], "explored");
        assert_eq!(view["summary"], serde_json::to_value(&s).unwrap());
        assert!(view["notice"].is_null(), "{}: {}", s.spec, view["notice"]);
        let report = &view["report"];
        assert_eq!(report["steps"].as_u64(), Some(s.steps));
        assert_eq!(report["max_area_ratio"].as_f64(), Some(s.max_area_ratio));
        assert_eq!(report["kerf"].as_f64(), Some(s.kerf));
        assert_eq!(
            report["end_reason"]["kind"].as_str(),
            Some(s.end_reason.as_str())
        );
        let geometry = &view["geometry"];
        assert_eq!(
            geometry["tiles"].as_array().unwrap().len(),
            s.tile_count as usize
        );
        assert_eq!(geometry["family"], s.family.to_string());
        assert_eq!(geometry["params"], json!(s.params));
        assert_eq!(
            view["linkages"]["signature"].as_str(),
            s.linkage_signature.as_deref()
        );
    }
}

#[tokio::test]
async fn any_spelling_of_a_stored_spec_finds_it_and_others_are_not_found() {
    let app = app();
    let s = &summaries(&catalogue().db)[0];
    // Trailing zeros and upper-case joints spell the same design.
    let params: Vec<String> = s.params.iter().map(|p| format!("{p}0")).collect();
    let respelled = format!(
        "{}:{}:{}:{}",
        s.family,
        params.join(","),
        s.cell,
        s.joints.to_uppercase()
    );
    assert_ne!(respelled, s.spec);
    let view = get(&app, &format!("/api/design?spec={}", enc(&respelled)))
        .await
        .ok();
    assert_eq!(view["spec"], s.spec.as_str());
    for spec in [
        nudged(s, 0.01),
        "rotating-squares".into(),
        "no such thing".into(),
    ] {
        for endpoint in ["design", "thumbnail"] {
            let reply = get(&app, &format!("/api/{endpoint}?spec={}", enc(&spec))).await;
            let kind = assert_error(&reply, StatusCode::NOT_FOUND, &spec);
            assert_eq!(kind, "not_found");
        }
    }
}

#[tokio::test]
async fn thumbnails_are_svg_of_both_states() {
    use resvg::{tiny_skia, usvg};
    let app = app();
    for s in summaries(&catalogue().db) {
        let reply = get(&app, &format!("/api/thumbnail?spec={}", enc(&s.spec))).await;
        assert_eq!(reply.status, StatusCode::OK, "{}", s.spec);
        assert_eq!(reply.content_type, "image/svg+xml");
        let text = reply.text();
        assert!(text.contains(&format!("<title>{}</title>", s.spec)));
        // Two panels of a 3×3 patch of the cell's tiles.
        let polygons = text.matches("<polygon").count();
        assert_eq!(polygons, 2 * 9 * s.tile_count as usize, "{}", s.spec);
        let tree = usvg::Tree::from_str(&text, &usvg::Options::default())
            .unwrap_or_else(|e| panic!("{}: not SVG: {e}", s.spec));
        let size = tree.size().to_int_size();
        let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height()).unwrap();
        resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
        // Both halves show tiles: pixels that are not the white background (an open sheet
        // fills a few percent of its panel).
        let (w, h) = (size.width() as usize, size.height() as usize);
        let px = pixmap.data();
        for half in [0..w / 2, w / 2..w] {
            let mut inked = 0;
            for y in 0..h {
                for x in half.clone() {
                    let p = &px[4 * (y * w + x)..4 * (y * w + x) + 3];
                    inked += usize::from(p.iter().any(|&c| c < 200));
                }
            }
            assert!(
                inked * 50 > h * w / 2,
                "{}: only {inked} inked pixels in {half:?}",
                s.spec
            );
        }
    }
}

/// Frames of a GIF: (width, height, RGBA of each frame).
fn decode_gif(bytes: &[u8]) -> (u16, u16, Vec<Vec<u8>>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(bytes).unwrap();
    let (w, h) = (decoder.width(), decoder.height());
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        frames.push(frame.buffer.to_vec());
    }
    (w, h, frames)
}

#[tokio::test]
async fn gifs_animate_the_deployment() {
    let app = app();
    let all = summaries(&catalogue().db);
    let stored = &all[0];
    let cases = [
        format!("/api/gif?spec={}", enc(&stored.spec)),
        format!("/api/gif?spec={}&kerf=0.02", enc(&nudged(stored, 0.01))),
        "/api/gif?spec=rotating-squares".to_string(),
    ];
    for uri in cases {
        let reply = get(&app, &uri).await;
        assert_eq!(reply.status, StatusCode::OK, "{uri}: {}", reply.text());
        assert_eq!(reply.content_type, "image/gif");
        assert_eq!(&reply.body[..6], b"GIF89a", "{uri}");
        let (w, h, frames) = decode_gif(&reply.body);
        assert_eq!(w, 360, "{uri}");
        assert!(h > 0);
        assert!(
            (2..=40).contains(&frames.len()),
            "{uri}: {} frames",
            frames.len()
        );
        assert_ne!(frames.first(), frames.last(), "{uri}: the sheet moves");
    }
}

#[tokio::test]
async fn live_deployments_are_views_without_origin() {
    let app = app();
    let all = summaries(&catalogue().db);
    for (s, frames) in all.iter().zip([2usize, 30, 400]) {
        let reply = post_design(
            &app,
            "/api/deploy",
            &s.spec,
            json!({ "frames": frames, "kerf": s.kerf }),
        )
        .await;
        let view = reply.ok();
        check_view(&view, &s.spec);
        assert!(view["origin"].is_null());
        assert!(view["summary"].is_null());
        let n = view["report"]["frames"].as_array().unwrap().len();
        assert!((2..=frames).contains(&n), "{} frames of {frames}", n);
        // The same design at the same kerf follows the stored trajectory.
        let report = &view["report"];
        assert_eq!(report["steps"].as_u64(), Some(s.steps), "{}", s.spec);
        assert_eq!(
            report["end_reason"]["kind"].as_str(),
            Some(s.end_reason.as_str())
        );
    }
    // Defaults: 60 frames at most, the library's kerf; the JSON form of a design works.
    let s = &all[1];
    let joints: Vec<Value> = s
        .joints
        .chars()
        .enumerate()
        .filter(|(_, c)| *c != '-')
        .map(|(k, c)| json!({ "edge": k, "at": c.to_string() }))
        .collect();
    let design = json!({
        "family": s.family.to_string(),
        "params": s.params,
        "cell": [s.cell.a(), s.cell.b()],
        "joints": joints,
    });
    let view = post_design(&app, "/api/deploy", &design.to_string(), json!({}))
        .await
        .ok();
    check_view(&view, "design JSON");
    assert_eq!(view["spec"], s.spec.as_str());
    assert!(view["report"]["frames"].as_array().unwrap().len() <= 60);
    let kerf = view["report"]["kerf"].as_f64().unwrap();
    let with_kerf = post_design(&app, "/api/deploy", &s.spec, json!({ "kerf": 2.0 * kerf }))
        .await
        .ok();
    assert_eq!(with_kerf["report"]["kerf"].as_f64(), Some(2.0 * kerf));
}

/// Every explored row as stored: summary, report JSON and linkage JSON.
fn explored_rows(db: &Path) -> Vec<(DesignSummary, String, Option<String>)> {
    let store = Store::open_read(db, Check::Full).unwrap();
    store
        .summaries()
        .unwrap()
        .into_iter()
        .filter(|s| s.origin == isogami_store::Origin::Explored)
        .map(|s| {
            let r = store.design_record(&s.spec).unwrap().unwrap();
            let (report, links) = (
                r.report_json().to_string(),
                r.linkages_json().map(String::from),
            );
            (s, report, links)
        })
        .collect()
}

#[tokio::test]
async fn saved_designs_appear_as_user_designs_once() {
    let (_dir, db) = private_db("save");
    let app = app_with(&db, ServerSettings::default());
    let before = explored_rows(&db);
    let all = summaries(&db);
    let s = all.iter().find(|s| s.family.number() == 59).unwrap();
    let spec = nudged(s, 0.01);

    let reply = post_design(&app, "/api/designs", &spec, json!({})).await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.text());
    let saved = reply.json();
    assert_eq!(saved["saved"], true);
    let canonical = saved["spec"].as_str().unwrap().to_string();
    assert_eq!(
        isogami::api::resolve_design(&spec).unwrap().to_string(),
        canonical
    );

    let users = get(&app, "/api/designs?origin=user").await.ok();
    assert_eq!(users["total"], 1);
    assert_eq!(users["rows"][0]["spec"], canonical.as_str());
    assert_eq!(users["rows"][0]["origin"], "user");
    let stats = get(&app, "/api/stats").await.ok();
    assert_eq!(stats["user_designs"], 1);
    assert_eq!(stats["designs"].as_u64(), Some(all.len() as u64 + 1));
    let view = get(&app, &format!("/api/design?spec={}", enc(&canonical)))
        .await
        .ok();
    assert_eq!(view["origin"], "user");
    check_view(&view, "saved design");
    let explored = get(&app, "/api/designs?origin=explored").await.ok();
    assert_eq!(explored["total"].as_u64(), Some(all.len() as u64));

    // Saving it again, in any spelling, is refused.
    let respelled = canonical.replace(&s.joints, &s.joints.to_uppercase());
    for again in [canonical.as_str(), spec.as_str(), respelled.as_str()] {
        let reply = post_design(&app, "/api/designs", again, json!({})).await;
        assert_eq!(assert_error(&reply, StatusCode::CONFLICT, again), "exists");
    }
    // A stored explored design cannot be saved as a user design either.
    let reply = post_design(&app, "/api/designs", &s.spec, json!({})).await;
    assert_eq!(
        assert_error(&reply, StatusCode::CONFLICT, &s.spec),
        "exists"
    );
    assert_eq!(explored_rows(&db), before, "explored rows changed");
    assert_eq!(summaries(&db).len(), all.len() + 1);
}

#[tokio::test]
async fn read_only_servers_and_refused_saves_leave_the_database_as_it_was() {
    let (_dir, db) = private_db("refused-saves");
    let bytes = std::fs::read(&db).unwrap();
    let s = summaries(&db)[0].clone();
    let read_only = app_with(
        &db,
        ServerSettings {
            allow_save: false,
            ..ServerSettings::default()
        },
    );
    let reply = post_design(&read_only, "/api/designs", &nudged(&s, 0.01), json!({})).await;
    assert_eq!(
        assert_error(&reply, StatusCode::FORBIDDEN, "read-only"),
        "read_only"
    );

    let app = app_with(&db, ServerSettings::default());
    let rigid = with_joints(&s, &"x".repeat(s.joints.len()));
    let bad: [(&str, Value); 6] = [
        (rigid.as_str(), json!({})),
        (s.spec.as_str(), json!({ "kerf": 0.5 })),
        (s.spec.as_str(), json!({ "kerf": -0.01 })),
        ("IH999:0.5:1x1:aaa", json!({})),
        (s.spec.as_str(), json!({ "frames": 100000 })),
        (s.spec.as_str(), json!({ "colour": "red" })),
    ];
    for (design, extra) in bad {
        let reply = post_design(&app, "/api/designs", design, extra.clone()).await;
        common::assert_client_error(&reply, &format!("save {design} {extra}"));
    }
    drop((app, read_only));
    assert_eq!(std::fs::read(&db).unwrap(), bytes, "database changed");
    assert_eq!(summaries(&db).len(), summaries(&catalogue().db).len());
}

#[tokio::test]
async fn a_stored_design_has_its_motion_class_and_a_live_one_none() {
    let app = app();
    let rows = summaries(&catalogue().db);
    for s in &rows {
        let reply = get(&app, &format!("/api/motion?spec={}", enc(&s.spec)))
            .await
            .ok();
        assert_eq!(reply["topology"], s.topology.as_str());
        let class = &reply["class"];
        let variants = class["variants"].as_array().unwrap();
        let mine: Vec<&Value> = variants
            .iter()
            .filter(|v| v["topology"] == s.topology.as_str())
            .collect();
        assert_eq!(mine.len(), 1, "{}: {class}", s.spec);
        // Its example is a stored design of that topology.
        let example = mine[0]["example"].as_str().unwrap();
        let of_example = rows.iter().find(|r| r.spec == example).unwrap();
        assert_eq!(of_example.topology, s.topology);
        assert_eq!(
            mine[0]["designs"].as_u64().unwrap() as usize,
            rows.iter().filter(|r| r.topology == s.topology).count()
        );
    }
    assert!(!rows.is_empty());
    let live = nudged(rows.iter().find(|r| !r.params.is_empty()).unwrap(), 0.01);
    let reply = get(&app, &format!("/api/motion?spec={}", enc(&live)))
        .await
        .ok();
    assert_eq!(reply["class"], Value::Null);
    assert_eq!(reply["topology"], Value::Null);
    assert_error(
        &get(&app, "/api/motion").await,
        StatusCode::BAD_REQUEST,
        "no spec",
    );
}

#[tokio::test]
async fn with_fallback_live_any_design_has_a_view_and_a_stored_one_is_the_stored_view() {
    let app = app();
    let s = &summaries(&catalogue().db)[0];
    // A stored design: its stored view, whatever the fallback.
    let stored = get(&app, &format!("/api/design?spec={}", enc(&s.spec)))
        .await
        .ok();
    let fallback = get(
        &app,
        &format!("/api/design?spec={}&fallback=live", enc(&s.spec)),
    )
    .await
    .ok();
    assert_eq!(fallback, stored);
    assert!(!fallback["origin"].is_null());
    // Asked at its own kerf: still stored; at another: deployed live there.
    let kerf = stored["report"]["kerf"].as_f64().unwrap();
    let same = get(
        &app,
        &format!(
            "/api/design?spec={}&fallback=live&kerf={kerf}",
            enc(&s.spec)
        ),
    )
    .await
    .ok();
    assert_eq!(same, stored);
    let other = get(
        &app,
        &format!(
            "/api/design?spec={}&fallback=live&kerf={}",
            enc(&s.spec),
            2.0 * kerf
        ),
    )
    .await
    .ok();
    assert!(other["origin"].is_null());
    assert_eq!(other["report"]["kerf"].as_f64(), Some(2.0 * kerf));
    // A design that is not stored: 404 without the fallback, with it the view POST
    // /api/deploy answers.
    let spec = nudged(s, 0.01);
    let reply = get(&app, &format!("/api/design?spec={}", enc(&spec))).await;
    assert_eq!(
        assert_error(&reply, StatusCode::NOT_FOUND, &spec),
        "not_found"
    );
    let live = get(
        &app,
        &format!("/api/design?spec={}&fallback=live", enc(&spec)),
    )
    .await
    .ok();
    check_view(&live, &spec);
    assert!(live["origin"].is_null() && live["summary"].is_null());
    let deployed = post_design(&app, "/api/deploy", &spec, json!({}))
        .await
        .ok();
    assert_eq!(live, deployed);
    // What cannot be deployed is refused as POST /api/deploy refuses it; bad parameters
    // are 400s.
    let reply = get(&app, "/api/design?spec=no%20such%20thing&fallback=live").await;
    let deployed = post_design(&app, "/api/deploy", "no such thing", json!({})).await;
    assert_eq!(
        (reply.status, reply.json()),
        (deployed.status, deployed.json())
    );
    assert_eq!(
        assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, "no such thing"),
        "bad_design"
    );
    for query in [
        format!("spec={}&fallback=maybe", enc(&spec)),
        format!("spec={}&kerf=0.01", enc(&spec)),
        format!("spec={}&fallback=live&kerf=nan", enc(&spec)),
    ] {
        let reply = get(&app, &format!("/api/design?{query}")).await;
        assert_eq!(
            assert_error(&reply, StatusCode::BAD_REQUEST, &query),
            "bad_parameter"
        );
    }
}

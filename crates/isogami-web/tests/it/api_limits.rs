//! Designs that cannot deploy are explained (rigid, ill-shaped, several degrees of freedom);
//! deployments are bounded in time, leave the server answering, and stop when their client
//! goes away; concurrent requests agree with sequential ones.

use crate::common;

use axum::http::StatusCode;
use axum::Router;
use common::{
    app, app_with, assert_error, catalogue, enc, get, post_design, private_db, summaries, Reply,
};
use isogami::api::{deploy, resolve_design, DeployRequest, FrameSelection};
use isogami::contact::ContactSettings;
use isogami::deploy::DeploySettings;
use isogami_web::ServerSettings;
use serde_json::json;
use std::time::{Duration, Instant};

/// A design with two degrees of freedom that takes many small steps at a narrow kerf: about
/// 1500 steps at kerf 1e-4.
const LONG: &str = "IH84:0.5,0.196416770201:1x1:aa-";
const LONG_KERF: f64 = 1e-4;

#[tokio::test]
async fn rigid_designs_are_422_rigid() {
    let app = app();
    for s in summaries(&catalogue().db).iter().take(4) {
        let welded = s.spec.replace(&s.joints, &"x".repeat(s.joints.len()));
        let reply = post_design(&app, "/api/deploy", &welded, json!({})).await;
        assert_eq!(
            assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, &welded),
            "rigid"
        );
        let reply = get(&app, &format!("/api/gif?spec={}", enc(&welded))).await;
        assert_eq!(
            assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, &welded),
            "rigid"
        );
    }
}

#[tokio::test]
async fn ill_shaped_designs_are_422_ill_shaped() {
    let app = app();
    // A kerf too wide for this tile's short edge: refused at 0.2, fine at the default.
    let slender = "IH22:0.23,0.05,0.15:1x1:aa-a-";
    let reply = post_design(&app, "/api/deploy", slender, json!({ "kerf": 0.2 })).await;
    assert_eq!(
        assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, slender),
        "ill_shaped"
    );
    let reply = post_design(&app, "/api/deploy", slender, json!({})).await;
    assert_eq!(reply.status, StatusCode::OK, "{}", reply.text());
    // Shape parameters that give no valid tile, as a shape slider pushed too far would.
    let mut refused = 0;
    for s in summaries(&catalogue().db).iter().take(6) {
        for factor in [25.0, -25.0] {
            let params: Vec<String> = s.params.iter().map(|p| (p * factor).to_string()).collect();
            let spec = format!("{}:{}:{}:{}", s.family, params.join(","), s.cell, s.joints);
            let reply = post_design(&app, "/api/deploy", &spec, json!({})).await;
            if reply.status != StatusCode::OK {
                refused += 1;
                assert_eq!(
                    assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, &spec),
                    "ill_shaped",
                    "{spec}"
                );
            }
        }
    }
    assert!(refused >= 4, "only {refused} scaled shapes refused");
    let spec = "IH59:5:1x1:aaaa";
    let reply = post_design(&app, "/api/deploy", spec, json!({})).await;
    assert_eq!(
        assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, spec),
        "ill_shaped"
    );
}

#[tokio::test]
async fn designs_with_several_degrees_of_freedom_carry_a_notice() {
    // Three degrees of freedom, about 100 steps.
    let spec = "IH86:0.121416770201:1x1:aaab-b";
    let view = post_design(&app(), "/api/deploy", spec, json!({ "frames": 10 }))
        .await
        .ok();
    assert!(view["report"]["dof"].as_u64().unwrap() > 1);
    assert_eq!(view["notice"]["kind"], "multi_dof");
    assert!(!view["notice"]["hint"].as_str().unwrap().is_empty());
}

#[tokio::test]
async fn deployments_past_the_time_limit_are_422_timeout() {
    let (_dir, db) = private_db("timeout");
    let bytes = std::fs::read(&db).unwrap();
    let app = app_with(
        &db,
        ServerSettings {
            sim_timeout: Duration::from_millis(5),
            ..ServerSettings::default()
        },
    );
    let body = json!({ "kerf": LONG_KERF, "frames": 400 });
    for endpoint in ["/api/deploy", "/api/designs"] {
        let reply = post_design(&app, endpoint, LONG, body.clone()).await;
        assert_eq!(
            assert_error(&reply, StatusCode::UNPROCESSABLE_ENTITY, endpoint),
            "timeout"
        );
    }
    let uri = format!("/api/gif?spec={}&kerf={LONG_KERF}", enc(LONG));
    assert_eq!(
        assert_error(
            &get(&app, &uri).await,
            StatusCode::UNPROCESSABLE_ENTITY,
            &uri
        ),
        "timeout"
    );
    drop(app);
    assert_eq!(std::fs::read(&db).unwrap(), bytes, "a timed-out save wrote");
}

/// While a long deployment runs the server answers other requests; when its client goes
/// away the simulation stops soon after (dropping the runtime waits for it).
#[test]
fn a_running_deployment_blocks_nothing_and_stops_when_its_client_leaves() {
    let design = resolve_design(LONG).unwrap();
    let request = DeployRequest {
        settings: DeploySettings {
            contact: ContactSettings::with_kerf(LONG_KERF),
            ..DeploySettings::default()
        },
        frames: FrameSelection::Evenly(400),
    };
    let start = Instant::now();
    deploy(&design, &request, &mut |_| true).unwrap();
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
            tokio::spawn(async move {
                let body = json!({ "kerf": LONG_KERF, "frames": 400 });
                post_design(&app, "/api/deploy", LONG, body).await
            })
        };
        for uri in ["/api/stats", "/api/designs", "/api/facets", "/api/families"] {
            let reply = get(&app, uri).await;
            assert_eq!(reply.status, StatusCode::OK, "{uri}");
            assert!(!long.is_finished(), "{uri} waited for the deployment");
        }
        tokio::time::sleep(full / 10).await;
        assert!(!long.is_finished());
        long.abort();
    });
    drop(runtime);
    let stopped = start.elapsed();
    assert!(
        stopped < full * 2 / 5,
        "the simulation ran on for {stopped:?} after its client left (a full run takes {full:?})"
    );
}

/// 32 requests of every kind.
fn mixed_requests() -> Vec<(&'static str, String, Option<String>)> {
    let all = summaries(&catalogue().db);
    let mut out: Vec<(&str, String, Option<String>)> = Vec::new();
    let mut get = |uri: String| out.push(("GET", uri, None));
    for q in [
        "",
        "sort=-max_area_ratio&limit=5",
        "family=IH84&family=IH59",
        "tiles=4&sort=steps",
        "range=max_expansion:0.5:&sort=-v1",
        "behaviour=isotropic_auxetic&offset=1&limit=2",
        "cell=2x1",
        "sort=linkage_signature&limit=3&offset=3",
    ] {
        get(format!("/api/designs?{q}"));
    }
    for q in [
        "",
        "family=IH22",
        "tiles=2&behaviour=none",
        "range=steps::90",
    ] {
        get(format!("/api/facets?{q}"));
    }
    for q in [
        "x=v0&y=v1",
        "x=max_expansion&y=min_expansion",
        "x=steps&y=kerf&family=IH86",
        "x=poisson_min&y=poisson_max",
    ] {
        get(format!("/api/scatter?{q}"));
    }
    for s in all.iter().step_by(4).take(4) {
        get(format!("/api/design?spec={}", enc(&s.spec)));
        get(format!("/api/thumbnail?spec={}", enc(&s.spec)));
    }
    for uri in ["/api/stats", "/api/families", "/api/dictionary"] {
        get(uri.into());
    }
    get(format!("/api/gif?spec={}", enc(&all[1].spec)));
    for s in [&all[0], &all[5], &all[0], &all[5]] {
        let body = json!({ "design": s.spec, "frames": 20 }).to_string();
        out.push(("POST", "/api/deploy".into(), Some(body)));
    }
    out
}

async fn answer(app: &Router, (method, uri, body): &(&str, String, Option<String>)) -> Reply {
    match *method {
        "GET" => get(app, uri).await,
        _ => common::post(app, uri, body.clone().unwrap()).await,
    }
}

#[test]
fn concurrent_requests_agree_with_sequential_answers() {
    let requests = mixed_requests();
    assert_eq!(requests.len(), 32);
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(4)
        .enable_all()
        .build()
        .unwrap();
    let app = app();
    runtime.block_on(async {
        let mut sequential = Vec::new();
        for r in &requests {
            let reply = answer(&app, r).await;
            assert_eq!(
                reply.status,
                StatusCode::OK,
                "{} {}: {}",
                r.0,
                r.1,
                reply.text()
            );
            sequential.push(reply);
        }
        let tasks: Vec<_> = requests
            .iter()
            .cloned()
            .map(|r| {
                let app = app.clone();
                tokio::spawn(async move { answer(&app, &r).await })
            })
            .collect();
        for ((r, task), before) in requests.iter().zip(tasks).zip(&sequential) {
            let reply = task.await.unwrap();
            assert_eq!(reply.status, StatusCode::OK, "{} {}", r.0, r.1);
            assert_eq!(reply.content_type, before.content_type, "{}", r.1);
            assert!(reply.body == before.body, "{} {}: answers differ", r.0, r.1);
        }
    });
}

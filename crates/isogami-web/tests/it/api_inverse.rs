//! The inverse-design jobs: a bad target or value is a 400 with the library's one-line message
//! and starts nothing; a small run ends `done` with the result the library (and so
//! `isogami inverse --json`) gives for the same request on the same database, run twice to
//! the same designs and objectives, its best design deploys, and its progress showed the
//! leaders as they improved; a stop ends a run as `stopped`; a second job is refused while
//! one runs; the caps on time and polling stop a run; ended jobs are forgotten; saving is
//! refused on a read-only server and before the end, and otherwise stores the refined
//! designs as the CLI's `--save` does.

use crate::common;

use axum::body::Body;
use axum::http::{Method, Request, StatusCode};
use axum::Router;
use common::{app_with, assert_error, catalogue, enc, get, post, private_db, send, summaries};
use isogami::inverse::{inverse_design, InverseRequest, Target};
use isogami_store::{Check, DesignQuery, Store};
use isogami_web::inverse::InverseLimits;
use isogami_web::ServerSettings;
use serde_json::{json, Value};
use std::path::Path;
use std::time::{Duration, Instant};

/// A run of a second or two on the fixture database.
const BIG: &str = r#"{"target": "area", "top": 5, "budget": 200}"#;

fn app_of(db: &Path, allow_save: bool, inverse: InverseLimits) -> Router {
    app_with(
        db,
        ServerSettings {
            allow_save,
            inverse,
            ..ServerSettings::default()
        },
    )
}

fn app() -> Router {
    app_of(&catalogue().db, true, InverseLimits::default())
}

/// Starts a job; its id.
async fn start(app: &Router, body: &str) -> u64 {
    let reply = post(app, "/api/inverse", body.to_string()).await;
    assert_eq!(reply.status, StatusCode::ACCEPTED, "{}", reply.text());
    let v = reply.json();
    assert_eq!(v["state"], "running");
    v["id"].as_u64().unwrap()
}

async fn status(app: &Router, id: u64) -> Value {
    get(app, &format!("/api/inverse/{id}")).await.ok()
}

async fn delete(app: &Router, uri: &str) -> Value {
    let request = Request::builder()
        .method(Method::DELETE)
        .uri(uri)
        .body(Body::empty())
        .unwrap();
    send(app, request).await.ok()
}

/// Polls job `id` until it is no longer running; every view seen, the last one ended.
async fn until_ended(app: &Router, id: u64) -> Vec<Value> {
    let t0 = Instant::now();
    let mut seen = Vec::new();
    loop {
        let v = status(app, id).await;
        let running = v["state"] == "running";
        seen.push(v);
        if !running {
            return seen;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(300),
            "job {id} still runs"
        );
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
}

/// What the library gives for `request` on `db`, as `isogami inverse --json` prints it
/// (without the wall time).
fn library_json(db: &Path, request: &InverseRequest) -> Value {
    let store = Store::open_read(db, Check::Quick).unwrap();
    let query = DesignQuery::for_constraints(&request.target.constraints);
    let candidates = store.candidates(&query).unwrap();
    let result = inverse_design(&candidates, request, &mut |_| true).unwrap();
    let mut v = serde_json::to_value(&result).unwrap();
    v.as_object_mut().unwrap().remove("seconds");
    v
}

fn small_request() -> InverseRequest {
    let mut r = InverseRequest::new(Target::parse("area").unwrap());
    r.top = 2;
    r.budget = 6;
    r
}

#[tokio::test]
async fn bad_targets_and_values_are_400s_with_the_librarys_message_and_start_nothing() {
    let app = app();
    let cases: [(&str, &str, &str); 9] = [
        (r#"{"target": "aera"}"#, "bad_target", "aera"),
        (r#"{"target": "lock(0.3,0.1)"}"#, "bad_target", "lock"),
        (r#"{"target": 7}"#, "bad_target", "target must be text"),
        (r#"{"target": "area", "top": 0}"#, "bad_parameter", "top 0"),
        (
            r#"{"target": "area", "kerf": 5}"#,
            "bad_parameter",
            "kerf 5",
        ),
        (
            r#"{"target": "area", "confirm": 0}"#,
            "bad_parameter",
            "confirm",
        ),
        (
            r#"{"target": "area", "budget": 1000}"#,
            "over_limit",
            "budget 1000",
        ),
        (
            r#"{"target": "area", "colour": 1}"#,
            "bad_parameter",
            "colour",
        ),
        ("not json", "bad_parameter", "request body"),
    ];
    for (body, kind, names) in cases {
        let reply = post(&app, "/api/inverse", body).await;
        assert_eq!(assert_error(&reply, StatusCode::BAD_REQUEST, body), kind);
        let message = reply.json()["error"].as_str().unwrap().to_string();
        assert!(message.contains(names), "{body}: {message}");
    }
    // The library's own message, word for word.
    let reply = post(&app, "/api/inverse", r#"{"target": "aera; tiles<=4"}"#).await;
    let expected = Target::resolve("aera; tiles<=4").unwrap_err().to_string();
    assert_eq!(reply.json()["error"], expected.as_str());
    let settings = get(&app, "/api/inverse").await.ok();
    assert_eq!(settings["running"], Value::Null, "no job started");
    assert_eq!(settings["limits"]["budget"], 200);
    assert_eq!(settings["save"], true);
    assert_eq!(settings["database"], "catalogue.db");
    let reply = get(&app, "/api/inverse/1").await;
    assert_eq!(
        assert_error(&reply, StatusCode::NOT_FOUND, "job 1"),
        "not_found"
    );
}

#[tokio::test]
async fn a_small_run_ends_done_with_the_librarys_result_and_its_best_design_deploys() {
    let app = app();
    let id = start(&app, r#"{"target": " area ", "top": 2, "budget": 6}"#).await;
    let views = until_ended(&app, id).await;
    let end = views.last().unwrap();
    assert_eq!(end["state"], "done", "{end}");
    assert_eq!(end["error"], Value::Null);
    assert_eq!(end["request"]["target"], "1*area");
    // The body that started it, as given (the target trimmed, the rest null: defaults), in
    // every view: what a page restores its form and command from.
    let body = json!({
        "target": "area", "top": 2, "budget": 6, "confirm": null, "triage": null,
        "samples": null, "kerf": null, "refine_kerf": null
    });
    for v in &views {
        assert_eq!(v["request"]["body"], body, "{}", v["state"]);
    }
    let mut result = end["result"].clone();
    let results = result["results"].as_array().unwrap().clone();
    assert!(!results.is_empty() && results.len() <= 2);

    // The same request through the library, as the CLI runs it: the same JSON but the wall
    // time (a second run: inverse design is deterministic).
    assert!(result["seconds"].as_f64().unwrap() > 0.0);
    result.as_object_mut().unwrap().remove("seconds");
    assert_eq!(result, library_json(&catalogue().db, &small_request()));

    // The best refined design deploys.
    let best = &results[0]["after"];
    let body = json!({ "design": best["spec"], "kerf": best["kerf"] });
    let deployed = post(&app, "/api/deploy", body.to_string()).await.ok();
    assert_eq!(deployed["spec"], best["spec"]);
    assert_eq!(deployed["report"]["dof"], 1);

    // Progress: every evaluation counted, the leaders ending as the results, the history of
    // the best objective going down to the best result.
    assert_eq!(end["evaluations"], result["evaluations"]);
    let leaders = end["progress"]["leaders"].as_array().unwrap();
    for (l, r) in leaders.iter().zip(&results) {
        assert_eq!(l["spec"], r["after"]["spec"]);
        assert_eq!(l["objective"], r["after"]["objective"]);
        assert_eq!(l["topology"], r["topology"]);
    }
    let history = end["history"].as_array().unwrap();
    assert!(!history.is_empty());
    let points: Vec<(f64, f64)> = history
        .iter()
        .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
        .collect();
    assert!(points
        .windows(2)
        .all(|w| w[1].0 > w[0].0 && w[1].1 < w[0].1));
    assert_eq!(
        points.last().unwrap().1,
        best["objective"].as_f64().unwrap()
    );
    // An ended job stays as it was.
    assert_eq!(status(&app, id).await["result"], end["result"]);
}

#[tokio::test]
async fn leaders_show_while_a_run_goes_and_a_stop_ends_it() {
    let app = app();
    let id = start(&app, BIG).await;
    // Leaders appear while it runs.
    let t0 = Instant::now();
    loop {
        let v = status(&app, id).await;
        assert_eq!(
            v["state"], "running",
            "the run ended before its leaders were seen"
        );
        let leaders = v["progress"]["leaders"].as_array().map_or(0, Vec::len);
        if leaders > 0 {
            let l = &v["progress"]["leaders"][0];
            assert!(l["spec"].as_str().unwrap().contains(':'));
            assert_eq!(l["objective"], v["progress"]["best"]);
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(60));
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
    let stopping = delete(&app, &format!("/api/inverse/{id}")).await;
    assert!(stopping["state"] == "stopped" || stopping["stopping"] == true);
    let end = until_ended(&app, id).await.pop().unwrap();
    assert_eq!(end["state"], "stopped");
    assert_eq!(end["result"], Value::Null);
    assert_eq!(end["error"]["kind"], "stopped");
    assert_eq!(end["error"]["error"], "inverse design stopped by request");
    // Stopping an ended job changes nothing.
    let again = delete(&app, &format!("/api/inverse/{id}")).await;
    assert_eq!(again["state"], "stopped");
}

#[tokio::test]
async fn a_second_job_is_refused_while_one_runs() {
    let app = app();
    let id = start(&app, BIG).await;
    let reply = post(&app, "/api/inverse", r#"{"target": "isotropic"}"#).await;
    assert_eq!(
        assert_error(&reply, StatusCode::CONFLICT, "second job"),
        "busy"
    );
    let message = reply.json()["error"].as_str().unwrap().to_string();
    assert!(message.contains(&format!("job {id}")), "{message}");
    assert_eq!(get(&app, "/api/inverse").await.ok()["running"], id);
    delete(&app, &format!("/api/inverse/{id}")).await;
    until_ended(&app, id).await;
    let next = start(&app, r#"{"target": "area", "top": 1, "budget": 0}"#).await;
    assert!(next > id);
    assert_eq!(
        until_ended(&app, next).await.pop().unwrap()["state"],
        "done"
    );
}

#[tokio::test]
async fn the_time_limit_and_an_abandoned_run_stop_it_and_ended_jobs_are_forgotten() {
    let short = InverseLimits {
        max_run: Duration::from_millis(300),
        ..InverseLimits::default()
    };
    let app = app_of(&catalogue().db, true, short);
    let id = start(&app, BIG).await;
    let end = until_ended(&app, id).await.pop().unwrap();
    assert_eq!(end["state"], "stopped");
    assert!(
        end["error"]["error"]
            .as_str()
            .unwrap()
            .contains("time limit of 0.3 s"),
        "{end}"
    );

    let unwatched = InverseLimits {
        abandon: Duration::from_millis(200),
        keep: Duration::from_secs(2),
        ..InverseLimits::default()
    };
    let app = app_of(&catalogue().db, true, unwatched);
    let id = start(&app, BIG).await;
    tokio::time::sleep(Duration::from_secs(1)).await;
    let end = status(&app, id).await;
    assert_eq!(end["state"], "stopped", "{end}");
    assert!(end["error"]["error"]
        .as_str()
        .unwrap()
        .contains("nobody asked for its progress"));
    tokio::time::sleep(Duration::from_millis(2200)).await;
    let reply = get(&app, &format!("/api/inverse/{id}")).await;
    assert_eq!(
        assert_error(&reply, StatusCode::NOT_FOUND, "forgotten"),
        "not_found"
    );
}

#[tokio::test]
async fn saving_is_refused_read_only_and_before_the_end_and_stores_the_refined_designs() {
    let (_dir, db) = private_db("inverse-save");
    let bytes = std::fs::read(&db).unwrap();
    let small = r#"{"target": "area", "top": 2, "budget": 6}"#;

    let read_only = app_of(&db, false, InverseLimits::default());
    let id = start(&read_only, small).await;
    assert_eq!(
        until_ended(&read_only, id).await.pop().unwrap()["state"],
        "done"
    );
    let reply = post(&read_only, &format!("/api/inverse/{id}/save"), "").await;
    assert_eq!(
        assert_error(&reply, StatusCode::FORBIDDEN, "read-only"),
        "read_only"
    );
    assert_eq!(get(&read_only, "/api/inverse").await.ok()["save"], false);
    drop(read_only);
    assert_eq!(std::fs::read(&db).unwrap(), bytes, "database changed");

    let app = app_of(&db, true, InverseLimits::default());
    let running = start(&app, BIG).await;
    let reply = post(&app, &format!("/api/inverse/{running}/save"), "").await;
    assert_eq!(
        assert_error(&reply, StatusCode::CONFLICT, "running"),
        "not_done"
    );
    delete(&app, &format!("/api/inverse/{running}")).await;
    until_ended(&app, running).await;
    let reply = post(&app, &format!("/api/inverse/{running}/save"), "").await;
    assert_eq!(
        assert_error(&reply, StatusCode::CONFLICT, "stopped"),
        "not_done"
    );

    let id = start(&app, small).await;
    let end = until_ended(&app, id).await.pop().unwrap();
    let results = end["result"]["results"].as_array().unwrap().clone();
    let reply = post(&app, &format!("/api/inverse/{id}/save"), "").await;
    assert_eq!(reply.status, StatusCode::CREATED, "{}", reply.text());
    let saved = reply.json()["saved"].clone();
    let specs: Vec<&Value> = results.iter().map(|r| &r["after"]["spec"]).collect();
    let saved_specs: Vec<&Value> = saved
        .as_array()
        .unwrap()
        .iter()
        .map(|s| &s["spec"])
        .collect();
    assert_eq!(saved_specs, specs);
    assert!(saved.as_array().unwrap().iter().all(|s| s["saved"] == true));
    assert_eq!(
        summaries(&db).len(),
        summaries(&catalogue().db).len() + results.len()
    );
    for spec in &specs {
        let view = get(
            &app,
            &format!("/api/design?spec={}", enc(spec.as_str().unwrap())),
        )
        .await
        .ok();
        assert_eq!(view["origin"], "user", "{spec}");
    }
    // The job's result now says what was saved, as `isogami inverse --save --json` does.
    assert_eq!(status(&app, id).await["result"]["saved"], saved);
    // Saving again stores nothing new.
    let again = post(&app, &format!("/api/inverse/{id}/save"), "").await;
    assert_eq!(again.status, StatusCode::CREATED);
    assert!(again.json()["saved"]
        .as_array()
        .unwrap()
        .iter()
        .all(|s| s["saved"] == false && s["note"] == "already in the database"));
    assert_eq!(
        summaries(&db).len(),
        summaries(&catalogue().db).len() + results.len()
    );
}

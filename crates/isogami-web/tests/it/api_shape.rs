//! The shape endpoints (issue 13 item 6): a special design's slider move is followed along
//! its shape constraints and the result still moves (checked by the library's own mobility
//! analysis and by a live deployment through the API); a pinned parameter is refused naming
//! it; a generic design's parameter just moves; bad requests are one-line 4xx errors.

use crate::common;

use axum::http::StatusCode;
use common::{app, assert_error, enc, get, post, post_design};
use isogami::api::{analyze, resolve_design};
use serde_json::{json, Value};

/// Special: one DOF only where p2 = p3.
const SPECIAL: &str = "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:aa-aa-";
/// Special with its only parameter pinned.
const PINNED: &str = "IH16:0.216506350946:1x1:-a-a-aaaa";
/// Generic: one DOF at every nearby shape.
const GENERIC: &str = "IH28:0.588675134594,0.35:1x1:a--a-b-bbb";

fn dof(spec: &str) -> usize {
    let design = resolve_design(spec).unwrap();
    analyze(&design, Default::default()).unwrap().mobility.dof
}

/// `SPECIAL` with parameter 2 set to `value` and nothing else changed.
fn naive(value: f64) -> String {
    let mut parts: Vec<String> = SPECIAL.split(':').map(String::from).collect();
    let mut params: Vec<String> = parts[1].split(',').map(String::from).collect();
    params[2] = value.to_string();
    parts[1] = params.join(",");
    parts.join(":")
}

async fn follow(design: &str, index: usize, value: f64) -> common::Reply {
    let body = json!({ "design": design, "index": index, "value": value });
    post(&app(), "/api/shape/follow", body.to_string()).await
}

#[tokio::test]
async fn classes_and_constraints_of_special_pinned_and_generic_designs() {
    let app = app();
    let s = get(&app, &format!("/api/shape?design={}", enc(SPECIAL)))
        .await
        .ok();
    assert_eq!(s["class"], "special");
    let constraints = s["constraints"].as_array().unwrap();
    assert_eq!(constraints.len(), 1);
    // The constraint keeps p2 = p3: its normal is ±(0, 0, -1, 1)/√2.
    let n: Vec<f64> = constraints[0]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(n[0].abs() < 1e-6 && n[1].abs() < 1e-6, "{n:?}");
    assert!((n[2] + n[3]).abs() < 1e-6 && (n[2].abs() - 0.5f64.sqrt()).abs() < 1e-6);
    assert_eq!(s["pinned"], json!([]));
    let p = get(&app, &format!("/api/shape?design={}", enc(PINNED)))
        .await
        .ok();
    assert_eq!(p["pinned"], json!([0]));
    let g = get(&app, &format!("/api/shape?design={}", enc(GENERIC)))
        .await
        .ok();
    assert_eq!(g["class"], "generic");
    assert_eq!(g["constraints"], json!([]));
    assert_eq!(g["samples_one_dof"], g["samples"]);
}

#[tokio::test]
async fn a_special_design_follows_its_constraint_and_keeps_moving() {
    // Moving p2 alone breaks the mechanism…
    assert_eq!(
        dof(&naive(0.24)),
        0,
        "the naive move must break it for this test to mean anything"
    );
    // …following moves p3 with it and keeps one DOF.
    let f = follow(SPECIAL, 2, 0.24).await.ok();
    let params: Vec<f64> = f["params"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!((params[2] - 0.24).abs() < 1e-12, "{params:?}");
    assert!((params[3] - 0.24).abs() < 1e-6, "p3 follows p2: {params:?}");
    assert!((params[0] - 0.12239750492).abs() < 1e-6 && (params[1] - 0.5).abs() < 1e-6);
    assert_eq!(f["class"], "special");
    assert!(f["steps"].as_u64().unwrap() >= 1);
    let spec = f["spec"].as_str().unwrap();
    assert_eq!(dof(spec), 1);
    // A live deployment of the followed design opens.
    let view = post_design(&app(), "/api/deploy", spec, json!({}))
        .await
        .ok();
    let frames = view["report"]["frames"].as_array().unwrap();
    assert!(frames.len() >= 2);
    let opened = view["report"]["max_expansion"].as_f64().unwrap();
    assert!(opened > 0.01, "max expansion {opened}");
}

#[tokio::test]
async fn a_pinned_parameter_is_refused_naming_it() {
    let r = follow(PINNED, 0, 0.22).await;
    let kind = assert_error(&r, StatusCode::UNPROCESSABLE_ENTITY, "pinned");
    assert_eq!(kind, "pinned");
    assert!(
        r.json()["error"].as_str().unwrap().contains("parameter 0"),
        "{}",
        r.text()
    );
}

#[tokio::test]
async fn a_generic_design_just_takes_the_value() {
    let f = follow(GENERIC, 1, 0.37).await.ok();
    assert_eq!(f["class"], "generic");
    assert_eq!(f["steps"], 0);
    assert_eq!(f["params"], json!([0.588675134594, 0.37]));
    assert_eq!(dof(f["spec"].as_str().unwrap()), 1);
}

#[tokio::test]
async fn bad_requests_are_one_line_errors() {
    let app = app();
    let cases: Vec<(common::Reply, StatusCode, &str)> = vec![
        (
            get(&app, "/api/shape").await,
            StatusCode::BAD_REQUEST,
            "missing design",
        ),
        (
            get(&app, &format!("/api/shape?design={}&x=1", enc(SPECIAL))).await,
            StatusCode::BAD_REQUEST,
            "unknown parameter",
        ),
        (
            get(&app, "/api/shape?design=IH999:1:1x1:a").await,
            StatusCode::UNPROCESSABLE_ENTITY,
            "unknown family",
        ),
        (
            get(
                &app,
                &format!(
                    "/api/shape?design={}",
                    enc("IH28:0.588675134594,0.35:1x1:xxxxxxxxxx")
                ),
            )
            .await,
            StatusCode::UNPROCESSABLE_ENTITY,
            "rigid design",
        ),
        (
            follow(SPECIAL, 7, 0.2).await,
            StatusCode::BAD_REQUEST,
            "no such parameter",
        ),
        (
            follow(SPECIAL, 2, 9.0).await,
            StatusCode::BAD_REQUEST,
            "too far",
        ),
        (
            post(&app, "/api/shape/follow", r#"{"design": "x", "index": 0}"#).await,
            StatusCode::BAD_REQUEST,
            "missing value",
        ),
        (
            post(
                &app,
                "/api/shape/follow",
                r#"{"design": "x", "index": -1, "value": 0}"#,
            )
            .await,
            StatusCode::BAD_REQUEST,
            "negative index",
        ),
    ];
    for (reply, status, what) in &cases {
        assert_error(reply, *status, what);
    }
    let rigid: Value = cases[3].0.json();
    assert_eq!(rigid["kind"], "not_one_dof", "{rigid}");
}

/// Issue 24 item 4: the sliders' ranges. Deploying at each end of a parameter's range is
/// accepted, and just past an end that is not the window's edge is refused as ill-shaped:
/// the server's refusal and the range come from the same checks.
#[tokio::test]
async fn shape_ranges_end_where_the_deployment_refuses_the_shape() {
    let app = app();
    let spec = "IH59:0.030263157895:1x1:aaaa";
    let r = get(&app, &format!("/api/shape/ranges?design={}", enc(spec)))
        .await
        .ok();
    assert_eq!(r["spec"], spec);
    let range = &r["ranges"][0];
    let (lo, hi, tol) = (
        range["lo"].as_f64().unwrap(),
        range["hi"].as_f64().unwrap(),
        range["tol"].as_f64().unwrap(),
    );
    assert!(lo < 0.030263157895 && 0.030263157895 < hi, "{range}");
    let with = |x: f64| format!("IH59:{x}:1x1:aaaa");
    for x in [lo, hi] {
        let d = post_design(&app, "/api/deploy", &with(x), json!({})).await;
        assert_ne!(
            d.status,
            StatusCode::UNPROCESSABLE_ENTITY,
            "{x}: {}",
            d.text()
        );
    }
    if range["hi_open"] == false {
        let d = post_design(&app, "/api/deploy", &with(hi + 10.0 * tol), json!({})).await;
        assert_eq!(
            assert_error(&d, StatusCode::UNPROCESSABLE_ENTITY, "past hi"),
            "ill_shaped"
        );
    }
    let bad = get(
        &app,
        &format!("/api/shape/ranges?design={}&kerf=-1", enc(spec)),
    )
    .await;
    assert_error(&bad, StatusCode::BAD_REQUEST, "bad kerf");
    let unknown = get(&app, &format!("/api/shape/ranges?design={}&k=1", enc(spec))).await;
    assert_error(&unknown, StatusCode::BAD_REQUEST, "unknown key");
    // The families list says what each parameter does.
    let families = get(&app, "/api/families").await.ok();
    let ih59 = families
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["name"] == "IH59")
        .unwrap();
    assert!(!ih59["param_effects"][0]["description"]
        .as_str()
        .unwrap()
        .is_empty());
}

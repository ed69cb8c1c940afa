//! Bad input: every malformed query, body, method and path gets a 4xx answer (JSON
//! `{error, kind, hint}` under `/api/`), never a 5xx, and no request path reaches the file
//! system.

use crate::common;

use axum::body::Body;
use axum::http::{Method, Request, StatusCode};
use common::{
    app, assert_client_error, assert_error, catalogue, enc, get, post, post_design, send, summaries,
};
use isogami_web::assets::{content_type, ASSETS};
use serde_json::json;

#[tokio::test]
async fn bad_query_parameters_are_400_with_a_json_error() {
    let app = app();
    let spec = enc(&summaries(&catalogue().db)[0].spec);
    let long = "a".repeat(5000);
    let mut uris: Vec<String> = [
        "family=IH999",
        "family=IH19",
        "family=foo",
        "family=%ff%fe",
        "family=",
        "cell=0x1",
        "cell=9x9",
        "cell=2",
        "tiles=-1",
        "tiles=two",
        "behaviour=wobbly",
        "origin=alien",
        "range=max_area_ratio:NaN:",
        "range=max_area_ratio:nan:",
        "range=max_area_ratio::inf",
        "range=max_area_ratio:-inf:",
        "range=max_area_ratio:1e999:",
        "range=max_area_ratio::-1e400",
        "range=max_area_ratio:3:1",
        "range=max_area_ratio:abc:",
        "range=max_area_ratio",
        "range=max_area_ratio:1:2:3",
        "range=v9:0:1",
        "range=nope:0:1",
        "limit=0",
        "limit=501",
        "limit=100000",
        "limit=-1",
        "limit=99999999999999999999",
        "limit=",
        "offset=-1",
        "offset=1e3",
        "offset=99999999999999999999",
        "sort=nope",
        "sort=-",
        "sort=",
        "sort=--spec",
        "colour=red",
    ]
    .iter()
    .flat_map(|q| {
        ["designs", "facets"]
            .iter()
            .map(move |e| format!("/api/{e}?{q}"))
    })
    .collect();
    uris.extend([
        format!("/api/designs?{long}=1"),
        format!("/api/designs?family={long}"),
        format!("/api/designs?range={long}"),
        // Past what SQLite counts (facets take no page, so only here).
        "/api/designs?offset=18446744073709551615".into(),
        "/api/scatter?x=max_expansion".into(),
        "/api/scatter?y=max_expansion".into(),
        "/api/scatter?x=nope&y=steps".into(),
        "/api/scatter?x=v7&y=v0".into(),
        "/api/scatter?x=steps&y=kerf&range=kerf:NaN:".into(),
        "/api/design".into(),
        format!("/api/design?spec={spec}&colour=red"),
        format!("/api/design?spec={}", "a".repeat(5000)),
        "/api/thumbnail".into(),
        format!("/api/thumbnail?spec={spec}&x=1"),
        "/api/gif".into(),
        format!("/api/gif?spec={spec}&kerf=NaN"),
        format!("/api/gif?spec={spec}&kerf=inf"),
        format!("/api/gif?spec={spec}&kerf=1e999"),
        format!("/api/gif?spec={spec}&kerf=abc"),
        format!("/api/gif?spec={spec}&kerf=0.5"),
        format!("/api/gif?spec={spec}&kerf=-0.01"),
        format!("/api/gif?spec={spec}&frames=100000"),
        "/api/sheet".into(),
        format!("/api/sheet?design={spec}&region=NaNxNaN"),
        format!("/api/sheet?design={spec}&region=99999999999999999999x1"),
        format!("/api/sheet?design={spec}&region=disc:inf"),
        format!("/api/sheet?design={spec}&region=rect:1e999,1"),
        format!("/api/sheet?design={spec}&region=polygon:"),
        format!("/api/sheet?design={spec}&edge_mm=-1"),
        format!("/api/sheet?design={spec}&t=inf"),
        format!("/api/sheet?design={spec}&min_cover=1e999"),
        format!("/api/sheet?design={spec}&kerf=abc"),
        format!("/api/sheet?design={spec}&deploy=true&frames=100000"),
        format!("/api/sheet?design={spec}&deploy=true&frames=-1"),
        format!("/api/sheet?design={spec}&deploy=yes"),
        format!("/api/sheet?design={spec}&design={spec}"),
        format!("/api/export?design={spec}&format=fold&raw=2"),
    ]);
    for uri in uris {
        let reply = get(&app, &uri).await;
        let kind = assert_error(&reply, StatusCode::BAD_REQUEST, &uri);
        assert_eq!(kind, "bad_parameter", "{uri}");
    }
}

#[tokio::test]
async fn malformed_designs_are_4xx_with_a_json_error() {
    let app = app();
    let s = &summaries(&catalogue().db)[0];
    let wrong_count = format!("{}:{}:{}:{}a", s.family, "", s.cell, s.joints);
    let json_edge = json!({"family": s.family.to_string(), "cell": [1, 1],
        "joints": [{"edge": 99, "at": "a"}]})
    .to_string();
    let json_twice = json!({"family": s.family.to_string(), "cell": [1, 1],
        "joints": [{"edge": 0, "at": "a"}, {"edge": 0, "at": "b"}]})
    .to_string();
    let designs = [
        "IH999:0.5:1x1:aaa".to_string(),
        "IH19::1x1:aaaa".into(),
        "garbage".into(),
        "".into(),
        ":::".into(),
        "IH59:0.1:1x1:aaa".into(),
        "IH59:0.1:1x1:aaaaa".into(),
        "IH59:0.1:1x1:aaqa".into(),
        "IH59:0.1:9x9:aaaa".into(),
        "IH59:0.1:0x1:aaaa".into(),
        "IH59:NaN:1x1:aaaa".into(),
        "IH59:inf:1x1:aaaa".into(),
        "IH59:1e999:1x1:aaaa".into(),
        "IH59:0.1,0.2,0.3,0.4,0.5,0.6,0.7:1x1:aaaa".into(),
        wrong_count,
        json_edge,
        json_twice,
        "{\"family\": \"IH59\"}".into(),
        "a".repeat(20 * 1024),
    ];
    for endpoint in ["/api/deploy", "/api/gif", "/api/sheet"] {
        for d in &designs {
            let reply = if endpoint == "/api/gif" {
                get(&app, &format!("{endpoint}?spec={}", enc(d))).await
            } else if endpoint == "/api/sheet" {
                get(&app, &format!("{endpoint}?design={}", enc(d))).await
            } else {
                post_design(&app, endpoint, d, json!({})).await
            };
            let what = format!("{endpoint} {}", &d[..d.len().min(80)]);
            let kind = assert_client_error(&reply, &what);
            assert!(
                ["bad_design", "bad_parameter", "ill_shaped"].contains(&kind.as_str()),
                "{what}: {kind}"
            );
        }
    }
}

#[tokio::test]
async fn bad_bodies_are_4xx_with_a_json_error() {
    let app = app();
    let spec = summaries(&catalogue().db)[0].spec.clone();
    let deep = format!("{}{}", "[".repeat(10_000), "]".repeat(10_000));
    let bodies: Vec<Vec<u8>> = [
        String::new(),
        "hello".into(),
        "[1, 2]".into(),
        "{}".into(),
        "null".into(),
        "{\"design\": 5}".into(),
        "{\"design\": null}".into(),
        format!("{{\"design\": \"{spec}\", \"kerf\": \"abc\"}}"),
        format!("{{\"design\": \"{spec}\", \"kerf\": NaN}}"),
        format!("{{\"design\": \"{spec}\", \"kerf\": Infinity}}"),
        format!("{{\"design\": \"{spec}\", \"kerf\": 1e999}}"),
        format!("{{\"design\": \"{spec}\", \"kerf\": 0.5}}"),
        format!("{{\"design\": \"{spec}\", \"kerf\": 0}}"),
        format!("{{\"design\": \"{spec}\", \"kerf\": -0.01}}"),
        format!("{{\"design\": \"{spec}\", \"kerf\": 1e-300}}"),
        format!("{{\"design\": \"{spec}\", \"frames\": 100000}}"),
        format!("{{\"design\": \"{spec}\", \"frames\": 1}}"),
        format!("{{\"design\": \"{spec}\", \"frames\": 0}}"),
        format!("{{\"design\": \"{spec}\", \"frames\": -1}}"),
        format!("{{\"design\": \"{spec}\", \"frames\": 1e20}}"),
        format!("{{\"design\": \"{spec}\", \"frames\": 2.5}}"),
        format!("{{\"design\": \"{spec}\", \"colour\": \"red\"}}"),
        format!("{{\"design\": \"{spec}\"}} trailing"),
        format!("design={}", enc(&spec)),
        deep,
    ]
    .into_iter()
    .map(String::into_bytes)
    .chain([b"{\"design\": \"\xff\xfe\"}".to_vec()])
    .collect();
    for endpoint in ["/api/deploy", "/api/designs"] {
        for body in &bodies {
            let reply = post(&app, endpoint, body.clone()).await;
            let text = String::from_utf8_lossy(&body[..body.len().min(80)]).into_owned();
            let kind = assert_error(
                &reply,
                StatusCode::BAD_REQUEST,
                &format!("{endpoint} {text}"),
            );
            assert_eq!(kind, "bad_parameter", "{endpoint} {text}");
        }
    }
}

#[tokio::test]
async fn oversized_bodies_are_413() {
    let app = app();
    let limit = isogami_web::ServerSettings::default().max_body;
    let spec = summaries(&catalogue().db)[0].spec.clone();
    for endpoint in ["/api/deploy", "/api/designs"] {
        // A valid request padded past the limit with whitespace.
        let padded = format!("{{\"design\": \"{spec}\"{}}}", " ".repeat(limit));
        let reply = post(&app, endpoint, padded).await;
        assert_error(&reply, StatusCode::PAYLOAD_TOO_LARGE, endpoint);
        // Just under the limit it is read (and refused for its design text's length only).
        let text = "a".repeat(limit - 64);
        let reply = post_design(&app, endpoint, &text, json!({})).await;
        assert_error(&reply, StatusCode::BAD_REQUEST, endpoint);
    }
}

#[tokio::test]
async fn wrong_methods_are_405_with_a_json_error() {
    let app = app();
    let cases = [
        (Method::GET, "/api/deploy"),
        (Method::PUT, "/api/designs"),
        (Method::DELETE, "/api/designs"),
        (Method::POST, "/api/stats"),
        (Method::POST, "/api/facets"),
        (Method::PATCH, "/api/design"),
    ];
    for (method, uri) in cases {
        let request = Request::builder()
            .method(method.clone())
            .uri(uri)
            .body(Body::from("{}"))
            .unwrap();
        let reply = send(&app, request).await;
        let kind = assert_error(
            &reply,
            StatusCode::METHOD_NOT_ALLOWED,
            &format!("{method} {uri}"),
        );
        assert_eq!(kind, "method_not_allowed");
    }
}

/// Whether `body` holds a line (of at least 8 characters) of the file at `path`.
fn leaks(body: &[u8], path: &str) -> bool {
    let Ok(text) = std::fs::read_to_string(path) else {
        return false;
    };
    let body = String::from_utf8_lossy(body);
    text.lines()
        .map(str::trim)
        .filter(|l| l.len() >= 8)
        .any(|l| body.contains(l))
}

#[tokio::test]
async fn request_paths_never_reach_the_file_system() {
    let app = app();
    let manifest = env!("CARGO_MANIFEST_DIR");
    let secrets = [
        "/etc/passwd".to_string(),
        format!("{manifest}/Cargo.toml"),
        format!("{manifest}/src/lib.rs"),
        format!("{manifest}/../../Cargo.toml"),
    ];
    let uris = [
        "/static/../../etc/passwd",
        "/..%2F..%2Fetc%2Fpasswd",
        "/%2e%2e/%2e%2e/etc/passwd",
        "/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
        "/%c0%ae%c0%ae/%c0%ae%c0%ae/etc/passwd",
        "/....//....//etc/passwd",
        "/index.html/../../../../etc/passwd",
        "/../Cargo.toml",
        "/Cargo.toml",
        "/src/lib.rs",
        "/build.rs",
        "//etc/passwd",
        "/etc/passwd",
        "/%2Fetc%2Fpasswd",
        "/api/../Cargo.toml",
        "/api/..%2F..%2FCargo.toml",
        "/api/%2e%2e/%2e%2e/Cargo.toml",
        "/api/stats/../../etc/passwd",
        "/api/thumbnail?spec=..%2F..%2Fetc%2Fpasswd",
        "/api/design?spec=%2Fetc%2Fpasswd",
        "/api/gif?spec=..%2F..%2FCargo.toml",
    ];
    for uri in uris {
        let reply = get(&app, uri).await;
        assert!(reply.status.is_client_error(), "{uri}: {}", reply.status);
        if uri.starts_with("/api/") {
            assert_client_error(&reply, uri);
        } else {
            assert_eq!(reply.status, StatusCode::NOT_FOUND, "{uri}");
        }
        for secret in &secrets {
            assert!(!leaks(&reply.body, secret), "{uri} shows {secret}");
        }
    }
}

#[tokio::test]
async fn unknown_api_paths_are_404_json() {
    let app = app();
    for uri in [
        "/api/",
        "/api/nope",
        "/api/designs/extra",
        "/api/stats.json",
        "/api/DESIGNS",
        "/api/index.html",
    ] {
        let reply = get(&app, uri).await;
        assert_eq!(
            assert_error(&reply, StatusCode::NOT_FOUND, uri),
            "not_found"
        );
    }
}

#[tokio::test]
async fn embedded_front_end_is_served_as_built() {
    let app = app();
    assert!(ASSETS.iter().any(|(name, _)| *name == "index.html"));
    for (name, bytes) in ASSETS {
        let reply = get(&app, &format!("/{name}")).await;
        assert_eq!(reply.status, StatusCode::OK, "{name}");
        assert_eq!(reply.body, *bytes, "{name}");
        assert_eq!(reply.content_type, content_type(name), "{name}");
    }
    let index = ASSETS.iter().find(|(n, _)| *n == "index.html").unwrap().1;
    let root = get(&app, "/").await;
    assert_eq!(root.body, index);
    assert!(root.content_type.starts_with("text/html"));
}

#[tokio::test]
async fn the_server_says_its_mode_where_a_page_looks_first() {
    // Every page fetches ./data/site.json first (a static site's file says "static"); the
    // server answers it, so no page logs a 404 in server mode (issue 24 item 8).
    let app = app();
    let reply = get(&app, "/data/site.json").await;
    assert_eq!(reply.status, StatusCode::OK);
    assert!(reply.content_type.starts_with("application/json"));
    assert_eq!(reply.json()["mode"], "server");
}

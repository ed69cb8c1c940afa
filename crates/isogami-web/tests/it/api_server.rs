//! Issue 23's server items over the real server: a damaged database is refused before
//! serving, slow clients are dropped (idle, unfinished headers, slow or oversized bodies),
//! exports are bounded in work, time and concurrency, saves obey the exploration's
//! admission rule, and the 500 hint names a real command. The slow-client and heavy-export
//! cases also run mixed together against one server (`a_server_under_hostile_clients_...`).

use crate::common;

use common::*;
use isogami::api::resolve_design;
use isogami::export::{export_design, ExportOptions, Format, PatchRequest};
use isogami_web::{serve_on, AppState, ServerSettings};
use serde_json::{json, Value};
use std::io::{Read, Write};
use std::net::SocketAddr;
use std::net::TcpStream;
use std::path::Path;
use std::time::{Duration, Instant};

/// The heavy export: a 40×40 STL of a 6-tile cell.
const HEAVY: &str = "/api/export?design=IH88::1x1:bbbaabbab&format=stl&patch=40x40";

/// A running server on its own runtime; stopped when dropped.
struct Server {
    addr: SocketAddr,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    runtime: Option<tokio::runtime::Runtime>,
}

impl Drop for Server {
    fn drop(&mut self) {
        drop(self.stop.take());
        if let Some(rt) = self.runtime.take() {
            rt.shutdown_timeout(Duration::from_secs(1));
        }
    }
}

/// A running server over `db`.
fn start(db: &Path, settings: ServerSettings) -> Server {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let state = AppState::open(db, settings).unwrap();
    let listener = runtime
        .block_on(tokio::net::TcpListener::bind("127.0.0.1:0"))
        .unwrap();
    let addr = listener.local_addr().unwrap();
    let (tx, rx) = tokio::sync::oneshot::channel::<()>();
    runtime.spawn(serve_on(listener, state, async move {
        let _ = rx.await;
    }));
    Server {
        addr,
        stop: Some(tx),
        runtime: Some(runtime),
    }
}

fn short_timeouts() -> ServerSettings {
    ServerSettings {
        header_timeout: Duration::from_millis(400),
        body_timeout: Duration::from_millis(400),
        ..ServerSettings::default()
    }
}

/// Reads until the server closes the connection (or `limit` passes): what it sent and
/// whether it closed.
fn read_until_closed(stream: &mut TcpStream, limit: Duration) -> (String, bool) {
    let mut got = Vec::new();
    let end = Instant::now() + limit;
    let mut buf = [0u8; 4096];
    loop {
        let left = end.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return (String::from_utf8_lossy(&got).into(), false);
        }
        stream.set_read_timeout(Some(left)).unwrap();
        match stream.read(&mut buf) {
            Ok(0) => return (String::from_utf8_lossy(&got).into(), true),
            Ok(n) => got.extend_from_slice(&buf[..n]),
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                ) =>
            {
                return (String::from_utf8_lossy(&got).into(), false)
            }
            Err(_) => return (String::from_utf8_lossy(&got).into(), true),
        }
    }
}

/// One request on a fresh connection: status line and body.
fn http(addr: SocketAddr, request: &str) -> (String, String) {
    let mut s = TcpStream::connect(addr).unwrap();
    s.write_all(request.as_bytes()).unwrap();
    let (text, _) = read_until_closed(&mut s, Duration::from_secs(60));
    let status = text.lines().next().unwrap_or("").to_string();
    let body = text.split_once("\r\n\r\n").map_or("", |x| x.1).to_string();
    (status, body)
}

fn get_close(path: &str) -> String {
    format!("GET {path} HTTP/1.1\r\nHost: t\r\nConnection: close\r\n\r\n")
}

/// The one-line JSON error in a body (chunked or not).
fn error_kind(body: &str) -> String {
    let start = body.find('{').unwrap_or(0);
    let end = body.rfind('}').map_or(body.len(), |e| e + 1);
    let v: Value = serde_json::from_str(&body[start..end]).unwrap_or(Value::Null);
    let message = v["error"].as_str().unwrap_or("");
    assert!(!message.is_empty() && !message.contains('\n'), "{body}");
    v["kind"].as_str().unwrap_or("").to_string()
}

#[test]
fn idle_connections_and_unfinished_headers_are_closed() {
    let settings = short_timeouts();
    let server = start(&catalogue().db, settings);
    let addr = server.addr;
    let bound = settings.header_timeout * 5;

    // Connected, nothing sent.
    let mut idle = TcpStream::connect(addr).unwrap();
    let (_, closed) = read_until_closed(&mut idle, bound);
    assert!(closed, "an idle connection was held past {bound:?}");

    // Headers trickled a byte at a time and never finished.
    let mut slow = TcpStream::connect(addr).unwrap();
    let started = Instant::now();
    let mut closed = false;
    for b in
        b"GET /api/stats HTTP/1.1\r\nHost: t\r\nX-Slow: aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa"
    {
        if slow.write_all(&[*b]).is_err() {
            closed = true;
            break;
        }
        std::thread::sleep(Duration::from_millis(50));
        if started.elapsed() > bound {
            break;
        }
    }
    if !closed {
        closed = read_until_closed(&mut slow, bound).1;
    }
    assert!(closed, "unfinished headers were held past {bound:?}");
    assert!(started.elapsed() < bound + Duration::from_secs(2));

    // A kept-alive connection that answered once is closed once idle.
    let mut kept = TcpStream::connect(addr).unwrap();
    kept.write_all(b"GET /api/families HTTP/1.1\r\nHost: t\r\n\r\n")
        .unwrap();
    let (text, closed) = read_until_closed(&mut kept, bound + Duration::from_secs(2));
    assert!(text.starts_with("HTTP/1.1 200"), "{text:.200}");
    assert!(closed, "an idle kept-alive connection was held");

    // The server still answers.
    let (status, _) = http(addr, &get_close("/api/stats"));
    assert!(status.contains("200"), "{status}");
}

#[test]
fn oversized_and_slow_bodies_are_refused_up_front() {
    let settings = short_timeouts();
    let server = start(&catalogue().db, settings);
    let addr = server.addr;
    let bound = settings.body_timeout * 5;

    // A declared length over the limit: 413 before a byte of the body is sent.
    let mut s = TcpStream::connect(addr).unwrap();
    s.write_all(
        b"POST /api/deploy HTTP/1.1\r\nHost: t\r\nContent-Type: application/json\r\n\
          Content-Length: 99999999999\r\n\r\n",
    )
    .unwrap();
    let (text, closed) = read_until_closed(&mut s, bound);
    assert!(text.starts_with("HTTP/1.1 413"), "{text:.300}");
    assert_eq!(error_kind(&text), "bad_body");
    assert!(closed, "the connection of a refused body stayed open");

    // Just over the limit declared, nothing sent: also 413 at once.
    let over = ServerSettings::default().max_body + 1;
    let (status, _) = http(
        addr,
        &format!("POST /api/designs HTTP/1.1\r\nHost: t\r\nContent-Length: {over}\r\n\r\n"),
    );
    assert!(status.contains("413"), "{status}");

    // A body that stops half-way: 408 within a few body timeouts, connection closed.
    let mut s = TcpStream::connect(addr).unwrap();
    let started = Instant::now();
    s.write_all(b"POST /api/deploy HTTP/1.1\r\nHost: t\r\nContent-Length: 100\r\n\r\n{\"des")
        .unwrap();
    let (text, closed) = read_until_closed(&mut s, bound + Duration::from_secs(2));
    assert!(text.starts_with("HTTP/1.1 408"), "{text:.300}");
    assert_eq!(error_kind(&text), "slow_body");
    assert!(closed);
    assert!(started.elapsed() < bound, "{:?}", started.elapsed());

    // A body within the limit sent at once is still read.
    let body = json!({ "design": "rotating-squares", "frames": 5 }).to_string();
    let (status, _) = http(
        addr,
        &format!(
            "POST /api/deploy HTTP/1.1\r\nHost: t\r\nConnection: close\r\n\
             Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
            body.len()
        ),
    );
    assert!(status.contains("200"), "{status}");
}

#[tokio::test]
async fn exports_too_large_for_the_server_are_422_before_any_work() {
    let app = app_with(
        &catalogue().db,
        ServerSettings {
            sim_timeout: Duration::from_millis(500),
            ..ServerSettings::default()
        },
    );
    for uri in [
        HEAVY.to_string(),
        format!("{HEAVY}&raw=true"),
        "/api/export?design=IH88::1x1:bbbaabbab&format=3mf&patch=20x20".into(),
        "/api/export?design=IH88::1x1:bbbaabbab&format=svg&patch=40x40".into(),
    ] {
        let started = Instant::now();
        let reply = get(&app, &uri).await;
        assert_eq!(
            assert_error(&reply, axum::http::StatusCode::UNPROCESSABLE_ENTITY, &uri),
            "too_large"
        );
        let message = reply.json()["error"].as_str().unwrap().to_string();
        assert!(message.contains("tiles"), "{message}");
        assert!(started.elapsed() < Duration::from_secs(5), "{uri}");
    }
    // A patch under the limit is still written.
    let reply = get(
        &app,
        "/api/export?design=rotating-squares&format=tiles-csv&patch=3x3&raw=true",
    )
    .await;
    assert_eq!(reply.status, 200, "{}", reply.text());
}

/// An export whose completion is most of its work: IH9's 16×16 rectangle (about 1,000
/// tiles, under the server's cap) pruned round after round (to a refusal: it keeps less than
/// half the region). Returns its URI, the time of the same export raw (deployment and counts
/// alone) and completed, in the library.
fn completion_bound_export() -> (String, Duration, Duration) {
    let spec = "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-";
    let design = resolve_design(spec).unwrap();
    let time = |complete: bool| {
        let request = PatchRequest {
            rows: 16,
            cols: 16,
            complete,
            ..PatchRequest::default()
        };
        let started = Instant::now();
        let _ = export_design(
            &design,
            &request,
            Format::TilesCsv,
            &ExportOptions::default(),
            &mut |_| true,
        );
        started.elapsed()
    };
    let raw = time(false);
    let full = time(true);
    (
        format!("/api/export?design={spec}&format=tiles-csv&patch=16x16"),
        raw,
        full,
    )
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_export_is_answered_by_its_deadline_and_its_job_stops_and_frees_its_permit() {
    let (uri, raw, full) = completion_bound_export();
    // A deadline inside the completion.
    let timeout = raw + full.saturating_sub(raw) / 8;
    let app = app_with(
        &catalogue().db,
        ServerSettings {
            sim_timeout: timeout,
            heavy_jobs: 1,
            ..ServerSettings::default()
        },
    );
    let started = Instant::now();
    let reply = get(&app, &uri).await;
    let answered = started.elapsed();
    assert_eq!(
        assert_error(&reply, axum::http::StatusCode::UNPROCESSABLE_ENTITY, &uri),
        "timeout"
    );
    assert!(
        answered < timeout * 5 + Duration::from_millis(500),
        "answered after {answered:?} with a {timeout:?} limit (the export alone takes {full:?})"
    );
    // The completion polls the deadline every pruning round, so the job stops by itself and
    // gives its permit back before it answers: the next export gets the permit at once. (It
    // used to run its completion to the end, holding the permit up to `full`, and a second
    // export waiting `timeout` for it was told the server is busy.) That export may itself
    // run into the short limit: any answer but `busy` says it had the permit.
    let small = "/api/export?design=rotating-squares&format=tiles-csv&patch=1x1";
    let reply = get(&app, small).await;
    assert!(
        reply.status == 200 || reply.json()["kind"] != "busy",
        "the stopped export still held its permit {:?} after it was answered (the export \
         takes {full:?}, {raw:?} raw, limit {timeout:?}): {}",
        started.elapsed() - answered,
        reply.text()
    );
}

#[test]
fn a_server_under_hostile_clients_keeps_answering() {
    let settings = ServerSettings {
        sim_timeout: Duration::from_millis(300),
        ..short_timeouts()
    };
    let server = start(&catalogue().db, settings);
    let addr = server.addr;
    let mut hostile = Vec::new();
    // Idle connections, unfinished headers, oversized and stalled bodies, heavy exports and
    // clients that leave in the middle of an export, all at once.
    for k in 0..12 {
        hostile.push(std::thread::spawn(move || {
            let mut s = TcpStream::connect(addr).unwrap();
            let _ = match k % 6 {
                0 => Ok(()),
                1 => s.write_all(b"GET /api/stats HTTP/1.1\r\nHo"),
                2 => s.write_all(
                    b"POST /api/designs HTTP/1.1\r\nHost: t\r\nContent-Length: 99999999999\r\n\r\n",
                ),
                3 => s.write_all(
                    b"POST /api/deploy HTTP/1.1\r\nHost: t\r\nContent-Length: 50\r\n\r\n{",
                ),
                4 => s.write_all(get_close(HEAVY).as_bytes()),
                _ => {
                    let uri = "/api/export?design=IH88::1x1:bbbaabbab&format=stl&patch=5x5";
                    let _ = s.write_all(get_close(uri).as_bytes());
                    std::thread::sleep(Duration::from_millis(100));
                    drop(s);
                    return (k, String::new(), true);
                }
            };
            let (text, closed) = read_until_closed(&mut s, Duration::from_secs(10));
            (k, text, closed)
        }));
    }
    let started = Instant::now();
    let (status, _) = http(addr, &get_close("/api/stats"));
    assert!(status.contains("200"), "{status}");
    for h in hostile {
        let (k, text, closed) = h.join().unwrap();
        assert!(closed, "hostile client {k} was held open");
        let status = text.lines().next().unwrap_or("");
        match k % 6 {
            2 => assert!(status.contains("413"), "{k}: {status}"),
            3 => assert!(status.contains("408"), "{k}: {status}"),
            4 => assert!(status.contains("422"), "{k}: {status}"),
            _ => {}
        }
    }
    assert!(started.elapsed() < Duration::from_secs(15));
    let (status, _) = http(addr, &get_close("/api/families"));
    assert!(status.contains("200"), "{status}");
}

#[test]
fn a_database_edited_behind_the_tools_back_is_refused_before_serving() {
    let (_dir, db) = private_db("tampered");
    let conn = rusqlite::Connection::open(&db).unwrap();
    let changed = conn
        .execute(
            "UPDATE designs SET max_area_ratio = max_area_ratio * 2 \
             WHERE rowid IN (SELECT rowid FROM designs LIMIT 2)",
            [],
        )
        .unwrap();
    assert_eq!(changed, 2);
    drop(conn);
    let e = AppState::open(&db, ServerSettings::default()).unwrap_err();
    let text = e.to_string();
    assert!(!text.contains('\n'), "{text}");
    assert!(text.to_lowercase().contains("checksum"), "{text}");
    // The untouched copy opens.
    assert!(AppState::open(&catalogue().db, ServerSettings::default()).is_ok());
}

#[test]
fn the_internal_error_hint_names_a_real_command() {
    let e = isogami_web::error::ApiError::internal("x");
    assert!(!e.hint.contains("db verify"), "{}", e.hint);
    assert!(e.hint.contains("isogami db stats"), "{}", e.hint);
}

#[tokio::test]
async fn saves_obey_the_explorations_admission_rule() {
    let (_dir, db) = private_db("admission");
    let before = summaries(&db).len();
    let bytes = std::fs::read(&db).unwrap();
    let app = app_with(&db, ServerSettings::default());
    // Seven degrees of freedom: it comes apart instead of deploying.
    let reply = post_design(&app, "/api/designs", "IH93::1x1:---", json!({})).await;
    assert_eq!(
        assert_error(&reply, axum::http::StatusCode::UNPROCESSABLE_ENTITY, "IH93"),
        "not_admitted"
    );
    let message = reply.json()["error"].as_str().unwrap().to_string();
    assert!(message.contains("degrees of freedom"), "{message}");
    assert_eq!(summaries(&db).len(), before);
    assert_eq!(std::fs::read(&db).unwrap(), bytes, "a refused save wrote");
}

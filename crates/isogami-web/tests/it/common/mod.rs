//! Shared fixtures of the API tests: a real design database made once per test binary by the
//! exploration pipeline (run_unit → UnitRecords → StoreWriter, as `isogami explore` does),
//! scratch folders, the router called in-process, and checks every error answer must pass.
#![allow(dead_code)]

pub mod oracle;

use axum::body::Body;
use axum::http::{header, Method, Request, StatusCode};
use axum::Router;
use http_body_util::BodyExt;
use isogami::catalog::{run_unit, CatalogSettings};
use isogami::cell::CellDims;
use isogami::tiling::Family;
use isogami_store::{Check, DesignSummary, RunInfo, Store, StoreWriter, UnitRecords};
use isogami_web::{router, AppState, ServerSettings};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use tower::ServiceExt;

/// Work units of the fixture: (family, a, b). Four families on their minimal cell and one on
/// a 2×1 supercell give several values of every facet that varies in a quick exploration
/// (family, cell, tile count, behaviour, linkage signature) and families with one, two and
/// three shape parameters (so v1 and v2 are missing on some rows).
/// IH1's 1×2 and 2×1 cells hold the same designs (cell twins), which the file stores once.
const UNITS: [(u32, u8, u8); 7] = [
    (84, 1, 1),
    (59, 1, 1),
    (86, 1, 1),
    (22, 1, 1),
    (69, 2, 1),
    (1, 1, 2),
    (1, 2, 1),
];

/// The quick exploration's settings (as `isogami explore --quick`), allowing 2×1 cells.
pub fn catalog_settings() -> CatalogSettings {
    let mut s = CatalogSettings::default();
    s.topology.max_dims = 2;
    s.topology.max_edges = 12;
    s.samples = 4;
    s
}

/// The fixture database of this test binary.
pub struct Catalogue {
    /// The database file (never written after it is made: copy it with [`private_db`]).
    pub db: PathBuf,
    /// The settings fingerprint it was made with.
    pub settings: String,
    /// Work units committed.
    pub units: usize,
}

/// The fixture database, made on first use.
pub fn catalogue() -> &'static Catalogue {
    static CELL: OnceLock<Catalogue> = OnceLock::new();
    CELL.get_or_init(|| {
        let dir = root().join("fixture");
        std::fs::create_dir_all(&dir).unwrap();
        let db = dir.join("catalogue.db");
        let settings = catalog_settings();
        let fingerprint = settings.fingerprint();
        let run = RunInfo {
            tool_version: env!("CARGO_PKG_VERSION"),
            settings: &fingerprint,
        };
        let mut writer = StoreWriter::open(&db, Some(run), Check::Full).unwrap();
        for (n, a, b) in UNITS {
            let family = Family::from_number(n).unwrap();
            let dims = CellDims::new(a, b).unwrap();
            let outcome = run_unit(family, dims, &settings).unwrap();
            assert!(!outcome.entries.is_empty(), "{family}/{dims} keeps designs");
            writer
                .commit_unit(&UnitRecords::from_outcome(&outcome, 0.25).unwrap())
                .unwrap();
        }
        // As `explore_into` does after committing units.
        writer.refresh_cell_twins().unwrap();
        writer.refresh_motion_classes().unwrap();
        drop(writer);
        Catalogue {
            db,
            settings: fingerprint,
            units: UNITS.len(),
        }
    })
}

/// This process's folder under cargo's temporary folder for integration tests; folders left
/// by earlier test processes that have ended are removed first.
fn root() -> &'static Path {
    static CELL: OnceLock<PathBuf> = OnceLock::new();
    CELL.get_or_init(|| {
        let base = Path::new(env!("CARGO_TARGET_TMPDIR")).join("isogami-web-tests");
        let _ = std::fs::create_dir_all(&base);
        if Path::new("/proc/self").exists() {
            for entry in std::fs::read_dir(&base).into_iter().flatten().flatten() {
                let name = entry.file_name().to_string_lossy().to_string();
                let alive = Path::new("/proc").join(&name).exists();
                if name.parse::<u32>().is_ok() && !alive {
                    let _ = std::fs::remove_dir_all(entry.path());
                }
            }
        }
        let dir = base.join(std::process::id().to_string());
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    })
}

/// A fresh folder for one test, removed when dropped.
pub struct Scratch(pub PathBuf);

impl Scratch {
    pub fn new(name: &str) -> Scratch {
        let dir = root().join(name);
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A private copy of the fixture database, for tests that write to it.
pub fn private_db(name: &str) -> (Scratch, PathBuf) {
    let dir = Scratch::new(name);
    let db = dir.path().join("catalogue.db");
    std::fs::copy(&catalogue().db, &db).unwrap();
    (dir, db)
}

/// Every summary of `db` in insertion order, read through the store.
pub fn summaries(db: &Path) -> Vec<DesignSummary> {
    Store::open_read(db, Check::Quick)
        .unwrap()
        .summaries()
        .unwrap()
}

/// The router over `db` with `settings`.
pub fn app_with(db: &Path, settings: ServerSettings) -> Router {
    router(AppState::open(db, settings).unwrap())
}

/// The router over the fixture database with default settings.
pub fn app() -> Router {
    app_with(&catalogue().db, ServerSettings::default())
}

/// An answer: status, content type and body.
#[derive(Debug, Clone)]
pub struct Reply {
    pub status: StatusCode,
    pub content_type: String,
    pub body: Vec<u8>,
}

impl Reply {
    /// The body as JSON (panics with the body when it is not).
    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.body).unwrap_or_else(|e| {
            panic!(
                "not JSON ({e}): {}",
                String::from_utf8_lossy(&self.body[..self.body.len().min(400)])
            )
        })
    }

    /// The JSON body of a 200 answer.
    pub fn ok(&self) -> Value {
        assert_eq!(
            self.status,
            StatusCode::OK,
            "{}",
            String::from_utf8_lossy(&self.body)
        );
        self.json()
    }

    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }
}

/// Sends `request` to `app`.
pub async fn send(app: &Router, request: Request<Body>) -> Reply {
    let response = app.clone().oneshot(request).await.unwrap();
    let status = response.status();
    let content_type = response
        .headers()
        .get(header::CONTENT_TYPE)
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let body = response.into_body().collect().await.unwrap().to_bytes();
    Reply {
        status,
        content_type,
        body: body.to_vec(),
    }
}

/// `GET uri`.
pub async fn get(app: &Router, uri: &str) -> Reply {
    send(
        app,
        Request::builder().uri(uri).body(Body::empty()).unwrap(),
    )
    .await
}

/// `POST uri` with a JSON body.
pub async fn post(app: &Router, uri: &str, body: impl Into<Body>) -> Reply {
    send(
        app,
        Request::builder()
            .method(Method::POST)
            .uri(uri)
            .header(header::CONTENT_TYPE, "application/json")
            .body(body.into())
            .unwrap(),
    )
    .await
}

/// `POST uri` with `{"design": design, ...extra}`.
pub async fn post_design(app: &Router, uri: &str, design: &str, extra: Value) -> Reply {
    let mut body = serde_json::json!({ "design": design });
    if let Value::Object(fields) = extra {
        body.as_object_mut().unwrap().extend(fields);
    }
    post(app, uri, body.to_string()).await
}

/// A query value, percent-encoded.
pub fn enc(text: &str) -> String {
    form_urlencoded::byte_serialize(text.as_bytes()).collect()
}

/// Checks an error answer: `status`, a JSON object of exactly `error`, `kind` and `hint`, all
/// non-empty single lines of bounded length. Returns the kind.
#[track_caller]
pub fn assert_error(reply: &Reply, status: StatusCode, what: &str) -> String {
    assert_eq!(reply.status, status, "{what}: {}", reply.text());
    assert!(
        reply.content_type.starts_with("application/json"),
        "{what}: content type {:?}",
        reply.content_type
    );
    let v = reply.json();
    let object = v.as_object().unwrap_or_else(|| panic!("{what}: {v}"));
    let mut keys: Vec<&str> = object.keys().map(String::as_str).collect();
    keys.sort();
    assert_eq!(keys, ["error", "hint", "kind"], "{what}: {v}");
    for key in keys {
        let text = object[key]
            .as_str()
            .unwrap_or_else(|| panic!("{what}: {key} not a string"));
        assert!(!text.trim().is_empty(), "{what}: empty {key}");
        assert!(!text.contains(['\n', '\r']), "{what}: {key} not one line");
        assert!(
            text.chars().count() <= 400,
            "{what}: {key} is {} characters long",
            text.chars().count()
        );
    }
    object["kind"].as_str().unwrap().to_string()
}

/// Checks a 4xx error answer of any status.
#[track_caller]
pub fn assert_client_error(reply: &Reply, what: &str) -> String {
    assert!(
        reply.status.is_client_error(),
        "{what}: status {} ({})",
        reply.status,
        reply.text()
    );
    assert_error(reply, reply.status, what)
}

/// Every number in `v`, with its path, for finiteness checks.
pub fn numbers<'a>(v: &'a Value, path: String, out: &mut Vec<(String, &'a Value)>) {
    match v {
        Value::Array(items) => {
            for (k, item) in items.iter().enumerate() {
                numbers(item, format!("{path}[{k}]"), out);
            }
        }
        Value::Object(fields) => {
            for (k, item) in fields {
                numbers(item, format!("{path}.{k}"), out);
            }
        }
        _ => out.push((path, v)),
    }
}

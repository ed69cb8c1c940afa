//! The embedded front end. A request path is only ever compared with the names of embedded
//! files; it never reaches the file system.

use crate::assets::{asset as embedded, content_type};
use crate::error::ApiError;
use axum::http::{header, Method, StatusCode, Uri};
use axum::response::{IntoResponse, Response};

/// Every request no route took. Under `/api` (which the nested API router does not see when
/// nothing follows the prefix) the API's JSON 404; otherwise, for GET and HEAD, `/` is
/// `index.html` and any other path the embedded file of that name, or 404.
pub async fn asset(method: Method, uri: Uri) -> Response {
    let path = uri.path().trim_start_matches('/');
    if path == "api" || path.starts_with("api/") {
        return ApiError::no_endpoint().into_response();
    }
    if method != Method::GET && method != Method::HEAD {
        return (
            StatusCode::METHOD_NOT_ALLOWED,
            [(header::ALLOW, "GET, HEAD")],
            "method not allowed\n",
        )
            .into_response();
    }
    let name = if path.is_empty() { "index.html" } else { path };
    match embedded(name) {
        Some(bytes) => (
            [
                (header::CONTENT_TYPE, content_type(name)),
                (header::CACHE_CONTROL, "no-cache"),
            ],
            bytes,
        )
            .into_response(),
        None => (
            StatusCode::NOT_FOUND,
            [(header::CONTENT_TYPE, "text/plain; charset=utf-8")],
            "not found\n",
        )
            .into_response(),
    }
}

/// `data/site.json` of the server: the file a page fetches first to learn its mode (a static
/// site from `isogami site` holds its own, `"mode": "static"`, with the catalogue's data),
/// answered here so that no page logs a 404 in server mode.
pub async fn server_mode() -> axum::Json<serde_json::Value> {
    axum::Json(serde_json::json!({ "mode": "server" }))
}

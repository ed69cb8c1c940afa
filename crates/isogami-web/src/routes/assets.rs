//! The embedded front end. A request path is only ever compared with the names of embedded
//! files; it never reaches the file system.

use crate::assets::{asset as embedded, content_type};
use axum::http::{header, StatusCode, Uri};
use axum::response::{IntoResponse, Response};

/// `/` is `index.html`; any other path is the embedded file of that name, or 404.
pub async fn asset(uri: Uri) -> Response {
    let path = uri.path().trim_start_matches('/');
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

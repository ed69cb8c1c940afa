//! Export endpoints: the formats list and a design's export as a download.

use crate::error::ApiResult;
use crate::export::query::parse_export;
use crate::export::{catalog, export_bounded, Download};
use crate::filters::pairs;
use crate::state::AppState;
use axum::extract::{RawQuery, State};
use axum::http::{header, HeaderValue};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde_json::Value;

/// `GET /api/export/formats`: every format (name, description, extension, media type,
/// whether it is a folder, which settings groups it uses), the groups' fields, the request's
/// defaults and limits.
pub async fn formats() -> Json<Value> {
    Json(catalog())
}

/// The header that carries the library's warning about an exported sheet (percent-encoded,
/// `+` for spaces), e.g. a raw rectangle's DOF.
pub const WARNING_HEADER: &str = "x-isogami-warning";

/// `GET /api/export?design=&format=&patch=&…`: the file, as an attachment named
/// `<design-slug>-<R>x<C>.<ext>` (a folder format as a zip), with the library's warning about
/// the sheet in [`WARNING_HEADER`]. Allowed on a read-only server: nothing is written.
pub async fn export(State(state): State<AppState>, RawQuery(raw): RawQuery) -> ApiResult<Response> {
    let query = parse_export(&pairs(raw.as_deref()))?;
    let download =
        export_bounded(query, state.settings().sim_timeout, state.heavy().clone()).await?;
    Ok(download_response(download))
}

/// A finished export as an attachment, with the library's warning in [`WARNING_HEADER`].
pub fn download_response(download: Download) -> Response {
    let mut response = (
        [
            (header::CONTENT_TYPE, download.media_type.to_string()),
            (
                header::CONTENT_DISPOSITION,
                format!("attachment; filename=\"{}\"", download.file_name),
            ),
            (header::CACHE_CONTROL, "no-store".to_string()),
        ],
        download.bytes,
    )
        .into_response();
    if let Some(warning) = download.warning {
        // Percent-encoded: a header value is ASCII.
        let text: String = form_urlencoded::byte_serialize(warning.as_bytes()).collect();
        if let Ok(value) = HeaderValue::from_str(&text) {
            response.headers_mut().insert(WARNING_HEADER, value);
        }
    }
    response
}

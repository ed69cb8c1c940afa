//! API errors. Every failure a request can cause becomes a status, a machine-readable kind,
//! a one-line message naming the problem and a hint saying what to do; bad input is always
//! 4xx, never 5xx.

use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;
use isogami_store::StoreError;
use serde::Serialize;

/// An error answer: `{"error": message, "kind": kind, "hint": hint}` with `status`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ApiError {
    /// HTTP status.
    pub status: StatusCode,
    /// Machine-readable kind, e.g. `bad_parameter`, `not_found`, `rigid`.
    pub kind: &'static str,
    /// One line naming the problem.
    pub message: String,
    /// What the user can do about it.
    pub hint: String,
}

#[derive(Serialize)]
struct Body<'a> {
    error: &'a str,
    kind: &'a str,
    hint: &'a str,
}

impl ApiError {
    /// An error with every field given.
    pub fn new(
        status: StatusCode,
        kind: &'static str,
        message: impl Into<String>,
        hint: impl Into<String>,
    ) -> ApiError {
        let one_line = |s: String| bounded(&s.replace(['\n', '\r'], " "));
        ApiError {
            status,
            kind,
            message: one_line(message.into()),
            hint: one_line(hint.into()),
        }
    }

    /// The status of a posted body that could not be read (missing, oversized), `bad_body`.
    pub fn bad_body(e: &axum::extract::rejection::BytesRejection) -> ApiError {
        ApiError::new(
            e.status(),
            "bad_body",
            format!("request body: {}", e.body_text()),
            "send at most 64 KiB of JSON",
        )
    }

    /// 400 `bad_parameter`: a request value that cannot be used, with the message.
    pub fn bad_parameter(message: impl Into<String>) -> ApiError {
        ApiError::new(
            StatusCode::BAD_REQUEST,
            "bad_parameter",
            message,
            "see the API section of the README for the accepted values",
        )
    }

    /// 404: no such API endpoint.
    pub fn no_endpoint() -> ApiError {
        ApiError::new(
            StatusCode::NOT_FOUND,
            "not_found",
            "no such API endpoint",
            "see the API section of the README",
        )
    }

    /// 405: an endpoint that does not take this method.
    pub fn method_not_allowed() -> ApiError {
        ApiError::new(
            StatusCode::METHOD_NOT_ALLOWED,
            "method_not_allowed",
            "this endpoint does not take this HTTP method",
            "POST to /api/deploy, /api/designs, /api/inverse and /api/graded; DELETE /api/inverse/{id} and /api/graded/{id}; GET everything else",
        )
    }

    /// 404: no such design in the database.
    pub fn not_found(spec: &str) -> ApiError {
        ApiError::new(
            StatusCode::NOT_FOUND,
            "not_found",
            format!("no design {spec:?} in the database"),
            "POST it to /api/deploy to simulate it live",
        )
    }

    /// 500 for a failure that is not the request's fault (a damaged database).
    pub fn internal(message: impl Into<String>) -> ApiError {
        ApiError::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "internal",
            message,
            "check the server's database with `isogami db stats --db FILE` (it verifies every row's checksum)",
        )
    }
}

/// Longest message or hint, in characters: user text echoed in a message (a spec, a number
/// written out in full) never makes an answer long.
pub const MAX_MESSAGE: usize = 300;

/// `s`, cut to [`MAX_MESSAGE`] characters with an ellipsis.
fn bounded(s: &str) -> String {
    if s.chars().count() <= MAX_MESSAGE {
        return s.to_string();
    }
    let mut out: String = s.chars().take(MAX_MESSAGE - 1).collect();
    out.push('…');
    out
}

impl From<StoreError> for ApiError {
    fn from(e: StoreError) -> ApiError {
        match e {
            StoreError::InvalidQuery(q) => ApiError::bad_parameter(q.to_string()),
            StoreError::DuplicateSpec(spec) => ApiError::new(
                StatusCode::CONFLICT,
                "exists",
                format!("{spec} is already in the database"),
                "open it from the catalogue",
            ),
            StoreError::Locked | StoreError::Busy => ApiError::new(
                StatusCode::CONFLICT,
                "busy",
                "another process is writing this database",
                "try again when the exploration has finished",
            ),
            e => ApiError::internal(e.to_string()),
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = Body {
            error: &self.message,
            kind: self.kind,
            hint: &self.hint,
        };
        (self.status, Json(body)).into_response()
    }
}

/// Result of a handler.
pub type ApiResult<T> = Result<T, ApiError>;

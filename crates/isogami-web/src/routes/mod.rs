//! The HTTP surface: the JSON API under `/api/` and the embedded front end everywhere else.
//!
//! | method, path | answer |
//! |---|---|
//! | `GET /api/stats` | database summary, tool version and settings |
//! | `GET /api/families` | the 81 families with parameter counts and defaults |
//! | `GET /api/dictionary` | the meaning of every catalogue field |
//! | `GET /api/measures` | the measures ranges, sorts and scatter axes take, with their dictionary entries |
//! | `GET /api/designs?filters` | a filtered, sorted page of catalogue rows |
//! | `GET /api/facets?filters` | counts per value of every facet |
//! | `GET /api/scatter?x=&y=&filters` | two measures of every matching design |
//! | `GET /api/design?spec=[&fallback=live&kerf=]` | the design view of a stored design (`fallback=live`: any design, deployed live when not stored) |
//! | `GET /api/thumbnail?spec=` | its thumbnail (SVG) |
//! | `GET /api/motions?filters` | the matching designs grouped by distinct motion (mechanisms view) |
//! | `GET /api/motion?spec=` | the same motion in other cells and families (its class) |
//! | `GET /api/gif?spec=[&kerf=]` | its deployment as an animated GIF |
//! | `GET /api/export/formats` | export formats, their settings fields, defaults and limits |
//! | `GET /api/export?design=&format=&…` | a design's export as a download (the completed sheet; `raw=true` the rectangle) |
//! | `GET /api/sheet?design=&region=&…` | a finite region: DOF, floppy tiles, completion, finite deployment |
//! | `POST /api/deploy` | a live deployment of a posted design |
//! | `POST /api/designs` | save a posted design as a user design |
//! | `GET /api/shape?design=` | generic or special over the shape space; constraints, pinned |
//! | `POST /api/shape/follow` | move one shape parameter, the others following the constraints |
//! | `GET /api/shape/ranges?design=[&kerf=]` | each shape parameter's valid range, the others fixed |
//! | `GET /api/inverse` | inverse design's defaults, caps, saving allowed, running job |
//! | `POST /api/inverse` | start an inverse-design job (202 `{id}`; 409 while one runs) |
//! | `GET /api/inverse/{id}` | its state, the request that started it, progress, leaders, result |
//! | `DELETE /api/inverse/{id}` | stop it |
//! | `POST /api/inverse/{id}/save` | save its refined designs as user designs |
//! | `GET /api/graded` | graded sheets' defaults, caps, running jobs |
//! | `GET /api/graded/outline?outline=` | a target outline read by the library, or its one-line error |
//! | `POST /api/graded/svg?name=` | an SVG file's outline read by the library, or its one-line error |
//! | `POST /api/graded` | start a graded-sheet job (202 `{id}`; 409 over the running cap) |
//! | `GET /api/graded/{id}` | its state, the request that started it, progress, snapshot of the sheet as it stands, result |
//! | `DELETE /api/graded/{id}` | stop it |
//! | `GET /api/graded/{id}/sheet` | its graded sheet as `isogami graded --out` writes it |
//! | `GET /api/graded/{id}/export?format=&…` | its graded sheet exported (laser, print, …) as `isogami export --sheet` |
//! | `GET /data/site.json` | `{"mode": "server"}`: what a page asks first (a static site's file says `static`) |

mod assets;
pub(crate) mod catalogue;
mod design;
mod export;
mod graded;
mod inverse;
mod motions;
mod shape;
mod sheet;

use crate::error::ApiError;
use crate::state::AppState;
use axum::body::Body;
use axum::extract::{DefaultBodyLimit, Request, State};
use axum::http::{header, StatusCode};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use std::time::Duration;

/// The whole application over `state`.
pub fn router(state: AppState) -> Router {
    let limit = state.settings().max_body;
    let bodies = BodyLimits {
        max: limit,
        timeout: state.settings().body_timeout,
    };
    let api = Router::new()
        .route("/stats", get(catalogue::stats))
        .route("/families", get(catalogue::families))
        .route("/dictionary", get(catalogue::dictionary))
        .route("/measures", get(catalogue::measures))
        .route("/designs", get(catalogue::designs).post(design::save))
        .route("/facets", get(catalogue::facets))
        .route("/scatter", get(catalogue::scatter))
        .route("/design", get(design::stored))
        .route("/thumbnail", get(design::thumbnail))
        .route("/motion", get(design::motion))
        .route("/motions", get(motions::motions))
        .route("/gif", get(design::gif))
        .route("/deploy", post(design::deploy_live))
        .route("/shape", get(shape::mobility))
        .route("/shape/follow", post(shape::follow_shape))
        .route("/shape/ranges", get(shape::ranges))
        .route("/sheet", get(sheet::sheet))
        .route("/export", get(export::export))
        .route("/export/formats", get(export::formats))
        .route("/inverse", get(inverse::settings).post(inverse::start))
        .route("/inverse/{id}", get(inverse::status).delete(inverse::stop))
        .route("/inverse/{id}/save", post(inverse::save))
        .route("/graded", get(graded::settings).post(graded::start))
        .route("/graded/outline", get(graded::outline))
        .route("/graded/svg", post(graded::svg))
        .route("/graded/{id}", get(graded::status).delete(graded::stop))
        .route("/graded/{id}/sheet", get(graded::sheet))
        .route("/graded/{id}/export", get(graded::export))
        .fallback(|| async { ApiError::no_endpoint() })
        .method_not_allowed_fallback(|| async { ApiError::method_not_allowed() });
    Router::new()
        .nest("/api", api)
        .route("/data/site.json", get(assets::server_mode))
        .fallback(assets::asset)
        .layer(DefaultBodyLimit::max(limit))
        .layer(middleware::from_fn_with_state(bodies, bounded_body))
        .with_state(state)
}

/// What a request body may be: its size and how long it may take to arrive.
#[derive(Debug, Clone, Copy)]
struct BodyLimits {
    max: usize,
    timeout: Duration,
}

/// Reads every request's body before the handler runs: a declared `Content-Length` over the
/// limit is 413 at once (nothing is read), a body that grows past it 413, one that has not
/// arrived within the body timeout 408 (the connection is then closed: a slow client holds
/// nothing for long).
async fn bounded_body(State(limits): State<BodyLimits>, request: Request, next: Next) -> Response {
    let too_large = || {
        ApiError::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            "bad_body",
            format!("request body longer than {} bytes", limits.max),
            "send at most 64 KiB of JSON",
        )
    };
    let declared = request
        .headers()
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.trim().parse::<u64>().ok());
    if declared.is_some_and(|n| n > limits.max as u64) {
        return close(too_large().into_response());
    }
    let (parts, body) = request.into_parts();
    match tokio::time::timeout(limits.timeout, axum::body::to_bytes(body, limits.max)).await {
        Ok(Ok(bytes)) => {
            next.run(Request::from_parts(parts, Body::from(bytes)))
                .await
        }
        Ok(Err(e)) if e.to_string().contains("length limit") => close(too_large().into_response()),
        Ok(Err(e)) => close(
            ApiError::new(
                StatusCode::BAD_REQUEST,
                "bad_body",
                format!("request body: {e}"),
                "send the whole body as declared",
            )
            .into_response(),
        ),
        Err(_) => close(
            ApiError::new(
                StatusCode::REQUEST_TIMEOUT,
                "slow_body",
                format!(
                    "request body not received within {:.1} s",
                    limits.timeout.as_secs_f64()
                ),
                "send the body at once",
            )
            .into_response(),
        ),
    }
}

/// `response` with `Connection: close`: the rest of the request's body is not read.
fn close(mut response: Response) -> Response {
    response.headers_mut().insert(
        header::CONNECTION,
        header::HeaderValue::from_static("close"),
    );
    response
}

//! Graded-sheet endpoints (see [`crate::graded`]): the page's settings, an outline checked by
//! the library, starting a job, polling it, stopping it, and downloading its graded sheet.

use crate::error::{ApiError, ApiResult};
use crate::filters::{get as param, pairs, truncate};
use crate::graded::body::outline_of;
use crate::graded::{outline_view, GradedBody, GradedJob, GradedView};
use crate::inverse::JobState;
use crate::state::AppState;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{Path, RawQuery, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde_json::{json, Value};
use std::sync::Arc;

/// `GET /api/graded`: the request's defaults, this server's caps and the running jobs' ids.
pub async fn settings(State(state): State<AppState>) -> Json<Value> {
    let mut v = state.settings().graded.describe();
    v["running"] = json!(state.graded_jobs().running());
    Json(v)
}

/// `GET /api/graded/outline?outline=TEXT`: the outline read by the library (`disc`,
/// `ellipse:A,B`, `polygon:x,y;…`) and its boundary at scale 1, or 400 `bad_target` with the
/// library's one-line message (a polygon not seen whole from its centroid, say).
pub async fn outline(RawQuery(raw): RawQuery) -> ApiResult<Json<Value>> {
    let pairs = pairs(raw.as_deref());
    if let Some((k, _)) = pairs.iter().find(|(k, _)| k != "outline") {
        return Err(ApiError::bad_parameter(format!(
            "unknown parameter {:?}",
            truncate(k)
        )));
    }
    let text = param(&pairs, "outline")
        .ok_or_else(|| ApiError::bad_parameter("missing parameter outline"))?;
    let outline = outline_of(text)?;
    Ok(Json(outline_view(text, &outline)))
}

/// `POST /api/graded`: checks the request (400 with a one-line message), refuses a job over
/// the running cap (409), starts the run on the blocking pool and answers 202 `{id}`.
pub async fn start(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> ApiResult<(StatusCode, Json<Value>)> {
    let body = GradedBody::from_request(body)?;
    let limits = state.settings().graded;
    let request = body.request(&limits)?;
    let job = state
        .graded_jobs()
        .start(&request, body.outline_text(), &limits)?;
    let id = job.id();
    tokio::task::spawn_blocking(move || job.run(&request));
    Ok((
        StatusCode::ACCEPTED,
        Json(json!({ "id": id, "state": JobState::Running })),
    ))
}

fn job(state: &AppState, id: &str) -> ApiResult<Arc<GradedJob>> {
    state.graded_jobs().get(id, &state.settings().graded)
}

/// `GET /api/graded/{id}`: state, progress, the latest snapshot, the result when done, the
/// error when failed or stopped.
pub async fn status(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<Json<GradedView>> {
    Ok(Json(job(&state, &id)?.view()))
}

/// `DELETE /api/graded/{id}`: stops a running job (it ends as `stopped` at the optimiser's
/// next step); an ended job is left as it is. Answers the job's view.
pub async fn stop(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<Json<GradedView>> {
    let job = job(&state, &id)?;
    job.request_stop();
    Ok(Json(job.view()))
}

/// `GET /api/graded/{id}/sheet`: a finished job's graded sheet, report and path check as
/// `isogami graded --out FILE` writes them (pretty JSON and a newline), as an attachment
/// `graded-<R>x<C>.json`; 409 before the job is done.
pub async fn sheet(State(state): State<AppState>, Path(id): Path<String>) -> ApiResult<Response> {
    let job = job(&state, &id)?;
    let run = job.run_result().ok_or_else(|| {
        ApiError::new(
            StatusCode::CONFLICT,
            "not_done",
            format!("graded-sheet job {} has no sheet to download", job.id()),
            "download once the job's state is done",
        )
    })?;
    let text = serde_json::to_string_pretty(&*run)
        .map_err(|e| ApiError::internal(format!("graded sheet JSON: {e}")))?;
    let echo = job.echo();
    Ok((
        [
            (header::CONTENT_TYPE, "application/json".to_string()),
            (
                header::CONTENT_DISPOSITION,
                format!(
                    "attachment; filename=\"graded-{}x{}.json\"",
                    echo.rows, echo.cols
                ),
            ),
            (header::CACHE_CONTROL, "no-store".to_string()),
        ],
        text + "\n",
    )
        .into_response())
}

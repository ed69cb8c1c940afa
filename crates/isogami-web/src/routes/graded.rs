//! Graded-sheet endpoints (see [`crate::graded`]): the page's settings, an outline (or an SVG
//! file's) checked by the library, starting a job, polling it, stopping it, and downloading its
//! graded sheet as JSON or exported (laser, print and every other format).

use crate::error::{ApiError, ApiResult};
use crate::export::export_graded_bounded;
use crate::export::heavy_permit;
use crate::export::query::parse_graded_export;
use crate::filters::{get as param, pairs, truncate};
use crate::graded::body::{outline_of, refusal, svg_outline};
use crate::graded::job::Echo;
use crate::graded::{outline_view, GradedBody, GradedJob, GradedView};
use crate::jobs::accepted;
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

/// `POST /api/graded/svg?name=FILE`: the body is an SVG file's text; answers its one closed
/// shape read by the library (`graded::outline_from_svg`) as the outline's polygon text and
/// its boundary at scale 1 (what `--target @FILE.svg` grades towards), or 400 `bad_target`
/// with the library's one-line message naming the file.
pub async fn svg(
    RawQuery(raw): RawQuery,
    body: Result<Bytes, BytesRejection>,
) -> ApiResult<Json<Value>> {
    let pairs = pairs(raw.as_deref());
    if let Some((k, _)) = pairs.iter().find(|(k, _)| k != "name") {
        return Err(ApiError::bad_parameter(format!(
            "unknown parameter {:?}",
            truncate(k)
        )));
    }
    let name = param(&pairs, "name").unwrap_or("outline.svg");
    let bytes = body.map_err(|e| ApiError::bad_body(&e))?;
    let text = std::str::from_utf8(&bytes).map_err(|_| {
        ApiError::new(
            StatusCode::BAD_REQUEST,
            "bad_target",
            format!("{}: not UTF-8 text (an SVG file is XML)", truncate(name)),
            "upload an SVG file with one closed shape",
        )
    })?;
    // Off the async workers: a bounded but not free parse (up to 4,096 vertices checked for
    // crossings) must not hold the cheap requests behind it.
    let (text, owned_name) = (text.to_string(), name.to_string());
    let outline = off_runtime(move || svg_outline(&text, &owned_name)).await?;
    let mut view = outline_view(&format!("@{name}"), &outline);
    view["name"] = json!(name);
    Ok(Json(view))
}

/// `POST /api/graded`: checks the request (400 with a one-line message), then asks the
/// library's setup whether it refuses it (400 with its message: a target the sheet cannot
/// reach, a tolerance out of range; see `body::refusal`), refuses a job over the running cap
/// (409), starts the run on the blocking pool and answers 202 `{id}`.
pub async fn start(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> ApiResult<(StatusCode, Json<Value>)> {
    let body = GradedBody::from_request(body)?;
    let limits = state.settings().graded;
    let outline_text = body.outline_text();
    // An SVG target is read off the async workers (see `svg`).
    let request = off_runtime(move || body.request(&limits)).await?;
    // The setup deploys the design's finite sheet: one of the heavy permits finite sheets
    // take, so that a burst of posts cannot run many at once.
    let (permit, _) = heavy_permit(state.heavy().clone(), state.settings().sim_timeout).await?;
    let checked = request.clone();
    off_runtime(move || {
        let _permit = permit;
        refusal(&checked)
    })
    .await?;
    let echo = Echo::of(&request, &outline_text);
    let job = state.graded_jobs().start(echo, &limits)?;
    let id = job.id();
    tokio::task::spawn_blocking(move || job.run(&request));
    Ok(accepted(id))
}

/// Runs `f` on the blocking pool.
async fn off_runtime<T: Send + 'static>(
    f: impl FnOnce() -> ApiResult<T> + Send + 'static,
) -> ApiResult<T> {
    tokio::task::spawn_blocking(f)
        .await
        .map_err(|e| ApiError::internal(format!("reading the request failed: {e}")))?
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

/// `GET /api/graded/{id}/export?format=&edge_mm=|width_mm=&t=&frames=&…`: a finished job's
/// graded sheet written by the library's `export::export_graded` in `format` (keys named as
/// `isogami export --sheet`'s flags, checked as `GET /api/export` checks them; `t` is the
/// opening, 0 closed — the default, what a laser cuts —, 1 or `open` the optimised state),
/// as an attachment `graded-<R>x<C>.<ext>` (a folder format zipped), bounded as a design's
/// export is; 409 before the job is done.
pub async fn export(
    State(state): State<AppState>,
    Path(id): Path<String>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Response> {
    let query = parse_graded_export(&pairs(raw.as_deref()))?;
    let job = job(&state, &id)?;
    let run = job.run_result().ok_or_else(|| {
        ApiError::new(
            StatusCode::CONFLICT,
            "not_done",
            format!("graded-sheet job {} has no sheet to export", job.id()),
            "export once the job's state is done",
        )
    })?;
    let echo = job.echo();
    let stem = format!("graded-{}x{}", echo.rows, echo.cols);
    let download = export_graded_bounded(
        run,
        query,
        &stem,
        state.settings().sim_timeout,
        state.heavy().clone(),
    )
    .await?;
    Ok(super::export::download_response(download))
}

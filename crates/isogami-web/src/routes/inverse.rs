//! Inverse-design endpoints (see [`crate::inverse`]): the panel's settings, starting a job,
//! polling it, stopping it, saving its refined designs.

use crate::error::{ApiError, ApiResult};
use crate::inverse::view::Echo;
use crate::inverse::{InverseBody, Job, JobView};
use crate::jobs::accepted;
use crate::state::AppState;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{Path, State};
use axum::http::StatusCode;
use axum::Json;
use isogami_store::{Check, StoreWriter};
use serde_json::{json, Value};
use std::sync::Arc;

/// `GET /api/inverse`: the request's defaults, this server's caps, whether saving is allowed,
/// the database's file name and the running job's id (null when none runs).
pub async fn settings(State(state): State<AppState>) -> Json<Value> {
    let name = state
        .db_path()
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut v = state
        .settings()
        .inverse
        .describe(state.settings().allow_save, &name);
    v["running"] = json!(state.jobs().running().first());
    Json(v)
}

/// `POST /api/inverse`: checks the request (400 with the library's message), refuses a second
/// job while one runs (409), starts the run on the blocking pool and answers 202 `{id}`.
pub async fn start(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> ApiResult<(StatusCode, Json<Value>)> {
    let body = InverseBody::from_request(body)?;
    let limits = state.settings().inverse;
    let request = body.request(&limits)?;
    let job = state.jobs().start(Echo::of(&request, &body), &limits)?;
    let id = job.id();
    let runner = state.clone();
    tokio::task::spawn_blocking(move || job.run(&runner, &request));
    Ok(accepted(id))
}

fn job(state: &AppState, id: &str) -> ApiResult<Arc<Job>> {
    state.jobs().get(id, &state.settings().inverse)
}

/// `GET /api/inverse/{id}`: state, progress, result when done, error when failed or stopped.
pub async fn status(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<Json<JobView>> {
    Ok(Json(job(&state, &id)?.view()))
}

/// `DELETE /api/inverse/{id}`: stops a running job (it ends as `stopped` after the
/// evaluations in flight); an ended job is left as it is. Answers the job's view.
pub async fn stop(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<Json<JobView>> {
    let job = job(&state, &id)?;
    job.request_stop();
    Ok(Json(job.view()))
}

/// `POST /api/inverse/{id}/save`: saves a finished job's refined designs as user designs
/// (403 on a read-only server, 409 before the job is done); answers 201 `{saved}` as the
/// CLI's `--save` reports them.
pub async fn save(
    State(state): State<AppState>,
    Path(id): Path<String>,
) -> ApiResult<(StatusCode, Json<Value>)> {
    if !state.settings().allow_save {
        return Err(ApiError::new(
            StatusCode::FORBIDDEN,
            "read_only",
            "this server does not save designs",
            "restart `isogami serve` without --read-only, or run `isogami inverse --save`",
        ));
    }
    let job = job(&state, &id)?;
    let result = job.result().ok_or_else(|| {
        ApiError::new(
            StatusCode::CONFLICT,
            "not_done",
            format!("inverse-design job {} has no result to save", job.id()),
            "save once the job's state is done",
        )
    })?;
    let saver = state.clone();
    let saved = tokio::task::spawn_blocking(move || {
        saver.with_save_lock(|| {
            let mut writer = StoreWriter::open(saver.db_path(), None, Check::Quick)?;
            Ok(writer.save_inverse_results(&result)?)
        })
    })
    .await
    .map_err(|e| ApiError::internal(format!("save task failed: {e}")))??;
    job.set_saved(&saved);
    Ok((StatusCode::CREATED, Json(json!({ "saved": saved }))))
}

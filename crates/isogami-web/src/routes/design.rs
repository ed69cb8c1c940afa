//! Design endpoints: a stored design's view, thumbnail and GIF; live deployment; saving.

use crate::error::{ApiError, ApiResult};
use crate::filters::{get as param, pairs, truncate};
use crate::live::{deploy_bounded, explain, run_bounded, timed_out, LiveRequest};
use crate::state::AppState;
use crate::thumbnail::thumbnail_svg;
use crate::view::DesignView;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{RawQuery, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use isogami::api::{linkages, resolve_design, DeployRequest, Design};
use isogami::catalog::{assess, Assessment, CatalogSettings};
use isogami::render::{deployment_frame_svgs, gif_from_svgs, Fonts};
use isogami_store::{Check, DesignRecord, Origin, StoreWriter};
use serde_json::json;
use std::sync::OnceLock;

/// The `spec` parameter (and nothing else but `allowed`).
fn spec_param(raw: Option<&str>, allowed: &[&str]) -> ApiResult<String> {
    let pairs = pairs(raw);
    for (k, _) in &pairs {
        if k != "spec" && !allowed.contains(&k.as_str()) {
            return Err(ApiError::bad_parameter(format!(
                "unknown parameter {:?}",
                truncate(k)
            )));
        }
    }
    let spec =
        param(&pairs, "spec").ok_or_else(|| ApiError::bad_parameter("missing parameter spec"))?;
    if spec.len() > 4096 {
        return Err(ApiError::bad_parameter("spec longer than 4 KiB"));
    }
    Ok(spec.to_string())
}

/// The stored design `spec`, as a view.
async fn stored_view(state: &AppState, spec: String) -> ApiResult<DesignView> {
    let stored = state
        .read(move |s| {
            // Stored specs are canonical: read the text as a design first so that any
            // spelling of a stored design finds it.
            let key = resolve_design(&spec).map_or(spec.clone(), |d| d.to_string());
            s.design(&key)?.ok_or_else(|| ApiError::not_found(&spec))
        })
        .await?;
    DesignView::stored(stored)
}

/// A finite `kerf` parameter, if given.
fn kerf_param(raw: Option<&str>) -> ApiResult<Option<f64>> {
    match param(&pairs(raw), "kerf") {
        Some(text) => Ok(Some(
            text.parse::<f64>()
                .ok()
                .filter(|k| k.is_finite())
                .ok_or_else(|| ApiError::bad_parameter("kerf must be a finite number"))?,
        )),
        None => Ok(None),
    }
}

/// `GET /api/design?spec=[&fallback=live[&kerf=]]`: the stored design's view, or 404. With
/// `fallback=live`, a design that is not stored — or asked at a `kerf` other than its stored
/// one — is deployed live instead, as `POST /api/deploy` does (its view has no origin): what
/// a page opening any design asks, with no failed request for one that is not stored.
pub async fn stored(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<DesignView>> {
    let spec = spec_param(raw.as_deref(), &["fallback", "kerf"])?;
    let live = match param(&pairs(raw.as_deref()), "fallback") {
        None => false,
        Some("live") => true,
        Some(other) => {
            return Err(ApiError::bad_parameter(format!(
                "fallback {:?}: the one fallback is live",
                truncate(other)
            )))
        }
    };
    let kerf = kerf_param(raw.as_deref())?;
    if kerf.is_some() && !live {
        return Err(ApiError::bad_parameter(
            "kerf goes with fallback=live (a stored design is at its stored kerf)",
        ));
    }
    match stored_view(&state, spec.clone()).await {
        Ok(view) if kerf.is_none_or(|k| (k - view.report.kerf).abs() <= 1e-12) => Ok(Json(view)),
        Ok(_) => live_view(&state, spec, kerf).await,
        Err(e) if live && e.kind == "not_found" => live_view(&state, spec, kerf).await,
        Err(e) => Err(e),
    }
}

/// The view of a live deployment of `spec` at `kerf`, as `POST /api/deploy` answers it.
async fn live_view(
    state: &AppState,
    spec: String,
    kerf: Option<f64>,
) -> ApiResult<Json<DesignView>> {
    let live = LiveRequest {
        design: spec,
        kerf,
        frames: None,
    };
    let (design, request) = live.resolve()?;
    let run = deploy_bounded(design.clone(), request, state.settings().sim_timeout).await?;
    Ok(Json(DesignView::live(&design, run)?))
}

/// `GET /api/motion?spec=`: the class of topologies (in other cells and families) that move
/// like the stored design's topology, as `{"topology": spec | null, "class": MotionClass |
/// null}`; nulls for a design that is not stored, a class null for a database whose classes
/// are not computed.
pub async fn motion(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<serde_json::Value>> {
    let spec = spec_param(raw.as_deref(), &[])?;
    let (topology, class) = state
        .read(move |s| {
            let key = resolve_design(&spec).map_or(spec.clone(), |d| d.to_string());
            let topology = s.design(&key)?.map(|d| d.summary.topology);
            Ok((topology, s.motion_class_of(&key)?))
        })
        .await?;
    Ok(Json(json!({ "topology": topology, "class": class })))
}

/// `GET /api/thumbnail?spec=`.
pub async fn thumbnail(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Response> {
    let spec = spec_param(raw.as_deref(), &[])?;
    let view = stored_view(&state, spec).await?;
    Ok((
        [
            (header::CONTENT_TYPE, "image/svg+xml"),
            (header::CACHE_CONTROL, "max-age=300"),
        ],
        thumbnail_svg(&view),
    )
        .into_response())
}

/// Frames and width of a GIF download.
const GIF_FRAMES: usize = 40;
const GIF_WIDTH: u32 = 360;

/// `GET /api/gif?spec=[&kerf=]`: the deployment of a stored design (at its stored kerf) or
/// of any design (at `kerf` or the default), as an animated GIF.
pub async fn gif(State(state): State<AppState>, RawQuery(raw): RawQuery) -> ApiResult<Response> {
    let spec = spec_param(raw.as_deref(), &["kerf"])?;
    let kerf = match kerf_param(raw.as_deref())? {
        Some(k) => Some(k),
        None => match stored_view(&state, spec.clone()).await {
            Ok(view) => Some(view.report.kerf),
            Err(e) if e.kind == "not_found" => None,
            Err(e) => return Err(e),
        },
    };
    let live = LiveRequest {
        design: spec,
        kerf,
        frames: Some(GIF_FRAMES),
    };
    let (design, request) = live.resolve()?;
    let run = deploy_bounded(design, request, state.settings().sim_timeout).await?;
    let bytes = tokio::task::spawn_blocking(move || {
        static FONTS: OnceLock<Fonts> = OnceLock::new();
        let fonts = FONTS.get_or_init(Fonts::system);
        let svgs = deployment_frame_svgs(
            &run.mechanism,
            &run.contact,
            &run.frames,
            f64::from(GIF_WIDTH),
        );
        gif_from_svgs(&svgs, GIF_WIDTH, 8, fonts)
    })
    .await
    .map_err(|e| ApiError::internal(format!("GIF task failed: {e}")))?
    .map_err(|e| ApiError::internal(format!("GIF: {e}")))?;
    Ok(([(header::CONTENT_TYPE, "image/gif")], bytes).into_response())
}

/// The JSON body of a POST, with a 4xx JSON error for a missing, oversized or malformed one.
fn body_json(body: Result<Bytes, BytesRejection>) -> ApiResult<LiveRequest> {
    let bytes = body.map_err(|e| ApiError::bad_body(&e))?;
    serde_json::from_slice(&bytes).map_err(|e| {
        ApiError::bad_parameter(format!(
            "request body is not {{\"design\": …, \"kerf\": …, \"frames\": …}}: {e}"
        ))
    })
}

/// `POST /api/deploy`: a live deployment, bounded in time, cancelled if the client leaves.
pub async fn deploy_live(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> ApiResult<Json<DesignView>> {
    let live = body_json(body)?;
    let (design, request) = live.resolve()?;
    let run = deploy_bounded(design.clone(), request, state.settings().sim_timeout).await?;
    Ok(Json(DesignView::live(&design, run)?))
}

/// `POST /api/designs`: deploys a design as `POST /api/deploy` does and saves it as a user
/// design (`origin = user`).
pub async fn save(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> ApiResult<(StatusCode, Json<serde_json::Value>)> {
    if !state.settings().allow_save {
        return Err(ApiError::new(
            StatusCode::FORBIDDEN,
            "read_only",
            "this server does not save designs",
            "restart `isogami serve` without --read-only",
        ));
    }
    let live = body_json(body)?;
    let (design, request) = live.resolve()?;
    let timeout = state.settings().sim_timeout;
    // The live deployment first (its failures as for `POST /api/deploy`: rigid, timeout, …),
    // then the admission rule on what deploys.
    let run = deploy_bounded(design.clone(), request, timeout).await?;
    admit(&state, &design, &request, timeout).await?;
    let analysis = linkages(&design).ok();
    let spec = design.to_string();
    let record =
        DesignRecord::from_parts(&design, &spec, Origin::User, &run.report, analysis.as_ref())
            .map_err(|e| explain_store(&e))?;
    let saver = state.clone();
    tokio::task::spawn_blocking(move || {
        saver.with_save_lock(|| {
            let mut writer = StoreWriter::open(saver.db_path(), None, Check::Quick)?;
            writer.save_user_design(&record)?;
            Ok(())
        })
    })
    .await
    .map_err(|e| ApiError::internal(format!("save task failed: {e}")))??;
    Ok((
        StatusCode::CREATED,
        Json(json!({ "spec": spec, "saved": true })),
    ))
}

/// The exploration's admission rule (`isogami::catalog::assess`) for a design about to be
/// saved, under the settings the database was explored with (the library's defaults for a
/// database that records none), the posted kerf in place of the catalogue's: a design the
/// exploration would not keep (not one DOF when closed, locked at once, below the expansion
/// threshold) is 422 `not_admitted` with the reason.
async fn admit(
    state: &AppState,
    design: &Design,
    request: &DeployRequest,
    timeout: std::time::Duration,
) -> ApiResult<()> {
    let recorded = state.read(|s| Ok(s.settings()?)).await?;
    let mut settings = recorded
        .as_deref()
        .and_then(CatalogSettings::from_fingerprint)
        .unwrap_or_default();
    settings.deploy.contact = request.settings.contact;
    let design = design.clone();
    let verdict = run_bounded(timeout, move |deadline| {
        assess(&design, &settings, &mut |_| deadline.keep_going())
    })
    .await?
    .map_err(|e| {
        if e.is_cancelled() {
            timed_out(timeout)
        } else {
            explain(&e)
        }
    })?;
    match verdict {
        Assessment::Admitted(_) => Ok(()),
        Assessment::Rejected(why) => Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "not_admitted",
            format!("not saved: the exploration would not keep this design ({why})"),
            "only working designs are saved: one degree of freedom when closed, free to open, \
             expanding past the catalogue's threshold; POST it to /api/deploy to look at it",
        )),
    }
}

fn explain_store(e: &isogami_store::StoreError) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "unsaveable",
        e.to_string(),
        "this deployment cannot be stored; try nearby parameters",
    )
}

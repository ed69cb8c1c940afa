//! Shape-aware mobility for the design page's shape sliders (issue 13 item 6): whether a
//! design keeps one degree of freedom at every nearby shape (generic) or only on a
//! sub-manifold (special), and moving one parameter while the others follow that sub-manifold,
//! so a slider moves along the mechanism's family instead of breaking it; and each
//! parameter's valid range (the others fixed), which the sliders are limited to, so that no
//! slider position is refused as ill-shaped. All call the library's `isogami::shape_space`
//! and nothing else, on the blocking pool.

use crate::error::{ApiError, ApiResult};
use crate::export::groups::check_design_text;
use crate::filters::{get as param, pairs, truncate};
use crate::live::{explain, run_bounded};
use crate::state::AppState;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{RawQuery, State};
use axum::http::StatusCode;
use axum::Json;
use isogami::api::{resolve_design, Design};
use isogami::shape_space::{
    classify, follow, param_ranges, ParamRange, ShapeError, ShapeMobility, ShapeSettings,
};
use serde::{Deserialize, Serialize};

/// The design of a request's text, or a 400/422 in the live deployment's terms.
fn design_of(text: &str) -> ApiResult<Design> {
    resolve_design(check_design_text(text)?).map_err(|e| explain(&e))
}

/// A query's pairs, refusing keys outside `allowed`, and the design its `design` key names.
fn design_query(raw: Option<&str>, allowed: &[&str]) -> ApiResult<(Vec<(String, String)>, Design)> {
    let pairs = pairs(raw);
    if let Some((k, _)) = pairs.iter().find(|(k, _)| !allowed.contains(&k.as_str())) {
        return Err(ApiError::bad_parameter(format!(
            "unknown parameter {:?}",
            truncate(k)
        )));
    }
    let text = param(&pairs, "design")
        .ok_or_else(|| ApiError::bad_parameter("missing parameter design"))?;
    let design = design_of(text)?;
    Ok((pairs, design))
}

/// A shape-space error in the words of someone moving a slider.
fn explain_shape(e: &ShapeError) -> ApiError {
    let unprocessable = |kind, hint: &str| {
        ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, kind, e.to_string(), hint)
    };
    match e {
        ShapeError::NoSuchParameter { .. } | ShapeError::NotFinite { .. } => {
            ApiError::bad_parameter(e.to_string())
        }
        ShapeError::NotOneDof { .. } => unprocessable(
            "not_one_dof",
            "shape following needs a design with one degree of freedom at its own shape",
        ),
        ShapeError::Pinned { .. } => unprocessable(
            "pinned",
            "this parameter cannot change while the sheet keeps moving; move another one",
        ),
        ShapeError::LeavesShapes { .. } => unprocessable(
            "ill_shaped",
            "the mechanism's family of shapes ends before that value; move the slider back",
        ),
        ShapeError::Lost { .. } => unprocessable(
            "lost",
            "the shapes that keep one degree of freedom could not be followed that far; \
             move in smaller steps",
        ),
        _ => unprocessable(
            "shape_failed",
            "the shape analysis failed for this design; try nearby parameters",
        ),
    }
}

/// `GET /api/shape?design=`: the design's shape class, constraints and pinned parameters
/// (the library's `ShapeMobility`).
pub async fn mobility(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<ShapeMobility>> {
    let (_, design) = design_query(raw.as_deref(), &["design"])?;
    // A few mobility analyses (milliseconds): bounded by the library's sample count.
    let timeout = state.settings().sim_timeout;
    let out = run_bounded(timeout, move |_| {
        classify(&design, &ShapeSettings::default())
    })
    .await?;
    Ok(Json(out.map_err(|e| explain_shape(&e))?))
}

/// The body of `POST /api/shape/follow`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FollowRequest {
    /// A design name, spec string or design JSON.
    pub design: String,
    /// The parameter to move (0-based).
    pub index: usize,
    /// Its new value.
    pub value: f64,
}

/// The answer of `POST /api/shape/follow`.
#[derive(Debug, Serialize)]
pub struct FollowAnswer {
    /// Spec of the moved design.
    pub spec: String,
    /// Every shape parameter of the moved design.
    pub params: Vec<f64>,
    /// The starting design's class (`generic`, `special`, `fixed_shape`).
    pub class: isogami::shape_space::ShapeClass,
    /// Continuation steps taken (0 for a generic design, which just takes the value).
    pub steps: usize,
    /// How far each parameter moved, in units of its scale.
    pub adjusted: Vec<f64>,
}

/// Farthest a parameter may be asked to move in one request, relative to max(1, |value|).
/// The continuation takes one step per 2 % of the parameter's scale, each a few
/// milliseconds, so this bounds a request's time; the page asks for small moves as a slider
/// is dragged, far inside it.
const MAX_MOVE: f64 = 1.0;

/// `POST /api/shape/follow`: moves parameter `index` to `value` and the others so that the
/// design keeps one degree of freedom (a generic design just takes the value).
pub async fn follow_shape(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> ApiResult<Json<FollowAnswer>> {
    let bytes = body.map_err(|e| ApiError::bad_body(&e))?;
    let request: FollowRequest = serde_json::from_slice(&bytes).map_err(|e| {
        ApiError::bad_parameter(format!(
            "request body is not {{\"design\": …, \"index\": …, \"value\": …}}: {e}"
        ))
    })?;
    let design = design_of(&request.design)?;
    let (index, value) = (request.index, request.value);
    if let Some(&now) = design.params.get(index) {
        if value.is_finite() && (value - now).abs() > MAX_MOVE * now.abs().max(1.0) {
            return Err(ApiError::bad_parameter(format!(
                "parameter {index} from {now} to {value} is too far for one move; move in \
                 smaller steps"
            )));
        }
    }
    let timeout = state.settings().sim_timeout;
    let followed = run_bounded(timeout, move |_| {
        follow(&design, index, value, &ShapeSettings::default())
    })
    .await?
    .map_err(|e| explain_shape(&e))?;
    Ok(Json(FollowAnswer {
        params: followed.design.params.clone(),
        spec: followed.spec,
        class: followed.class,
        steps: followed.steps,
        adjusted: followed.adjusted,
    }))
}

/// The answer of `GET /api/shape/ranges`.
#[derive(Debug, Serialize)]
pub struct RangesAnswer {
    /// The design's spec.
    pub spec: String,
    /// The kerf the ranges hold for.
    pub kerf: f64,
    /// One range per shape parameter (the library's `ParamRange`).
    pub ranges: Vec<ParamRange>,
}

/// `GET /api/shape/ranges?design=[&kerf=]`: each shape parameter's valid interval, the
/// others fixed (where the design builds and insets at the kerf, so deploying it is never
/// refused as ill-shaped), and the well-shaped band inside it. 422 `ill_shaped` for a design
/// that does not build at its own parameters.
pub async fn ranges(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<RangesAnswer>> {
    let (pairs, design) = design_query(raw.as_deref(), &["design", "kerf"])?;
    let kerf = match param(&pairs, "kerf") {
        None => isogami::contact::ContactSettings::default().kerf,
        Some(t) => t
            .parse::<f64>()
            .ok()
            .filter(|k| k.is_finite())
            .ok_or_else(|| ApiError::bad_parameter("kerf must be a finite number"))?,
    };
    isogami::contact::ContactSettings::with_kerf(kerf)
        .validate()
        .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
    let timeout = state.settings().sim_timeout;
    let spec = design.to_string();
    let out = run_bounded(timeout, move |_| param_ranges(&design, kerf)).await?;
    let ranges = out.ok_or_else(|| {
        ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "ill_shaped",
            format!("{spec} does not build at kerf {kerf}"),
            "move the shape sliders back towards the defaults, or make the kerf narrower",
        )
    })?;
    Ok(Json(RangesAnswer { spec, kerf, ranges }))
}

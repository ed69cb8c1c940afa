//! Finite-sheet endpoint: a region of a design, its DOF, completion and finite deployment.

use crate::error::ApiResult;
use crate::filters::pairs;
use crate::finite::query::parse_sheet;
use crate::finite::{sheet_bounded, SheetAnswer};
use crate::state::AppState;
use axum::extract::{RawQuery, State};
use axum::Json;

/// `GET /api/sheet?design=&region=&edge_mm=&t=&min_cover=&raw=&deploy=&frames=&kerf=`: the
/// finite sheet of a region (see [`SheetAnswer`]), under the server's simulation time limit.
pub async fn sheet(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<SheetAnswer>> {
    let query = parse_sheet(&pairs(raw.as_deref()))?;
    Ok(Json(
        sheet_bounded(query, state.settings().sim_timeout, state.heavy().clone()).await?,
    ))
}

//! The catalogue's mechanisms view: `GET /api/motions?filters` — the matching designs grouped
//! by motion class (`Store::motion_groups`: one group per distinct motion with its counts and
//! ranges over the matching designs, members in the query's order, designs without a class in
//! one `unclassified` group). Takes the filter and sort keys of `/api/designs`; `limit` and
//! `offset` are accepted and ignored (every matching group is answered).

use crate::error::ApiResult;
use crate::filters::{pairs, parse};
use crate::state::AppState;
use axum::extract::{RawQuery, State};
use axum::Json;
use isogami_store::MotionGroups;

/// `GET /api/motions?filters`.
pub async fn motions(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<MotionGroups>> {
    let request = parse(&pairs(raw.as_deref()), &[])?;
    let groups = state
        .read(move |s| Ok(s.motion_groups(&request.query)?))
        .await?;
    Ok(Json(groups))
}

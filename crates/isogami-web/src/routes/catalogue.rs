//! Catalogue endpoints: stats, families, dictionary, pages of designs, facet counts, scatter.

use crate::error::{ApiError, ApiResult};
use crate::filters::{pairs, parse, MAX_SCATTER};
use crate::state::AppState;
use axum::extract::{RawQuery, State};
use axum::Json;
use isogami::tiling::{Family, FamilyInfo};
use isogami_store::query::ScatterPoint;
use isogami_store::{FieldDoc, Measure, Page, DICTIONARY};
use serde::Serialize;
use serde_json::{Map, Value};

/// `GET /api/stats`: the database summary with its settings as a JSON object.
pub async fn stats(State(state): State<AppState>) -> ApiResult<Json<Value>> {
    let stats = state.read(|s| Ok(s.stats()?)).await?;
    let mut v = serde_json::to_value(&stats).map_err(|e| ApiError::internal(e.to_string()))?;
    if let Some(text) = &stats.settings {
        v["settings"] = serde_json::from_str(text).unwrap_or(Value::String(text.clone()));
    }
    v["server_version"] = Value::String(env!("CARGO_PKG_VERSION").into());
    Ok(Json(v))
}

/// `GET /api/families`.
pub async fn families() -> Json<Vec<FamilyInfo>> {
    Json(Family::all().map(|f| f.info()).collect())
}

/// `GET /api/dictionary`.
pub async fn dictionary() -> Json<&'static [FieldDoc]> {
    Json(DICTIONARY)
}

/// One measure the catalogue ranges, sorts and plots by: its name as `range=`, `sort=`, `x=`
/// and `y=` take it, with its dictionary entry (type, unit, meaning).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct MeasureDoc {
    /// Name in the query string (a row's field; `v0`…`v5` for `params[k]`).
    pub name: String,
    /// JSON type of its value in a row; `|null` when a design may lack it.
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// Unit, or "".
    pub unit: &'static str,
    /// What it means.
    pub meaning: String,
}

/// Every measure of the store ([`Measure::all`]), in its order, each with its dictionary
/// entry: the browser's list of range filters, sort keys, scatter axes and table columns, so a
/// measure added to the store reaches the pages without a change there.
pub fn measure_docs() -> Vec<MeasureDoc> {
    Measure::all()
        .map(|m| {
            let name = m.to_string();
            if let Measure::Param(k) = m {
                return MeasureDoc {
                    meaning: format!(
                        "Shape parameter v{k} of the family (params[{k}]); null for families with fewer"
                    ),
                    name,
                    kind: "number|null",
                    unit: "",
                };
            }
            match DICTIONARY.iter().find(|d| d.field == name) {
                Some(d) => MeasureDoc {
                    name,
                    kind: d.kind,
                    unit: d.unit,
                    meaning: d.meaning.to_string(),
                },
                None => MeasureDoc {
                    name,
                    kind: "number|null",
                    unit: "",
                    meaning: String::new(),
                },
            }
        })
        .collect()
}

/// `GET /api/measures`.
pub async fn measures() -> Json<Vec<MeasureDoc>> {
    Json(measure_docs())
}

/// `GET /api/designs?filters`.
pub async fn designs(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<Page>> {
    let request = parse(&pairs(raw.as_deref()), &[])?;
    let page = state.read(move |s| Ok(s.page(&request.query)?)).await?;
    Ok(Json(page))
}

/// `GET /api/facets?filters`: `{facet: [{value, count}]}` for every facet.
pub async fn facets(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<Value>> {
    let request = parse(&pairs(raw.as_deref()), &[])?;
    let counts = state
        .read(move |s| Ok(s.all_facet_counts(&request.query)?))
        .await?;
    let mut out = Map::new();
    for (facet, values) in counts {
        let values = serde_json::to_value(values).map_err(|e| ApiError::internal(e.to_string()))?;
        out.insert(facet.to_string(), values);
    }
    Ok(Json(Value::Object(out)))
}

/// `GET /api/scatter?x=&y=&filters`.
pub async fn scatter(
    State(state): State<AppState>,
    RawQuery(raw): RawQuery,
) -> ApiResult<Json<Vec<ScatterPoint>>> {
    let request = parse(&pairs(raw.as_deref()), &[])?;
    let (Some(x), Some(y)) = (request.x, request.y) else {
        return Err(ApiError::bad_parameter("scatter needs x and y measures"));
    };
    let points = state
        .read(move |s| Ok(s.scatter(&request.query, x, y, MAX_SCATTER)?))
        .await?;
    Ok(Json(points))
}

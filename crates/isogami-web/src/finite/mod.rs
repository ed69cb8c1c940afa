//! Finite sheets over HTTP (issue 22): `GET /api/sheet` — a region of a design, its degrees
//! of freedom with a free boundary, its completion to a one-DOF sheet or the library's reason
//! why there is none, and on request the completed sheet's finite deployment. Every answer
//! comes from `isogami::api::{finite_sheet, deploy_sheet}`, run off the async runtime under the
//! live deployment's deadline and one of the heavy-job permits exports take
//! ([`sheet_bounded`]).
//!
//! | module | what |
//! |---|---|
//! | [`query`] | query string → design, [`SheetRequest`], deployment frames |

pub mod query;

use crate::error::{ApiError, ApiResult};
use crate::export::heavy_permit;
use crate::live::{explain, run_answered, timed_out, Deadline};
use axum::http::StatusCode;
use isogami::api::{
    deploy_sheet, finite_sheet, resolve_design, sheet_geometry, Design, SheetAnalysis,
    SheetDeployRequest, SheetDeployment, SheetRequest,
};
use isogami::deploy::TilePose;
use isogami::finite::{FiniteError, FiniteSheet};
use isogami::kinematics::Mechanism;
use isogami::Error;
use query::SheetQuery;
use serde::Serialize;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::Semaphore;

/// The answer of `GET /api/sheet`.
#[derive(Debug, Clone, Serialize)]
pub struct SheetAnswer {
    /// The library's analysis, as `isogami sheet --json` prints it: the raw region, its
    /// mobility (DOF opened and closed, floppy modes with their tiles) and the completion.
    /// When completion was refused, the raw region alone (`completion` null).
    pub analysis: SheetAnalysis,
    /// Why the region has no one-DOF sheet (the library's one line), when completion was
    /// asked for and refused.
    pub refused: Option<String>,
    /// The finite deployment, as `isogami sheet --deploy --json` prints it without its
    /// `analysis` (which is [`SheetAnswer::analysis`]); null when not asked or not possible.
    #[serde(serialize_with = "without_analysis")]
    pub deployment: Option<SheetDeployment>,
    /// Why a deployment that was asked for is not there (the sheet is not one DOF).
    pub not_deployed: Option<String>,
    /// What a front end needs to draw both sheets.
    pub drawing: Drawing,
}

/// A deployment's JSON without its `analysis` (the answer has it once, beside).
fn without_analysis<S: serde::Serializer>(
    deployment: &Option<SheetDeployment>,
    out: S,
) -> Result<S::Ok, S::Error> {
    let Some(d) = deployment else {
        return out.serialize_none();
    };
    let mut value = serde_json::to_value(d).map_err(serde::ser::Error::custom)?;
    if let Some(fields) = value.as_object_mut() {
        fields.remove("analysis");
    }
    value.serialize(out)
}

/// Tile outlines of the raw and the completed sheet in the closed state, in the tiling's
/// units like the deployment frames: tile `n` of a sheet has its vertices at
/// `(pose.x, pose.y) + R(pose.theta)·p` for p in `tiles[sheet.tiles[n].tile]`. A deployment
/// frame's poses place the same polygons.
#[derive(Debug, Clone, Serialize)]
pub struct Drawing {
    /// Mean edge length L (tiling units).
    pub length_scale: f64,
    /// Each cell tile's polygon about its centroid, counter-clockwise (tiling units).
    pub tiles: Vec<Vec<[f64; 2]>>,
    /// Closed-state pose of every tile of the raw region, in the order of `analysis.raw.tiles`.
    pub raw: Vec<TilePose>,
    /// Closed-state pose of every tile of the completed sheet, in the order of
    /// `analysis.completion.sheet.tiles`.
    pub completed: Option<Vec<TilePose>>,
}

/// The closed-state poses of `sheet`'s tiles (tiling units).
fn closed_poses(sheet: &FiniteSheet, mech: &Mechanism) -> Vec<TilePose> {
    let l = mech.length_scale;
    sheet
        .poses(mech, &mech.rest)
        .into_iter()
        .map(|(p, theta)| TilePose {
            x: p.x * l,
            y: p.y * l,
            theta,
        })
        .collect()
}

/// The drawing of `analysis`'s sheets.
fn drawing(design: &Design, analysis: &SheetAnalysis) -> Result<Drawing, Error> {
    let geometry = sheet_geometry(design)?;
    let cell = design.cell()?;
    let mech = Mechanism::new(&cell, &design.joints)?;
    Ok(Drawing {
        length_scale: geometry.length_scale,
        tiles: geometry.tiles,
        raw: closed_poses(&analysis.raw, &mech),
        completed: analysis
            .completion
            .as_ref()
            .map(|c| closed_poses(&c.sheet, &mech)),
    })
}

/// The library's reason when `e` says there is no one-DOF sheet.
fn no_one_dof(e: &Error) -> Option<String> {
    matches!(e, Error::Finite(FiniteError::NoOneDofSheet { .. })).then(|| e.to_string())
}

/// Runs `query` (on the blocking pool): the analysis, and the deployment when asked.
fn run(design: &Design, query: &SheetQuery, deadline: &Deadline) -> Result<SheetAnswer, Error> {
    let keep_going = &mut |_: usize| deadline.keep_going();
    let mut refused = None;
    let mut not_deployed = None;
    if let Some(frames) = query.deploy {
        let request = SheetDeployRequest {
            sheet: query.request.clone(),
            frames,
            ..SheetDeployRequest::default()
        };
        match deploy_sheet(design, &request, &mut *keep_going) {
            Ok(d) => {
                return Ok(SheetAnswer {
                    drawing: drawing(design, &d.analysis)?,
                    analysis: d.analysis.clone(),
                    refused: None,
                    deployment: Some(d),
                    not_deployed: None,
                });
            }
            // A completion refused, or a raw region that is not one DOF: the raw analysis
            // below says what the region is, and this says why nothing deployed.
            Err(e) => match no_one_dof(&e) {
                Some(reason) if query.request.complete => refused = Some(reason),
                Some(reason) => not_deployed = Some(reason),
                None => return Err(e),
            },
        }
    }
    // The analysis answers even when the completion is refused: the raw region, and why.
    let request = SheetRequest {
        keep_raw_on_refusal: true,
        ..query.request.clone()
    };
    let analysis = finite_sheet(design, &request, &mut *keep_going)?;
    let refused = refused.or_else(|| analysis.refusal.clone());
    if refused.is_some() && query.deploy.is_some() {
        not_deployed = refused.clone();
    }
    Ok(SheetAnswer {
        drawing: drawing(design, &analysis)?,
        analysis,
        refused,
        deployment: None,
        not_deployed,
    })
}

/// Runs `query` on the blocking pool holding one `heavy` permit (waited for within
/// `timeout`: 503 `busy` after that), answered by `timeout` (the time waited included) plus
/// [`ANSWER_GRACE`](crate::live::ANSWER_GRACE), and stopped at the deadline or when the
/// caller's future is dropped (the client went away).
pub async fn sheet_bounded(
    query: SheetQuery,
    timeout: Duration,
    heavy: Arc<Semaphore>,
) -> ApiResult<SheetAnswer> {
    // A design that cannot be read is a bad value of the request: 400, as for exports.
    let design = resolve_design(&query.design).map_err(|e| {
        let why = explain(&e);
        ApiError::new(StatusCode::BAD_REQUEST, why.kind, why.message, why.hint)
    })?;
    let (permit, left) = heavy_permit(heavy, timeout).await?;
    run_answered(left, move |deadline| {
        let _permit = permit;
        run(&design, &query, deadline)
    })
    .await
    .map_err(|e| match e.kind {
        // Past the deadline without the job's own answer: the sheet's words, not a deployment's.
        "timeout" => explain_sheet(&Error::Finite(FiniteError::Cancelled), timeout),
        _ => e,
    })?
    .map_err(|e| explain_sheet(&e, timeout))
}

/// A finite-sheet error as an answer: stopped at the time limit 422 `timeout`; a region or
/// request the library refuses 400 with its message; no one-DOF sheet at all (the periodic
/// sheet does not open) 422 `no_one_dof_sheet`; the deployment's failures as for a live
/// deployment.
pub fn explain_sheet(e: &Error, timeout: Duration) -> ApiError {
    match e {
        e if e.is_cancelled() => ApiError {
            hint: "ask for a smaller region here, or run `isogami sheet` from the command line \
                   (no time limit)"
                .into(),
            ..timed_out(timeout)
        },
        Error::Finite(
            FiniteError::BadRegion(_)
            | FiniteError::BadRequest(_)
            | FiniteError::EmptySheet
            | FiniteError::Settings(_),
        ) => ApiError::bad_parameter(e.to_string()),
        Error::Finite(FiniteError::NoOneDofSheet { .. }) => ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "no_one_dof_sheet",
            e.to_string(),
            "this design's sheet does not open; try another design or kerf",
        ),
        e => explain(e),
    }
}

//! Fabrication and interchange exports over HTTP: the formats list with the settings each
//! uses ([`catalog`]), and downloads of what the library's one export entry point
//! (`isogami::export::export_design`) writes, run off the async runtime with the live
//! deployment's deadline and cancel-on-drop ([`export_bounded`]).
//!
//! | module | what |
//! |---|---|
//! | [`query`] | query string → design, format, patch request, options (or a graded sheet's scale, opening, frames, options) |
//! | [`groups`] | settings groups (laser, …): query keys, form fields, defaults |
//! | [`archive`] | a folder export as one zip file |

pub mod archive;
pub mod groups;
pub mod query;

use crate::error::{ApiError, ApiResult};
use crate::live::{explain, run_answered, timed_out};
use crate::site::slug;
use axum::http::StatusCode;
use isogami::api::{resolve_design, GradedRun};
use isogami::contact::ContactSettings;
use isogami::deploy::DeployError;
use isogami::export::laser::LaserError;
use isogami::export::{
    export_files_until, export_graded, patch_at_with, read_graded, ExportError, ExportFiles,
    Format, PatchRequest, MAX_PATCH, MAX_PATCH_FRAMES,
};
use isogami::finite::FiniteError;
use isogami::Error;
use query::{ExportQuery, GradedExportQuery};
use serde_json::{json, Value};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::Semaphore;

/// Media type of a folder format's download.
pub const ZIP: &str = "application/zip";

/// The formats, the settings groups and the request's defaults and limits: what
/// `GET /api/export/formats` serves and a static site stores.
pub fn catalog() -> Value {
    let formats: Vec<Value> = Format::ALL
        .iter()
        .map(|&f| {
            json!({
                "name": f.name(),
                "description": f.description(),
                "extension": f.extension(),
                "media_type": f.media_type(),
                "folder": f.extension().is_none(),
                "download_type": if f.extension().is_none() { ZIP } else { f.media_type() },
                "settings": groups::groups_of(f),
                "uses_state": f.uses_state(),
            })
        })
        .collect();
    let settings: Vec<Value> = groups::GROUPS
        .iter()
        .map(|g| json!({ "name": g.name, "label": g.label, "fields": (g.fields)() }))
        .collect();
    let d = PatchRequest::default();
    let edge_mm = match d.scale {
        isogami::export::Scale::EdgeMm(mm) | isogami::export::Scale::WidthMm(mm) => mm,
    };
    json!({
        "formats": formats,
        "settings": settings,
        "defaults": {
            "rows": d.rows,
            "cols": d.cols,
            "edge_mm": edge_mm,
            "t": 0.0,
            "kerf": ContactSettings::default().kerf,
            "frames": d.frames,
            "raw": false,
        },
        "limits": {
            "max_patch": MAX_PATCH,
            "max_frames": MAX_PATCH_FRAMES,
            "max_cell_frames": query::MAX_CELL_FRAMES,
            "max_tiles": MAX_EXPORT_TILES,
        },
    })
}

/// A finished export: the bytes, their media type and the download's file name.
#[derive(Debug, Clone, PartialEq)]
pub struct Download {
    /// The file (a zip for a folder format).
    pub bytes: Vec<u8>,
    /// Its media type.
    pub media_type: &'static str,
    /// `<design-slug>-<R>x<C>.<ext>` (`….<format>.zip` for a folder format).
    pub file_name: String,
    /// The library's warning about the sheet written (a raw rectangle that is not one DOF
    /// names its DOF), as `isogami export` prints it.
    pub warning: Option<String>,
}

/// The download's file name for the design `spec`.
pub fn file_name(spec: &str, query: &ExportQuery) -> String {
    let stem = format!(
        "{}-{}x{}",
        slug(spec),
        query.request.rows,
        query.request.cols
    );
    match query.format.extension() {
        Some(ext) => format!("{stem}.{ext}"),
        None => format!("{stem}.{}.zip", query.format.name()),
    }
}

/// Most tiles in the rectangle of an export on the server. Every export analyses the
/// rectangle's mobility, a completed one prunes it round after round and a solid (STL, 3MF)
/// meshes it: stages that grow faster than the tile count, whose single steps (a
/// factorisation, the solid's union) do not poll the time limit, so the work is bounded
/// before it starts. The default 6×6 patch of a 50-tile cell passes;
/// the largest patch of a 6-tile cell (40×40, 9,600 tiles) does not. `isogami export` has no
/// such limit.
pub const MAX_EXPORT_TILES: usize = 1800;

/// The export's work, checked before anything runs: 422 `too_large` with the reason when
/// the rectangle holds more than [`MAX_EXPORT_TILES`] tiles.
pub fn check_work(cell_tiles: usize, query: &ExportQuery) -> ApiResult<()> {
    let r = &query.request;
    let tiles = r.rows * r.cols * cell_tiles;
    if tiles > MAX_EXPORT_TILES {
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "too_large",
            format!(
                "patch {}x{} of a {cell_tiles}-tile cell is {tiles} tiles: the server exports at \
                 most {MAX_EXPORT_TILES}",
                r.rows, r.cols
            ),
            "export a smaller patch, or run `isogami export` from the command line (no limit)",
        ));
    }
    Ok(())
}

/// Runs the export of `query` on the blocking pool: its size checked first
/// ([`check_work`]), then one of the `heavy` permits taken (waiting at most `timeout`, else
/// 503 `busy`), then the library's stages — the patch (its deployment and completion) and
/// the format (a print's layout and solid), each polling the deadline — answered by
/// `timeout` (+ the grace of [`run_answered`]) or stopped when the caller's future is
/// dropped (the client went away). The permit goes with the job and is released when its
/// thread ends, within one step of the stop.
pub async fn export_bounded(
    query: ExportQuery,
    timeout: Duration,
    heavy: Arc<Semaphore>,
) -> ApiResult<Download> {
    // A design that cannot be read is a bad value of the request: 400, like the others.
    let design = resolve_design(&query.design).map_err(|e| {
        let why = explain(&e);
        match why.kind {
            "ill_shaped" => ApiError::new(StatusCode::BAD_REQUEST, why.kind, why.message, why.hint),
            _ => ApiError::new(
                StatusCode::BAD_REQUEST,
                "bad_design",
                why.message,
                "a design is a name (rotating-squares), a spec FAMILY:PARAMS:CELL:JOINTS or \
                 design JSON",
            ),
        }
    })?;
    let cell_tiles = design
        .cell()
        .map_err(|e| explain(&Error::from(e)))?
        .tiles
        .len();
    check_work(cell_tiles, &query)?;
    let (permit, left) = heavy_permit(heavy, timeout).await?;
    let spec = design.to_string();
    let name = file_name(&spec, &query);
    let format = query.format;
    let (patch, files) = run_answered(left, move |deadline| {
        let _permit = permit;
        let patch = patch_at_with(&design, &query.request, &mut |_| deadline.keep_going())?;
        let files = export_files_until(format, &patch, &query.options, &|| deadline.keep_going())?;
        Ok((patch, files))
    })
    .await
    .map_err(|e| export_timeout(e, timeout))?
    .map_err(|e| explain_export(&e, timeout))?;
    let warning = patch.finite.warning();
    Ok(match files {
        ExportFiles::One(bytes) => Download {
            bytes,
            media_type: format.media_type(),
            file_name: name,
            warning,
        },
        ExportFiles::Folder(named) => Download {
            bytes: archive::zip_files(&named)?,
            media_type: ZIP,
            file_name: name,
            warning,
        },
    })
}

/// One `heavy` permit, waited for at most `timeout` (busy after that), and the time left:
/// exports and finite sheets share them.
pub(crate) async fn heavy_permit(
    heavy: Arc<Semaphore>,
    timeout: Duration,
) -> ApiResult<(tokio::sync::OwnedSemaphorePermit, Duration)> {
    let started = Instant::now();
    let permit = tokio::time::timeout(timeout, heavy.acquire_owned())
        .await
        .map_err(|_| busy())?
        .map_err(|_| ApiError::internal("the export permits were closed"))?;
    Ok((permit, timeout.saturating_sub(started.elapsed())))
}

/// The download's file name of a graded sheet's export: `<stem>.<ext>`, or
/// `<stem>.<format>.zip` for a folder format.
pub fn graded_file_name(stem: &str, format: Format) -> String {
    match format.extension() {
        Some(ext) => format!("{stem}.{ext}"),
        None => format!("{stem}.{}.zip", format.name()),
    }
}

/// Runs the export of a finished graded run on the blocking pool, bounded as
/// [`export_bounded`] is (its tiles checked against [`MAX_EXPORT_TILES`], one `heavy` permit,
/// `timeout`, stopped when the caller goes away). The run is written as `isogami graded --out`
/// writes it and read back by `export::read_graded`, so that the file equals what
/// `isogami export --sheet` makes of the downloaded sheet; then `export::export_graded`.
pub async fn export_graded_bounded(
    run: Arc<GradedRun>,
    query: GradedExportQuery,
    stem: &str,
    timeout: Duration,
    heavy: Arc<Semaphore>,
) -> ApiResult<Download> {
    let tiles = run.sheet.tiles.len();
    if tiles > MAX_EXPORT_TILES {
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "too_large",
            format!(
                "a graded sheet of {tiles} tiles: the server exports at most {MAX_EXPORT_TILES}"
            ),
            "run `isogami export --sheet` from the command line (no limit)",
        ));
    }
    let (permit, left) = heavy_permit(heavy, timeout).await?;
    let format = query.format;
    let (patch, files) = run_answered(left, move |deadline| {
        let _permit = permit;
        let text = serde_json::to_string_pretty(&*run).map_err(|e| ExportError::Read {
            format: "graded sheet",
            reason: e.to_string(),
        })?;
        let input = read_graded(&text)?;
        export_graded(
            &input.sheet,
            input.path.as_ref(),
            &query.request,
            format,
            &query.options,
            &|| deadline.keep_going(),
        )
    })
    .await
    .map_err(|e| export_timeout(e, timeout))?
    .map_err(|e| explain_export(&e, timeout))?;
    let warning = patch.finite.warning();
    let file_name = graded_file_name(stem, format);
    Ok(match files {
        ExportFiles::One(bytes) => Download {
            bytes,
            media_type: format.media_type(),
            file_name,
            warning,
        },
        ExportFiles::Folder(named) => Download {
            bytes: archive::zip_files(&named)?,
            media_type: ZIP,
            file_name,
            warning,
        },
    })
}

/// 503 `busy`: every export permit stayed taken for the whole time limit.
fn busy() -> ApiError {
    ApiError::new(
        StatusCode::SERVICE_UNAVAILABLE,
        "busy",
        "the server is running as many exports and finite sheets as it allows",
        "try again in a moment, or run `isogami export` or `isogami sheet` from the command line",
    )
}

/// The export hint on a `timeout` answer.
fn export_timeout(e: ApiError, timeout: Duration) -> ApiError {
    if e.kind == "timeout" {
        return explain_export(
            &ExportError::Library(Error::Deploy(DeployError::Cancelled)),
            timeout,
        );
    }
    e
}

/// An export error as an answer: the deployment's failures as for a live deployment (422,
/// `timeout` when stopped), a rectangle without a one-DOF completion 422 `no_one_dof_sheet`
/// with the library's reason and the hint to export it raw, a sheet the library cannot lay out from the design's own geometry
/// 422 `export_failed`, every other refusal (a value of the request) 400 with the library's
/// message.
pub fn explain_export(e: &ExportError, timeout: Duration) -> ApiError {
    match e {
        e if e.is_cancelled() => ApiError {
            hint: "export a smaller patch or fewer frames here, or run `isogami export` from the \
                   command line (no time limit)"
                .into(),
            ..timed_out(timeout)
        },
        ExportError::Library(Error::Finite(FiniteError::NoOneDofSheet { .. })) => ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "no_one_dof_sheet",
            e.to_string(),
            "export the raw rectangle instead (raw=true; `isogami export --raw`): it is written \
             as it is, with its floppy boundary; `isogami sheet` shows why there is no \
             completion",
        ),
        ExportError::Library(inner) => explain(inner),
        ExportError::Degenerate { .. }
        | ExportError::Encode { .. }
        | ExportError::Laser(
            LaserError::NoTiles
            | LaserError::BadTile { .. }
            | LaserError::Overlap { .. }
            | LaserError::JointNotOnEdge { .. }
            | LaserError::NoSuchTile { .. },
        ) => ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "export_failed",
            e.to_string(),
            "this design's sheet cannot be written in this format; try another state or format",
        ),
        _ => ApiError::bad_parameter(e.to_string()),
    }
}

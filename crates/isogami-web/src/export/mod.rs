//! Fabrication and interchange exports over HTTP: the formats list with the settings each
//! uses ([`catalog`]), and downloads of what the library's one export entry point
//! (`isogami::export::export_design`) writes, run off the async runtime with the live
//! deployment's deadline and cancel-on-drop ([`export_bounded`]).
//!
//! | module | what |
//! |---|---|
//! | [`query`] | query string → design, format, patch request, options |
//! | [`groups`] | settings groups (laser, …): query keys, form fields, defaults |
//! | [`archive`] | a folder export as one zip file |

pub mod archive;
pub mod groups;
pub mod query;

use crate::error::{ApiError, ApiResult};
use crate::live::{explain, run_bounded, timed_out};
use crate::site::slug;
use axum::http::StatusCode;
use isogami::api::resolve_design;
use isogami::contact::ContactSettings;
use isogami::export::laser::LaserError;
use isogami::export::{
    export_design, ExportError, ExportFiles, Format, PatchRequest, MAX_PATCH, MAX_PATCH_FRAMES,
};
use isogami::finite::FiniteError;
use isogami::Error;
use query::ExportQuery;
use serde_json::{json, Value};
use std::time::Duration;

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

/// Runs the export of `query` on the blocking pool, stopped at `timeout` or when the caller's
/// future is dropped (the client went away).
pub async fn export_bounded(query: ExportQuery, timeout: Duration) -> ApiResult<Download> {
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
    let spec = design.to_string();
    let name = file_name(&spec, &query);
    let format = query.format;
    let (patch, files) = run_bounded(timeout, move |deadline| {
        export_design(&design, &query.request, format, &query.options, &mut |_| {
            deadline.keep_going()
        })
    })
    .await?
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

/// An export error as an answer: the deployment's failures as for a live deployment (422,
/// `timeout` when stopped), a rectangle without a one-DOF completion 422 `no_one_dof_sheet`
/// with the library's reason and the hint to export it raw, a sheet the library cannot lay out from the design's own geometry
/// 422 `export_failed`, every other refusal (a value of the request) 400 with the library's
/// message.
pub fn explain_export(e: &ExportError, timeout: Duration) -> ApiError {
    match e {
        ExportError::Library(inner) if inner.is_cancelled() => ApiError {
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

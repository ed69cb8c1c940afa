//! The query string of `GET /api/export` → what to export: the design text, the format, the
//! patch request and the format options. Keys are named as `isogami export`'s flags with
//! underscores (`edge_mm` for `--edge-mm`); every key is checked, an unknown or repeated one
//! is refused, and the library's own validation runs before anything is deployed. The sheet
//! written is the R×C rectangle's completion to a one-DOF sheet unless `raw=true` asks for
//! the rectangle as it is (`complete=true|false` is still read: `complete=false` is raw).
//! A graded sheet's export (`GET /api/graded/{id}/export`) reads the keys the two share
//! ([`parse_graded_export`]).

use super::groups::{group_keys, Values, GROUPS};
use crate::error::{ApiError, ApiResult};
use crate::filters::truncate;
use isogami::contact::ContactSettings;
use isogami::export::{
    ExportOptions, Format, GradedPatchRequest, PatchRequest, Scale, State, MAX_PATCH,
};

/// Most cells × frames one export may hold on the server: every frame places every tile of
/// the patch, and a FOLD file writes them all (a 40×40 patch of a 12-tile cell with 100
/// frames would be about half a gigabyte). The limit lets the largest patch through at the
/// default frame count; the CLI has no such limit.
pub const MAX_CELL_FRAMES: usize = MAX_PATCH * MAX_PATCH * 11;

/// Keys of the request itself (the settings groups add theirs).
pub const REQUEST_KEYS: [&str; 10] = [
    "design", "format", "patch", "edge_mm", "width_mm", "t", "kerf", "frames", "raw", "complete",
];

/// A parsed export request.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportQuery {
    /// The design as given (name, spec or JSON): read by the library when it runs.
    pub design: String,
    /// The format.
    pub format: Format,
    /// The patch, checked by [`PatchRequest::validate`].
    pub request: PatchRequest,
    /// The format options, checked by [`ExportOptions::validate`] for this format.
    pub options: ExportOptions,
}

/// Refuses a key that is neither one of `own` nor a settings group's, and a repeated key.
fn check_keys(pairs: &[(String, String)], own: &[&str]) -> ApiResult<()> {
    let groups = group_keys();
    for (k, (key, _)) in pairs.iter().enumerate() {
        if !own.contains(&key.as_str()) && !groups.contains(&key.as_str()) {
            return Err(ApiError::bad_parameter(format!(
                "unknown parameter {:?}",
                truncate(key)
            )));
        }
        if pairs[..k].iter().any(|(other, _)| other == key) {
            return Err(ApiError::bad_parameter(format!(
                "parameter {key} given twice"
            )));
        }
    }
    Ok(())
}

/// `format`, by the library's names.
fn format_of(values: &Values<'_>) -> ApiResult<Format> {
    values
        .get("format")
        .ok_or_else(|| ApiError::bad_parameter("missing parameter format"))?
        .parse()
        .map_err(|e: isogami::export::ExportError| ApiError::bad_parameter(e.to_string()))
}

/// `edge_mm` or `width_mm` (`default` when neither).
fn scale_of(values: &Values<'_>, default: Scale) -> ApiResult<Scale> {
    Ok(
        match (values.number("edge_mm")?, values.number("width_mm")?) {
            (Some(_), Some(_)) => {
                return Err(ApiError::bad_parameter(
                    "give edge_mm or width_mm, not both",
                ))
            }
            (_, Some(w)) => Scale::WidthMm(w),
            (Some(e), None) => Scale::EdgeMm(e),
            (None, None) => default,
        },
    )
}

/// `t`: a number, `open` or `limit` (`default` when not given).
fn state_of(values: &Values<'_>, default: State) -> ApiResult<State> {
    match values.get("t") {
        None => Ok(default),
        Some(text) => text.parse().map_err(ApiError::bad_parameter),
    }
}

/// `frames` (`default` when not given).
fn frames_of(values: &Values<'_>, default: usize) -> ApiResult<usize> {
    match values.get("frames") {
        None => Ok(default),
        Some(text) => text.parse::<usize>().map_err(|_| {
            ApiError::bad_parameter(format!(
                "frames {:?}: expected a whole number",
                truncate(text)
            ))
        }),
    }
}

/// The format options: every settings group's keys read, then checked for `format`.
fn options_of(values: &Values<'_>, format: Format) -> ApiResult<ExportOptions> {
    let mut options = ExportOptions::default();
    for group in GROUPS {
        (group.apply)(&mut options, values)?;
    }
    options
        .validate(format)
        .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
    Ok(options)
}

/// Reads and checks the query pairs.
pub fn parse_export(pairs: &[(String, String)]) -> ApiResult<ExportQuery> {
    check_keys(pairs, &REQUEST_KEYS)?;
    let values = Values(pairs);
    let design = values.design()?;
    let format = format_of(&values)?;

    let defaults = PatchRequest::default();
    let (rows, cols) = match values.get("patch") {
        Some(text) => parse_patch(text)?,
        None => (defaults.rows, defaults.cols),
    };
    let scale = scale_of(&values, defaults.scale)?;
    let state = state_of(&values, defaults.state)?;
    let kerf = values
        .number("kerf")?
        .unwrap_or(ContactSettings::default().kerf);
    let frames = frames_of(&values, defaults.frames)?;
    // The completed sheet unless the rectangle is asked for, by either key.
    let complete = match (values.flag("raw")?, values.flag("complete")?) {
        (Some(raw), Some(complete)) if raw == complete => {
            return Err(ApiError::bad_parameter(format!(
                "raw={raw} and complete={complete} contradict each other: give one of them"
            )))
        }
        (Some(raw), _) => !raw,
        (None, Some(complete)) => complete,
        (None, None) => true,
    };
    let request = PatchRequest {
        rows,
        cols,
        scale,
        state,
        kerf,
        frames,
        complete,
        region: None,
    };
    request
        .validate()
        .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
    if rows * cols * frames > MAX_CELL_FRAMES {
        return Err(ApiError::bad_parameter(format!(
            "patch {rows}x{cols} with {frames} frames: at most {MAX_CELL_FRAMES} cells × frames \
             on the server (fewer frames or a smaller patch, or `isogami export`)"
        )));
    }
    let options = options_of(&values, format)?;
    Ok(ExportQuery {
        design: design.to_string(),
        format,
        request,
        options,
    })
}

/// Keys of a graded sheet's export, named as `isogami export --sheet`'s flags (the settings
/// groups add theirs): no design, patch, kerf or completion — the sheet is the job's.
pub const GRADED_KEYS: [&str; 5] = ["format", "edge_mm", "width_mm", "t", "frames"];

/// A parsed export request of a graded sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct GradedExportQuery {
    /// The format.
    pub format: Format,
    /// Scale, state (the opening) and frames, checked by [`GradedPatchRequest::validate`].
    pub request: GradedPatchRequest,
    /// The format options, checked by [`ExportOptions::validate`] for this format.
    pub options: ExportOptions,
}

/// Reads and checks the query pairs of a graded sheet's export: the keys, values and
/// defaults of [`parse_export`] for what they share (`t` is the sheet's opening: 0 closed,
/// 1 or `open` the optimised state).
pub fn parse_graded_export(pairs: &[(String, String)]) -> ApiResult<GradedExportQuery> {
    check_keys(pairs, &GRADED_KEYS)?;
    let values = Values(pairs);
    let format = format_of(&values)?;
    let defaults = GradedPatchRequest::default();
    let request = GradedPatchRequest {
        scale: scale_of(&values, defaults.scale)?,
        state: state_of(&values, defaults.state)?,
        frames: frames_of(&values, defaults.frames)?,
    };
    request
        .validate()
        .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
    let options = options_of(&values, format)?;
    Ok(GradedExportQuery {
        format,
        request,
        options,
    })
}

/// `ROWSxCOLS`, as `--patch`.
fn parse_patch(text: &str) -> ApiResult<(usize, usize)> {
    let bad = || {
        ApiError::bad_parameter(format!(
            "patch {:?}: expected ROWSxCOLS, each 1..={MAX_PATCH}, e.g. 6x6",
            truncate(text)
        ))
    };
    let (r, c) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let r = r.trim().parse::<usize>().map_err(|_| bad())?;
    let c = c.trim().parse::<usize>().map_err(|_| bad())?;
    Ok((r, c))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filters::pairs;

    fn parsed(q: &str) -> ApiResult<ExportQuery> {
        parse_export(&pairs(Some(q)))
    }

    #[test]
    fn every_cli_flag_has_its_key() {
        let q = parsed(
            "design=rotating-squares&format=SVG&patch=2x3&width_mm=120&t=open&kerf=0.02&frames=5\
             &material=card&hinge_mm=0.9&margin_mm=0&labels=true&cut_colour=%23ff00ff",
        )
        .unwrap();
        assert_eq!(q.format, Format::Svg);
        assert_eq!((q.request.rows, q.request.cols), (2, 3));
        assert_eq!(q.request.scale, Scale::WidthMm(120.0));
        assert_eq!(q.request.state, State::Open);
        assert_eq!((q.request.kerf, q.request.frames), (0.02, 5));
        let l = &q.options.laser;
        // The preset's kerf and thickness, the hinge given.
        let card = Material::Card.numbers();
        assert_eq!(
            (l.hinge_mm, l.kerf_mm, l.thickness_mm),
            (0.9, card.kerf_mm, card.thickness_mm)
        );
        assert_eq!((l.margin_mm, l.labels), (0.0, true));
        assert_eq!(l.colours.cut, "#ff00ff");
    }

    use isogami::export::laser::Material;

    #[test]
    fn absent_keys_are_the_library_defaults_with_the_completed_sheet() {
        let q = parsed("design=rotating-squares&format=fold").unwrap();
        assert_eq!(
            q.request,
            PatchRequest {
                complete: true,
                ..PatchRequest::default()
            }
        );
        assert_eq!(q.options, ExportOptions::default());
    }

    #[test]
    fn raw_asks_for_the_rectangle_and_complete_is_still_read() {
        let complete = |q: &str| {
            parsed(&format!("design=x&format=fold{q}"))
                .unwrap()
                .request
                .complete
        };
        assert!(complete(""));
        assert!(!complete("&raw=true"));
        assert!(complete("&raw=false"));
        assert!(!complete("&complete=false"));
        assert!(complete("&complete=1"));
        assert!(!complete("&raw=1&complete=false"));
        assert!(complete("&raw=0&complete=true"));
    }

    #[test]
    fn bad_values_are_refused_naming_the_key() {
        for (q, needle) in [
            ("format=svg", "missing parameter design"),
            ("design=x", "missing parameter format"),
            ("design=x&format=stl2", "unknown export format"),
            ("design=x&format=svg&patch=41x41", "at most 40"),
            ("design=x&format=svg&patch=0x2", "at least 1"),
            ("design=x&format=svg&patch=6", "ROWSxCOLS"),
            ("design=x&format=svg&t=1.5", "[0, 1]"),
            ("design=x&format=svg&t=later", "'open'"),
            ("design=x&format=svg&edge_mm=-2", "edge length -2 mm"),
            ("design=x&format=svg&width_mm=0", "patch width 0 mm"),
            ("design=x&format=svg&edge_mm=1&width_mm=1", "not both"),
            ("design=x&format=svg&frames=1", "frames"),
            ("design=x&format=svg&hinge_mm=-1", "hinge_mm"),
            ("design=x&format=svg&kerf_mm=abc", "kerf_mm"),
            ("design=x&format=svg&margin_mm=NaN", "margin_mm"),
            ("design=x&format=svg&material=wood", "material"),
            ("design=x&format=svg&labels=maybe", "labels"),
            ("design=x&format=svg&cut_colour=red", "cut colour"),
            ("design=x&format=svg&colour=red", "unknown parameter"),
            ("design=x&format=svg&format=dxf", "twice"),
            ("design=x&format=svg&raw=yes", "raw"),
            ("design=x&format=svg&complete=yes", "complete"),
            ("design=x&format=svg&raw=true&complete=true", "contradict"),
            (
                "design=x&format=fold&patch=40x40&frames=12",
                "cells × frames",
            ),
        ] {
            let e = parsed(q).unwrap_err();
            assert_eq!(e.status, 400, "{q}");
            assert!(e.message.contains(needle), "{q}: {}", e.message);
        }
        // The largest patch at the default frame count is allowed.
        assert!(parsed("design=x&format=fold&patch=40x40").is_ok());
        assert_eq!(
            PatchRequest::default().frames * MAX_PATCH * MAX_PATCH,
            MAX_CELL_FRAMES
        );
        // Laser values are only judged for the formats laid out with them.
        assert!(parsed("design=x&format=fold&hinge_mm=-1").is_ok());
    }
}

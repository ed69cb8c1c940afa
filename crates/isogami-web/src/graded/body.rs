//! The body of `POST /api/graded` → the library's [`GradedRequest`], with the meaning of
//! `isogami graded`'s flags (a left-out field is the flag's default; `target` — or its older
//! name `outline` — is `--target`'s text, read by the library's own parser, and `svg` the text
//! of the file `--target @FILE.svg` names, read by `graded::outline_from_svg`), checked against
//! this server's caps; then the library's own refusals of the request ([`refusal`]: its setup
//! refuses a target too thin for the sheet's tiles, a field past the design's opening, a
//! tolerance out of range) answered as 400s before a job starts.

use super::limits::GradedLimits;
use crate::error::{ApiError, ApiResult};
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::http::StatusCode;
use isogami::api::resolve_design;
use isogami::graded::{
    outline_from_svg, parse_outline, parse_target, setup, GradedError, GradedRequest, Outline,
    Target,
};
use serde::Deserialize;
use serde_json::{json, Value};

/// Longest design or outline text accepted.
pub const MAX_TEXT: usize = 16 * 1024;

/// Longest SVG text accepted (a body is at most 64 KiB of JSON on this server).
pub const MAX_SVG: usize = 48 * 1024;

/// Points drawn around a disc or an ellipse for the page (as the library's report does).
const OUTLINE_SAMPLES: usize = 128;

/// What a client posts.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GradedBody {
    /// The design: a name, a spec or design JSON (`--design`; default rotating-squares).
    pub design: Option<String>,
    /// Cells along w (`--region R×_`; default 3).
    pub rows: Option<usize>,
    /// Cells along u (`--region _×C`; default 3).
    pub cols: Option<usize>,
    /// The target: an outline `disc`, `ellipse:A,B` or `polygon:x,y;x,y;…`, or an area-ratio
    /// field `field:FROM,TO[,DEGREES]` (`--target`; `outline` is its older name).
    #[serde(alias = "outline")]
    pub target: Option<String>,
    /// An SVG file's text whose one closed shape is the target outline (`--target @FILE.svg`),
    /// instead of `target`.
    pub svg: Option<String>,
    /// The SVG file's name, for the echo and the command line (default `outline.svg`).
    pub svg_name: Option<String>,
    /// The opened state as the periodic deployment's t in (0, 1] (`--t`).
    pub t: Option<f64>,
    /// States the pins must close in (`--states`).
    pub states: Option<usize>,
    /// Iterations of the fit (`--iterations`).
    pub iterations: Option<usize>,
    /// Largest error that meets the target, a fraction (`--tolerance`; default the library's:
    /// `graded::verdict::OUTLINE_TOLERANCE` or `FIELD_TOLERANCE`). Checked by the library.
    pub tolerance: Option<f64>,
    /// When the sheet graded towards the target does not open, give the nearest one that does
    /// (default true; false is `--no-fallback`: the sheet graded towards the target, whatever
    /// its path).
    pub fall_back: Option<bool>,
}

/// 400 `bad_target`: the library's message about the outline.
fn bad_target(message: String) -> ApiError {
    ApiError::new(
        StatusCode::BAD_REQUEST,
        "bad_target",
        message,
        "a target is disc, ellipse:A,B, polygon:x,y;x,y;… seen whole from its centroid, \
         field:FROM,TO[,DEGREES] or an SVG file with one closed shape",
    )
}

/// What to do about a target the sheet cannot reach.
pub const UNREACHABLE_HINT: &str = "grade a larger region or towards a rounder target; a \
     field's area ratios within what the design's own sheet opens to";

/// 400 `over_limit`: a count above this server's cap.
fn over_limit(message: String) -> ApiError {
    ApiError::new(
        StatusCode::BAD_REQUEST,
        "over_limit",
        message,
        "run `isogami graded` from the command line for larger sheets",
    )
}

/// The outline of `text` read by the library, or 400 with its one-line message.
pub fn outline_of(text: &str) -> ApiResult<Outline> {
    if text.len() > MAX_TEXT {
        return Err(bad_target("outline longer than 16 KiB".into()));
    }
    parse_outline(text).map_err(|e| bad_target(e.to_string()))
}

/// The target of `text` (an outline or a field) read by the library, or 400 with its
/// one-line message.
pub fn target_of(text: &str) -> ApiResult<Target> {
    if text.len() > MAX_TEXT {
        return Err(bad_target("target longer than 16 KiB".into()));
    }
    parse_target(text).map_err(|e| bad_target(e.to_string()))
}

/// The outline of an SVG file's text read by the library, or 400 with its one-line message
/// (naming the file as `name`).
pub fn svg_outline(svg: &str, name: &str) -> ApiResult<Outline> {
    if svg.len() > MAX_SVG {
        return Err(bad_target(format!(
            "{}: SVG longer than 48 KiB (this server's limit; `isogami graded --target @FILE.svg` has none)",
            crate::filters::truncate(name)
        )));
    }
    outline_from_svg(svg)
        .map_err(|e| bad_target(format!("{}: {e}", crate::filters::truncate(name))))
}

/// What the page draws of an outline: the text and its boundary at scale 1 (centred on its
/// centroid, counter-clockwise; 128 points around a disc or an ellipse).
pub fn outline_view(text: &str, outline: &Outline) -> Value {
    json!({
        "outline": text,
        "points": outline.boundary(1.0, OUTLINE_SAMPLES),
    })
}

impl GradedBody {
    /// Reads a posted body, with a 4xx JSON error for a missing, oversized or malformed one.
    pub fn from_request(body: Result<Bytes, BytesRejection>) -> ApiResult<GradedBody> {
        let bytes = body.map_err(|e| ApiError::bad_body(&e))?;
        serde_json::from_slice(&bytes).map_err(|e| {
            ApiError::bad_parameter(format!(
                "request body is not {{\"design\": …, \"rows\": …, \"cols\": …, \"outline\": …}}: {e}"
            ))
        })
    }

    /// The target's text as given (default `disc`; `@NAME` for an SVG file, as the CLI
    /// takes it).
    pub fn outline_text(&self) -> String {
        match &self.svg {
            Some(_) => format!("@{}", self.svg_file_name()),
            None => self.target.as_deref().unwrap_or("disc").to_string(),
        }
    }

    /// The SVG file's name (`outline.svg` when not given), without any folder.
    fn svg_file_name(&self) -> String {
        let name = self.svg_name.as_deref().unwrap_or("").trim();
        let name = name.rsplit(['/', '\\']).next().unwrap_or("");
        let name: String = name
            .chars()
            .filter(|c| !c.is_control() && !c.is_whitespace())
            .take(80)
            .collect();
        if name.is_empty() {
            "outline.svg".into()
        } else {
            name
        }
    }

    /// The target: the SVG file's outline, or the target text's outline or field.
    fn target(&self) -> ApiResult<Target> {
        match (&self.svg, &self.target) {
            (Some(_), Some(_)) => Err(ApiError::bad_parameter("give target or svg, not both")),
            (Some(svg), None) => svg_outline(svg, &self.svg_file_name()).map(Target::Outline),
            (None, text) => target_of(text.as_deref().unwrap_or("disc")),
        }
    }

    /// The library's request, checked against `limits` (the design read and its cell built,
    /// so that a bad one is a 400 here rather than a failed job).
    pub fn request(&self, limits: &GradedLimits) -> ApiResult<GradedRequest> {
        let mut r = GradedRequest::default();
        if let Some(d) = &self.design {
            if d.len() > MAX_TEXT {
                return Err(ApiError::bad_parameter("design longer than 16 KiB"));
            }
            if !d.trim().is_empty() {
                r.design = d.trim().to_string();
            }
        }
        r.rows = self.rows.unwrap_or(3);
        r.cols = self.cols.unwrap_or(3);
        if r.rows == 0 || r.cols == 0 {
            return Err(ApiError::bad_parameter(format!(
                "a region of {}x{} cells: at least one cell each way",
                r.rows, r.cols
            )));
        }
        if r.rows > limits.max_side || r.cols > limits.max_side {
            return Err(over_limit(format!(
                "a region of {}x{} cells is above this server's limit of {} cells each way",
                r.rows, r.cols, limits.max_side
            )));
        }
        if r.rows * r.cols > limits.max_cells {
            return Err(over_limit(format!(
                "a region of {}x{} = {} cells is above this server's limit of {} cells",
                r.rows,
                r.cols,
                r.rows * r.cols,
                limits.max_cells
            )));
        }
        r = r.with_target(self.target()?);
        if let Some(t) = self.t {
            if !(t.is_finite() && t > 0.0 && t <= 1.0) {
                return Err(ApiError::bad_parameter(format!(
                    "t = {t} must be in (0, 1] (an opened state)"
                )));
            }
            r.t = Some(t);
        }
        r.states = self.states.unwrap_or(r.states);
        if r.states == 0 || r.states > limits.max_states {
            return Err(ApiError::bad_parameter(format!(
                "{} states: from 1 to {}",
                r.states, limits.max_states
            )));
        }
        r.tolerance = self.tolerance;
        r.fall_back = self.fall_back.unwrap_or(r.fall_back);
        r.solve.max_iterations = self.iterations.unwrap_or(r.solve.max_iterations);
        if r.solve.max_iterations == 0 {
            return Err(ApiError::bad_parameter("iterations must be at least 1"));
        }
        if r.solve.max_iterations > limits.max_iterations {
            return Err(over_limit(format!(
                "iterations {} is above this server's limit of {}",
                r.solve.max_iterations, limits.max_iterations
            )));
        }
        let design = resolve_design(&r.design).map_err(|e| {
            ApiError::new(
                StatusCode::BAD_REQUEST,
                "bad_design",
                e.to_string(),
                "a design is a name (rotating-squares), a spec FAMILY:PARAMS:CELL:JOINTS or \
                 design JSON",
            )
        })?;
        let per_cell = design
            .cell()
            .map_err(|e| ApiError::bad_parameter(e.to_string()))?
            .tiles
            .len();
        let tiles = r.rows * r.cols * per_cell;
        if tiles > limits.max_tiles {
            return Err(over_limit(format!(
                "a region of {}x{} cells of {} tiles each ({tiles} tiles) is above this \
                 server's limit of {} tiles",
                r.rows, r.cols, per_cell, limits.max_tiles
            )));
        }
        Ok(r)
    }
}

/// The library's own refusal of `request`, run through its setup (the design's finite sheet
/// deployed and opened, about 0.2 s for 150 tiles): a target the sheet cannot reach
/// (`GradedError::Unreachable`: an outline too thin for its tiles, a field past the design's
/// periodic opening) or cannot use is 400 `bad_target`, a setting or region it refuses (a
/// tolerance that is not a positive fraction, a field on fewer than 2×2 cells) 400
/// `bad_parameter`, both with the library's one-line message. Any other failure of the setup
/// (a design whose sheet does not open, say) is left to the job, which reports it as its
/// error, as before: Ok here.
pub fn refusal(request: &GradedRequest) -> ApiResult<()> {
    let Err(e) = setup(request) else {
        return Ok(());
    };
    match &e {
        isogami::Error::Graded(GradedError::Unreachable(_)) => Err(ApiError::new(
            StatusCode::BAD_REQUEST,
            "bad_target",
            e.to_string(),
            UNREACHABLE_HINT,
        )),
        isogami::Error::Graded(GradedError::BadTarget(_)) => Err(bad_target(e.to_string())),
        isogami::Error::Graded(GradedError::BadSetting(_) | GradedError::BadRegion(_)) => {
            Err(ApiError::bad_parameter(e.to_string()))
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body(v: Value) -> GradedBody {
        serde_json::from_value(v).unwrap()
    }

    #[test]
    fn fields_mean_what_the_cli_flags_mean() {
        let limits = GradedLimits::default();
        let r = body(json!({})).request(&limits).unwrap();
        let d = GradedRequest::default();
        assert_eq!((r.rows, r.cols, &r.design), (3, 3, &d.design));
        assert_eq!(
            (r.outline.clone(), r.states, r.t),
            (Outline::Disc, d.states, None)
        );
        let r = body(json!({
            "design": "rotating-squares", "rows": 2, "cols": 4, "outline": "ellipse:1.4,1",
            "t": 0.5, "states": 4, "iterations": 60
        }))
        .request(&limits)
        .unwrap();
        assert_eq!((r.rows, r.cols), (2, 4));
        assert_eq!(r.outline, Outline::Ellipse { a: 1.4, b: 1.0 });
        assert_eq!((r.t, r.states, r.solve.max_iterations), (Some(0.5), 4, 60));
        // Left out: the library's tolerance and its fall-back; given: as `--tolerance` and
        // `--no-fallback`.
        assert_eq!((r.tolerance, r.fall_back), (None, true));
        let r = body(json!({"tolerance": 0.02, "fall_back": false}))
            .request(&limits)
            .unwrap();
        assert_eq!((r.tolerance, r.fall_back), (Some(0.02), false));
        // `target` is `outline`'s newer name, and takes a field too.
        let r = body(json!({"target": "field:1.2,1.8,90"}))
            .request(&limits)
            .unwrap();
        assert_eq!(
            r.field,
            Some(isogami::graded::parse_field("field:1.2,1.8,90").unwrap())
        );
        // An SVG file's text: the library's outline of it, echoed as `@NAME`.
        let svg = r#"<svg><polygon points="0,0 2,0 2,1 0,1"/></svg>"#;
        let b = body(json!({"svg": svg, "svg_name": "/tmp/x/box.svg"}));
        assert_eq!(b.outline_text(), "@box.svg");
        assert_eq!(
            b.request(&limits).unwrap().outline,
            outline_from_svg(svg).unwrap()
        );
    }

    #[test]
    fn bad_values_and_values_over_the_caps_are_refused() {
        let limits = GradedLimits::default();
        let star = "polygon:0,0;4,0;4,4;3,4;3,1;1,1;1,4;0,4";
        let e = body(json!({ "outline": star }))
            .request(&limits)
            .unwrap_err();
        assert_eq!((e.status, e.kind), (StatusCode::BAD_REQUEST, "bad_target"));
        assert_eq!(e.message, parse_outline(star).unwrap_err().to_string());
        let cases = [
            (json!({"rows": 0}), "bad_parameter", "at least one cell"),
            (json!({"rows": 9}), "over_limit", "9x3"),
            (json!({"rows": 7, "cols": 7}), "over_limit", "49 cells"),
            (json!({"t": 0}), "bad_parameter", "t = 0"),
            (json!({"states": 0}), "bad_parameter", "0 states"),
            (json!({"iterations": 801}), "over_limit", "iterations 801"),
            (json!({"iterations": 0}), "bad_parameter", "iterations"),
            (json!({"target": "field:1.2"}), "bad_target", "field:"),
            (
                json!({"svg": "<svg/>", "svg_name": "a.svg"}),
                "bad_target",
                "a.svg: ",
            ),
            (
                json!({"svg": "<svg/>", "target": "disc"}),
                "bad_parameter",
                "not both",
            ),
            (
                json!({"design": "no-such-design"}),
                "bad_design",
                "no-such-design",
            ),
        ];
        for (v, kind, names) in cases {
            let e = body(v.clone()).request(&limits).unwrap_err();
            assert_eq!(e.status, StatusCode::BAD_REQUEST, "{v}");
            assert_eq!(e.kind, kind, "{v}: {e:?}");
            assert!(e.message.contains(names), "{v}: {}", e.message);
        }
    }

    #[test]
    fn the_librarys_refusals_are_400s_in_its_words() {
        let limits = GradedLimits::default();
        let request = |v: Value| body(v).request(&limits).unwrap();
        // Too thin for 16 tiles: the library's Unreachable, a bad target.
        let r = request(json!({"rows": 2, "cols": 2, "target": "ellipse:100,1"}));
        let e = refusal(&r).unwrap_err();
        assert_eq!((e.status, e.kind), (StatusCode::BAD_REQUEST, "bad_target"));
        assert_eq!(e.message, setup(&r).unwrap_err().to_string());
        assert!(
            e.message.starts_with("unreachable target: "),
            "{}",
            e.message
        );
        // A field past the design's periodic opening (rotating squares open to 2).
        let e = refusal(&request(
            json!({"rows": 2, "cols": 2, "target": "field:3,3"}),
        ))
        .unwrap_err();
        assert_eq!(e.kind, "bad_target", "{}", e.message);
        // A tolerance the library refuses, and a field on one cell: bad parameters.
        for v in [
            json!({"rows": 2, "cols": 2, "tolerance": -1}),
            json!({"rows": 1, "cols": 1, "target": "field:1.3,1.5"}),
        ] {
            let e = refusal(&request(v.clone())).unwrap_err();
            assert_eq!(
                (e.status, e.kind),
                (StatusCode::BAD_REQUEST, "bad_parameter"),
                "{v}"
            );
        }
        // A reachable target is the job's.
        refusal(&request(json!({"rows": 2, "cols": 2}))).unwrap();
        // Types are checked on reading.
        for v in [json!({"tolerance": "5 %"}), json!({"fall_back": 1})] {
            assert!(serde_json::from_value::<GradedBody>(v).is_err());
        }
    }
}

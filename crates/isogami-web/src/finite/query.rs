//! The query string of `GET /api/sheet` → the library's [`SheetRequest`] and what else to run.
//! Keys are named as `isogami sheet`'s flags with underscores (`min_cover` for
//! `--min-cover`); every key is checked, an unknown or repeated one is refused, and the
//! library's own checks ([`SheetRequest::validate`], the region's parser) run before anything
//! is deployed. The server's caps on top of them keep a request within its time limit.

use crate::error::{ApiError, ApiResult};
use crate::export::groups::Values;
use crate::filters::truncate;
use isogami::api::SheetRequest;
use isogami::contact::ContactSettings;
use isogami::finite::Region;

/// Most cells along either direction of an R×C region on the server (the library takes up
/// to 40; the CLI has no time limit).
pub const MAX_SHEET_CELLS: usize = 12;
/// Widest region in mm on the server, in mean edge lengths (a rectangle's longer side, a
/// disc's diameter, a polygon's bounding box).
pub const MAX_SHEET_SPAN: f64 = 40.0;
/// Most frames of a finite deployment on the server.
pub const MAX_SHEET_FRAMES: usize = 200;
/// Frames of a finite deployment unless asked otherwise (as `isogami sheet --deploy`).
pub const DEFAULT_SHEET_FRAMES: usize = 24;

/// Keys of the request.
pub const SHEET_KEYS: [&str; 9] = [
    "design",
    "region",
    "edge_mm",
    "t",
    "min_cover",
    "raw",
    "deploy",
    "frames",
    "kerf",
];

/// A parsed finite-sheet request.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetQuery {
    /// The design as given (name, spec or JSON): read by the library when it runs.
    pub design: String,
    /// The sheet: region, scale, counting state, completion, smallest covered fraction and
    /// the deployment settings (kerf).
    pub request: SheetRequest,
    /// Deploy the (completed) sheet, with this many frames.
    pub deploy: Option<usize>,
}

/// Reads and checks the query pairs.
pub fn parse_sheet(pairs: &[(String, String)]) -> ApiResult<SheetQuery> {
    for (k, (key, _)) in pairs.iter().enumerate() {
        if !SHEET_KEYS.contains(&key.as_str()) {
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
    let values = Values(pairs);
    let design = values.design()?;
    let defaults = SheetRequest::default();
    let region = match values.get("region") {
        None => defaults.region.clone(),
        Some(text) => text
            .parse::<Region>()
            .map_err(|e| ApiError::bad_parameter(e.to_string()))?,
    };
    let edge_mm = values.number("edge_mm")?.unwrap_or(defaults.edge_mm);
    if !(edge_mm.is_finite() && edge_mm > 0.0) {
        return Err(ApiError::bad_parameter(format!(
            "edge_mm {edge_mm}: expected a length in mm above 0"
        )));
    }
    check_size(&region, edge_mm)?;
    let t = values.number("t")?.unwrap_or(defaults.t);
    let min_covered = match values.number("min_cover")? {
        Some(percent) => percent / 100.0,
        None => defaults.min_covered,
    };
    let raw = values.flag("raw")?.unwrap_or(false);
    let deploy = values.flag("deploy")?.unwrap_or(false);
    let frames = match values.get("frames") {
        None => None,
        Some(text) => Some(text.parse::<usize>().map_err(|_| {
            ApiError::bad_parameter(format!(
                "frames {:?}: expected a whole number",
                truncate(text)
            ))
        })?),
    };
    if frames.is_some() && !deploy {
        return Err(ApiError::bad_parameter(
            "frames are the finite deployment's: give deploy=true with them",
        ));
    }
    let frames = frames.unwrap_or(DEFAULT_SHEET_FRAMES);
    if !(2..=MAX_SHEET_FRAMES).contains(&frames) {
        return Err(ApiError::bad_parameter(format!(
            "frames {frames} outside 2..={MAX_SHEET_FRAMES}"
        )));
    }
    let mut settings = defaults.settings;
    if let Some(kerf) = values.number("kerf")? {
        if !kerf.is_finite() {
            return Err(ApiError::bad_parameter("kerf must be a finite number"));
        }
        settings.contact = ContactSettings::with_kerf(kerf);
    }
    settings
        .validate()
        .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
    let request = SheetRequest {
        region,
        edge_mm,
        t,
        complete: !raw,
        min_covered,
        keep_raw_on_refusal: false,
        settings,
    };
    request
        .validate()
        .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
    Ok(SheetQuery {
        design: design.to_string(),
        request,
        deploy: deploy.then_some(frames),
    })
}

/// The server's caps on a region's size (the library has already checked its shape).
fn check_size(region: &Region, edge_mm: f64) -> ApiResult<()> {
    let span = match region {
        Region::Cells { rows, cols } => {
            if *rows > MAX_SHEET_CELLS || *cols > MAX_SHEET_CELLS {
                return Err(ApiError::bad_parameter(format!(
                    "region {rows}x{cols}: at most {MAX_SHEET_CELLS}x{MAX_SHEET_CELLS} cells on \
                     the server (`isogami sheet` takes more)"
                )));
            }
            return Ok(());
        }
        Region::Rect {
            width_mm,
            height_mm,
        } => width_mm.max(*height_mm),
        Region::Disc { radius_mm } => 2.0 * radius_mm,
        Region::Polygon { points_mm } => {
            let extent = |d: usize| {
                let (lo, hi) = points_mm
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                        (lo.min(p[d]), hi.max(p[d]))
                    });
                hi - lo
            };
            extent(0).max(extent(1))
        }
    };
    if span / edge_mm > MAX_SHEET_SPAN {
        return Err(ApiError::bad_parameter(format!(
            "region {region} is {:.0} mean edge lengths across at {edge_mm} mm per edge: at most \
             {MAX_SHEET_SPAN:.0} on the server (`isogami sheet` takes more)",
            span / edge_mm
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filters::pairs;

    fn parsed(q: &str) -> ApiResult<SheetQuery> {
        parse_sheet(&pairs(Some(q)))
    }

    #[test]
    fn absent_keys_are_the_library_and_cli_defaults() {
        let q = parsed("design=rotating-squares").unwrap();
        assert_eq!(q.request, SheetRequest::default());
        assert_eq!(q.deploy, None);
        let q = parsed("design=x&deploy=true").unwrap();
        assert_eq!(q.deploy, Some(DEFAULT_SHEET_FRAMES));
    }

    #[test]
    fn every_cli_flag_has_its_key() {
        let q = parsed(
            "design=x&region=disc:30&edge_mm=10&t=0.5&min_cover=25&raw=true&deploy=1&frames=7\
             &kerf=0.02",
        )
        .unwrap();
        assert_eq!(q.request.region, Region::Disc { radius_mm: 30.0 });
        assert_eq!((q.request.edge_mm, q.request.t), (10.0, 0.5));
        assert_eq!(q.request.min_covered, 0.25);
        assert!(!q.request.complete);
        assert_eq!(q.request.settings.contact.kerf, 0.02);
        assert_eq!(q.deploy, Some(7));
    }

    #[test]
    fn bad_values_are_refused_naming_the_key() {
        for (q, needle) in [
            ("region=6x6", "missing parameter design"),
            ("design=x&region=hexagon", "is not a region"),
            ("design=x&region=0x3", "rows and columns"),
            ("design=x&region=13x2", "at most 12x12"),
            ("design=x&region=rect:900,10", "across"),
            ("design=x&region=disc:-1", "radius"),
            ("design=x&region=polygon:0,0;1,1", "at least 3 points"),
            ("design=x&edge_mm=0", "edge_mm"),
            ("design=x&t=0", "(0, 1]"),
            ("design=x&t=NaN", "(0, 1]"),
            ("design=x&t=soon", "t \"soon\""),
            ("design=x&min_cover=200", "covered fraction"),
            ("design=x&raw=maybe", "raw"),
            ("design=x&deploy=true&frames=1", "frames 1"),
            ("design=x&deploy=true&frames=1000", "frames 1000"),
            ("design=x&frames=5", "deploy=true"),
            ("design=x&kerf=inf", "kerf"),
            ("design=x&kerf=-1", "kerf"),
            ("design=x&colour=red", "unknown parameter"),
            ("design=x&region=2x2&region=3x3", "twice"),
        ] {
            let e = parsed(q).unwrap_err();
            assert_eq!(e.status, 400, "{q}");
            assert!(e.message.contains(needle), "{q}: {}", e.message);
        }
    }
}

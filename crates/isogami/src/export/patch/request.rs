//! What a patch export asks for — rows and columns or a region, scale, state, completion —
//! and the limits every request is checked against.

use crate::contact::ContactSettings;
use crate::export::error::ExportError;
use crate::finite::Region;
use crate::math::Real;

/// Most rows and most columns of a patch (40 × 40 cells; a 40×40 patch of a 12-tile cell
/// holds 19 200 tiles, enough for any sheet a laser bed or a print bed takes).
pub const MAX_PATCH: usize = 40;

/// Smallest edge length or patch width in mm (a micrometre: below it the numbers written are
/// no size any machine makes, and a subnormal scale loses its digits).
pub const MIN_SIZE_MM: Real = 1e-3;

/// Largest edge length or patch width in mm (a kilometre: a 40×40 patch of it stays far from
/// overflow in every format).
pub const MAX_SIZE_MM: Real = 1e6;

/// Most states in [`Patch::states`].
pub const MAX_PATCH_FRAMES: usize = 100;

/// How the patch is scaled to millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scale {
    /// The mean edge length L of the tiles, in mm.
    EdgeMm(Real),
    /// The width (x extent) of the patch at the asked state, in mm.
    WidthMm(Real),
}

/// Which state of the deployment to export.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum State {
    /// The accepted state with t nearest this value, in [0, 1] (0 closed, 1 the contact
    /// limit).
    T(Real),
    /// The most open state: the accepted state of largest area ratio (the last such state on
    /// a tie). Many designs reach it mid-path and close again before contact ends the path.
    Open,
    /// The state where the path ends (the contact limit, or wherever the deployment stopped).
    Limit,
}

impl std::str::FromStr for State {
    type Err = String;

    /// `open`, `limit` or a number t in [0, 1] (checked with the rest of the request).
    fn from_str(text: &str) -> Result<State, String> {
        match text.trim() {
            "open" => Ok(State::Open),
            "limit" => Ok(State::Limit),
            t => t.parse::<Real>().map(State::T).map_err(|_| {
                format!(
                    "t '{}': expected a number in [0, 1], 'open' (the most open state) or \
                     'limit' (where the path ends)",
                    t.chars().take(60).collect::<String>().escape_debug()
                )
            }),
        }
    }
}

/// What patch to make.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchRequest {
    /// Cells along w, 1..=[`MAX_PATCH`].
    pub rows: usize,
    /// Cells along u, 1..=[`MAX_PATCH`].
    pub cols: usize,
    /// Millimetres.
    pub scale: Scale,
    /// The state.
    pub state: State,
    /// Cut width relative to the mean edge length, the deployment's contact setting (see
    /// [`ContactSettings::kerf`]): it decides where contact ends the deployment.
    pub kerf: Real,
    /// States kept in [`Patch::states`] for animated formats, nearest to evenly spaced t,
    /// 2..=[`MAX_PATCH_FRAMES`].
    pub frames: usize,
    /// Write the rectangle's completion to a one-DOF sheet ([`crate::finite::complete`]),
    /// the default, refused when there is none; `false` writes the R×C rectangle as it is
    /// (floppy boundary and all, its DOF named by [`PatchMobility::warning`]).
    pub complete: bool,
    /// Another region instead of the `rows` × `cols` rectangle (cells, or a rectangle, disc
    /// or polygon in mm centred on cell [0, 0], at the edge length of [`Scale::EdgeMm`]):
    /// completed, or written raw, as the rectangle would be.
    pub region: Option<Region>,
}

impl Default for PatchRequest {
    /// 6×6 cells, 20 mm mean edge, closed, default kerf, 11 states, the rectangle's one-DOF
    /// completion.
    fn default() -> Self {
        PatchRequest {
            rows: 6,
            cols: 6,
            scale: Scale::EdgeMm(20.0),
            state: State::T(0.0),
            kerf: ContactSettings::default().kerf,
            frames: 11,
            complete: true,
            region: None,
        }
    }
}

impl PatchRequest {
    /// The scale's name and value in mm.
    pub(super) fn scale_value(&self) -> (&'static str, Real) {
        scale_value(self.scale)
    }

    /// The region the sheet is cut from: [`PatchRequest::region`], or the rectangle.
    pub fn region(&self) -> Region {
        self.region.clone().unwrap_or(Region::Cells {
            rows: self.rows,
            cols: self.cols,
        })
    }

    /// The mean edge length in mm a region in mm is measured with (the rectangle of cells
    /// needs none).
    pub(super) fn region_edge_mm(&self) -> Real {
        match self.scale {
            Scale::EdgeMm(mm) => mm,
            Scale::WidthMm(_) => 1.0,
        }
    }

    /// Checks sizes, scale, state and frame count (the kerf is checked by the deployment;
    /// a region's shape when its tiles are found).
    pub fn validate(&self) -> Result<(), ExportError> {
        let (rows, cols) = match &self.region {
            None => (self.rows, self.cols),
            Some(Region::Cells { rows, cols }) => (*rows, *cols),
            Some(_) => {
                if let Scale::WidthMm(_) = self.scale {
                    return Err(ExportError::RegionNeedsEdge);
                }
                (1, 1)
            }
        };
        if rows == 0 || cols == 0 {
            return Err(ExportError::EmptyPatch { rows, cols });
        }
        if rows > MAX_PATCH || cols > MAX_PATCH {
            return Err(ExportError::PatchTooLarge {
                rows,
                cols,
                max: MAX_PATCH,
            });
        }
        check_scale_state_frames(self.scale, self.state, self.frames)
    }
}

/// The scale's name and value in mm.
pub(super) fn scale_value(scale: Scale) -> (&'static str, Real) {
    match scale {
        Scale::EdgeMm(v) => ("edge length", v),
        Scale::WidthMm(v) => ("patch width", v),
    }
}

/// Checks a scale, a state and a frame count against their limits (every patch request,
/// a design's or a graded sheet's).
pub(super) fn check_scale_state_frames(
    scale: Scale,
    state: State,
    frames: usize,
) -> Result<(), ExportError> {
    let (what, value) = scale_value(scale);
    if !(MIN_SIZE_MM..=MAX_SIZE_MM).contains(&value) {
        return Err(ExportError::BadSize { what, value });
    }
    if let State::T(t) = state {
        if !(0.0..=1.0).contains(&t) {
            return Err(ExportError::StatePastTrajectory { t });
        }
    }
    if !(2..=MAX_PATCH_FRAMES).contains(&frames) {
        return Err(ExportError::FrameCount {
            count: frames,
            max: MAX_PATCH_FRAMES,
        });
    }
    Ok(())
}

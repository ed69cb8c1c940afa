//! Margins: whether a design still works when it is made, not only at its exact shape, and
//! which of its states is the most open one.
//!
//! **Shape tolerance.** No laser or printer holds a shape exactly. A design is made at a
//! shape a little off its stored one, and a *special* design (one DOF only on a sub-manifold
//! of shapes, see [`crate::shape_space`]) moved off that sub-manifold is rigid: it locks
//! early. So the tolerance is measured by deploying, not inferred: the design is deployed at
//! shapes moved by a vertex displacement δ (relative to the mean edge length L) along a fixed
//! quasi-random direction of its shape parameters, both ways, and it *keeps its opening* at δ
//! when both moved shapes reach at least [`KEPT_FRACTION`] of its largest area ratio. The
//! stored tolerance is the largest δ of [`TOLERANCE_LEVELS`] that keeps it (found by
//! bisection over the levels, which assumes that a design that keeps its opening at δ keeps
//! it at every smaller level; the independent check in the tests does not assume it).
//! [`FABRICATION_TOLERANCE`], ±0.05 mm at 20 mm edges, is the level the catalogue calls
//! buildable; a design that loses its opening at the smallest level (10⁻⁶ L) is *special*.
//!
//! Moves stay inside the family's parameters, so every moved shape still tiles the plane: a
//! family without shape parameters has nothing to move (no tolerance, `None`), and cut errors
//! that break the tiling itself are not modelled.
//!
//! A moved shape is deployed only as far as [`PROBE_ARC_FACTOR`] times the arc length at which
//! the design is most open (all of it when that is the path's end): it is most open near
//! there, and the rest of a path that closes again costs time and says nothing.
//!
//! The vertex displacement of a parameter move is that of the prototile's vertices about its
//! centroid (a move that only shifts the tile is no shape error), to first order: a forward
//! difference of step [`RATE_STEP`] in scaled parameters.
//!
//! **Most open state.** Many designs reach their largest area mid-path and close again
//! before contact ends the path: the most open state is the accepted state of largest area
//! ratio (its t), and the state where the path ends has its own area ratio.

use super::settings::CatalogSettings;
use crate::api;
use crate::contact::ContactModel;
use crate::deploy::{deploy_until, step_measures, summarize_steps, DeploySettings, Trajectory};
use crate::error::Result;
use crate::kinematics::Mechanism;
use crate::math::{Real, Vec2};
use crate::shape_space::{halton_point, param_scales};
use crate::tiling::Tiling;
use crate::topology::Design;
use serde::{Deserialize, Serialize};

/// Vertex displacement, relative to the mean edge length, that the catalogue asks a design to
/// keep its opening under: ±0.05 mm at 20 mm edges, a good laser cutter's or printer's
/// positional accuracy.
pub const FABRICATION_TOLERANCE: Real = 2.5e-3;

/// Fraction of its largest area ratio a moved shape must reach to count as keeping the
/// design's opening.
pub const KEPT_FRACTION: Real = 0.95;

/// The vertex displacements (relative to L) at which the tolerance is tried, smallest first.
/// The smallest decides special (lost there) from generic.
pub const TOLERANCE_LEVELS: [Real; 7] =
    [1e-6, 1e-5, 1e-4, 1e-3, FABRICATION_TOLERANCE, 1e-2, 2.5e-2];

/// Step, in scaled parameter coordinates, of the difference that gives the vertex
/// displacement of a parameter move.
pub const RATE_STEP: Real = 1e-6;

/// Index of [`FABRICATION_TOLERANCE`] in [`TOLERANCE_LEVELS`].
const FABRICATION_LEVEL: usize = 4;

/// A design's margins, stored per design.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Margins {
    /// t of the most open state (largest area ratio) among the accepted states; 1 when the
    /// sheet is most open where contact ends it.
    pub open_t: Real,
    /// Area ratio of the state where the path ends (the contact limit or wherever the
    /// deployment stopped).
    pub end_area_ratio: Real,
    /// The largest vertex displacement of [`TOLERANCE_LEVELS`] (relative to L) under which
    /// the design keeps its opening; 0 when it loses it already at the smallest level (a
    /// special design); None when the family has no shape parameters.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape_tolerance: Option<Real>,
    /// At [`FABRICATION_TOLERANCE`]: the smaller largest area ratio of the two moved shapes,
    /// as a fraction of the design's (above 1 when both open further), each measured along its
    /// path up to [`PROBE_ARC_FACTOR`] times the arc length of the design's most open state;
    /// None when the family has no shape parameters.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fabrication_kept: Option<Real>,
}

impl Margins {
    /// True when the shape keeps the design's opening at `tolerance` (relative to L): always
    /// for a family without shape parameters.
    pub fn keeps_at(&self, tolerance: Real) -> bool {
        self.shape_tolerance.is_none_or(|t| t >= tolerance)
    }

    /// True when the design loses its opening at the smallest move (it opens only at its
    /// exact shape).
    pub fn is_special(&self) -> bool {
        self.shape_tolerance == Some(0.0)
    }
}

/// One move of a design's shape: the direction in parameter space and how far along it one
/// unit of vertex displacement (relative to L) goes.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeMove {
    /// Unit direction in scaled parameter coordinates (see [`param_scales`]).
    pub direction: Vec<Real>,
    /// Parameter change (Euclidean norm, parameter units) per unit of relative vertex
    /// displacement along `direction`.
    pub params_per_displacement: Real,
}

impl ShapeMove {
    /// The parameters of `design` moved by vertex displacement `delta` (relative to L),
    /// `sign` ±1.
    pub fn params(&self, design: &Design, delta: Real, sign: Real) -> Vec<Real> {
        let scales = param_scales(design.family);
        let step = sign * delta * self.step_per_displacement(design);
        design
            .params
            .iter()
            .zip(&scales)
            .zip(&self.direction)
            .map(|((p, s), x)| p + step * s * x)
            .collect()
    }

    /// Scaled-coordinate step per unit of relative vertex displacement.
    fn step_per_displacement(&self, design: &Design) -> Real {
        let scales = param_scales(design.family);
        let norm = self
            .direction
            .iter()
            .zip(&scales)
            .map(|(x, s)| (x * s) * (x * s))
            .sum::<Real>()
            .sqrt();
        self.params_per_displacement / norm
    }
}

/// The fixed quasi-random direction of `design`'s shape moves (the same for every design of
/// a family with the same parameter count) and its displacement rate; None for a family
/// without shape parameters or when no move of the tile changes its shape.
pub fn shape_move(design: &Design) -> Result<Option<ShapeMove>> {
    let n = design.params.len();
    if n == 0 {
        return Ok(None);
    }
    // The second Halton point mapped to [-1, 1]^n: the first is (1/2, 1/3, ...), whose first
    // coordinate maps to 0.
    let raw: Vec<Real> = halton_point(1, n).iter().map(|x| 2.0 * x - 1.0).collect();
    let norm = raw.iter().map(|x| x * x).sum::<Real>().sqrt();
    let direction: Vec<Real> = raw.iter().map(|x| x / norm).collect();
    let scales = param_scales(design.family);
    let here = centred(&design.tiling()?);
    let moved: Vec<Real> = design
        .params
        .iter()
        .zip(&scales)
        .zip(&direction)
        .map(|((p, s), x)| p + RATE_STEP * s * x)
        .collect();
    let there = centred(&Tiling::new(design.family, &moved)?);
    let length = mean_edge(&here);
    let largest = here
        .iter()
        .zip(&there)
        .map(|(a, b)| (b - a).norm())
        .fold(0.0, Real::max);
    let displacement = largest / length / RATE_STEP;
    if !(displacement.is_finite() && displacement > 0.0) {
        return Ok(None);
    }
    let param_norm = direction
        .iter()
        .zip(&scales)
        .map(|(x, s)| (x * s) * (x * s))
        .sum::<Real>()
        .sqrt();
    Ok(Some(ShapeMove {
        direction,
        params_per_displacement: param_norm / displacement,
    }))
}

/// The prototile's vertices about their centroid.
fn centred(tiling: &Tiling) -> Vec<Vec2> {
    let v = tiling.prototile();
    let c = v.iter().fold(Vec2::zeros(), |acc, p| acc + p) / v.len() as Real;
    v.iter().map(|p| p - c).collect()
}

/// Mean edge length of a closed polygon.
fn mean_edge(v: &[Vec2]) -> Real {
    let n = v.len();
    (0..n).map(|i| (v[(i + 1) % n] - v[i]).norm()).sum::<Real>() / n as Real
}

/// The largest area ratio of `design` deployed with `settings`; 1 (it does not open) when it
/// cannot be built or deployed at all (a rigid shape is refused by the deployment).
pub fn largest_area_ratio(design: &Design, settings: &DeploySettings) -> Real {
    largest_area_ratio_until(design, settings, None)
}

/// [`largest_area_ratio`] over the path up to arc length `arc_limit` (when given).
fn largest_area_ratio_until(
    design: &Design,
    settings: &DeploySettings,
    arc_limit: Option<Real>,
) -> Real {
    let opened = || -> Result<Real> {
        let cell = design.cell()?;
        let mech = Mechanism::new(&cell, &design.joints)?;
        let contact = ContactModel::new(&mech, settings.contact)?;
        let traj = deploy_until(&mech, &contact, settings, arc_limit, &mut |_| true)?;
        Ok(summarize_steps(&mech, &traj)?.max_area_ratio)
    };
    match opened() {
        Ok(a) if a.is_finite() => a.max(1.0),
        _ => 1.0,
    }
}

/// How far along the path a moved shape is deployed: the nominal path's arc length at its
/// most open state times this (a slightly moved shape is most open near the same arc
/// length), or the whole path when the most open state is its end. A moved shape most open
/// further on is measured short of its largest area ratio: the tolerance errs on the safe
/// side.
pub const PROBE_ARC_FACTOR: Real = 1.25;

/// The smaller largest area ratio of `design` moved by `delta` both ways along `mv`, each
/// deployed up to arc length `arc_limit` (when given).
fn moved_opening(
    design: &Design,
    mv: &ShapeMove,
    delta: Real,
    settings: &DeploySettings,
    arc_limit: Option<Real>,
) -> Real {
    [1.0, -1.0]
        .iter()
        .map(|&sign| {
            let moved = design.at_params(&mv.params(design, delta, sign));
            largest_area_ratio_until(&moved, settings, arc_limit)
        })
        .fold(Real::INFINITY, Real::min)
}

/// The margins of `design` from its deployment `traj` (of `mech`, deployed with `settings`),
/// deploying the moved shapes the tolerance needs with the same settings.
pub(crate) fn margins_of_trajectory(
    design: &Design,
    mech: &Mechanism,
    traj: &Trajectory,
    settings: &DeploySettings,
) -> Result<Margins> {
    let measures = step_measures(mech, traj)?;
    let mut open = 0;
    for (k, m) in measures.iter().enumerate() {
        if m.area_ratio >= measures[open].area_ratio {
            open = k;
        }
    }
    let largest = measures.get(open).map_or(1.0, |m| m.area_ratio);
    let end_area_ratio = measures.last().map_or(1.0, |m| m.area_ratio);
    let (shape_tolerance, fabrication_kept) = match shape_move(design)? {
        None => (None, None),
        Some(mv) => {
            let last = traj.steps.len().saturating_sub(1);
            let arc_limit = (open < last).then(|| PROBE_ARC_FACTOR * traj.steps[open].arc);
            let (tolerance, kept) = tolerance(design, &mv, largest, settings, arc_limit);
            (Some(tolerance), Some(kept))
        }
    };
    Ok(Margins {
        open_t: if measures.is_empty() {
            0.0
        } else {
            traj.t(open)
        },
        end_area_ratio,
        shape_tolerance,
        fabrication_kept,
    })
}

/// The margins of `design` deployed afresh with the catalogue's settings (for rows stored
/// before the catalogue had them, and for `analyze`).
pub fn margins(design: &Design, settings: &CatalogSettings) -> Result<Margins> {
    let request = settings.deploy_request();
    let path = api::deploy_path(design, &request.settings, &mut |_| true)?;
    margins_of_trajectory(design, &path.mechanism, &path.trajectory, &request.settings)
}

/// The shape tolerance (a level of [`TOLERANCE_LEVELS`], 0 when none keeps the opening) and
/// the fraction kept at [`FABRICATION_TOLERANCE`].
fn tolerance(
    design: &Design,
    mv: &ShapeMove,
    largest: Real,
    settings: &DeploySettings,
    arc_limit: Option<Real>,
) -> (Real, Real) {
    let kept_at = |level: usize| {
        moved_opening(design, mv, TOLERANCE_LEVELS[level], settings, arc_limit) / largest
    };
    let top = TOLERANCE_LEVELS.len() - 1;
    let kept = kept_at(FABRICATION_LEVEL);
    // Bisection over the levels from the fabrication level: `good` keeps the opening (or is
    // none), `bad` loses it (or is past the last level). Lost at the fabrication level, the
    // smallest level is tried next (special or not); kept, the largest.
    let (mut good, mut bad) = if kept >= KEPT_FRACTION {
        (Some(FABRICATION_LEVEL), TOLERANCE_LEVELS.len())
    } else {
        (None, FABRICATION_LEVEL)
    };
    loop {
        let probe = match (good, bad) {
            (None, 0) => break,
            (Some(g), b) if b - g <= 1 => break,
            (None, FABRICATION_LEVEL) => 0,
            (Some(FABRICATION_LEVEL), b) if b == TOLERANCE_LEVELS.len() => top,
            (None, b) => b / 2,
            (Some(g), b) => (g + b) / 2,
        };
        if kept_at(probe) >= KEPT_FRACTION {
            good = Some(probe);
        } else {
            bad = probe;
        }
    }
    (good.map_or(0.0, |g| TOLERANCE_LEVELS[g]), kept)
}

/// A design's margins with what a user needs to read them: its largest area ratio, and for a
/// special design the first-order shape constraints it opens on and how far a shape moved
/// off them by the smallest level opens.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MarginsReport {
    /// The design's spec.
    pub design: String,
    /// The margins, as the catalogue stores them.
    pub margins: Margins,
    /// The design's largest area ratio.
    pub max_area_ratio: Real,
    /// Parameter change (Euclidean norm) per unit of relative vertex displacement along the
    /// direction the tolerance was measured in; None for a family without shape parameters.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub params_per_displacement: Option<Real>,
    /// For a special design: the largest area ratio of a shape moved by the smallest level
    /// (10⁻⁶ L) both ways (the smaller).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub opening_off_shape: Option<Real>,
    /// For a special design: its first-order shape constraints, unit normals n in parameter
    /// space (a shape change δp keeps one DOF to first order when n·δp = 0 for every n).
    pub constraints: Vec<Vec<Real>>,
    /// The catalogue's finite 6×6-cell patch (raw DOF, and the fraction its completion to a
    /// one-DOF sheet keeps, none when it has no such sheet), as the catalogue stores it; None
    /// when it could not be counted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub finite: Option<super::finite::FiniteFigures>,
}

/// The margins of `design` (deployed afresh with `settings`) and what explains them (see
/// [`MarginsReport`]).
pub fn margins_report(design: &Design, settings: &CatalogSettings) -> Result<MarginsReport> {
    let request = settings.deploy_request();
    let path = api::deploy_path(design, &request.settings, &mut |_| true)?;
    margins_report_of_trajectory(design, &path.mechanism, &path.trajectory, settings)
}

/// [`margins_report`] from a deployment already made with `settings`' deploy request (`traj`
/// of `mech`): what `deploy` reports after its own run, without deploying the design again.
pub fn margins_report_of_trajectory(
    design: &Design,
    mech: &Mechanism,
    traj: &Trajectory,
    settings: &CatalogSettings,
) -> Result<MarginsReport> {
    let request = settings.deploy_request();
    let margins = margins_of_trajectory(design, mech, traj, &request.settings)?;
    let max_area_ratio = summarize_steps(mech, traj)?.max_area_ratio;
    let mv = shape_move(design)?;
    let (opening_off_shape, constraints) = match (&mv, margins.is_special()) {
        (Some(mv), true) => {
            let off = moved_opening(design, mv, TOLERANCE_LEVELS[0], &request.settings, None);
            let shape = crate::shape_space::ShapeSettings {
                mobility: request.settings.mobility,
                ..Default::default()
            };
            let constraints = crate::shape_space::classify(design, &shape)
                .map(|c| c.constraints)
                .unwrap_or_default();
            (Some(off), constraints)
        }
        _ => (None, Vec::new()),
    };
    let cell = design.cell()?;
    let finite = super::finite::figures_of_trajectory(design, &cell, mech, traj, settings).ok();
    Ok(MarginsReport {
        design: design.to_string(),
        margins,
        max_area_ratio,
        params_per_displacement: mv.map(|m| m.params_per_displacement),
        opening_off_shape,
        constraints,
        finite,
    })
}

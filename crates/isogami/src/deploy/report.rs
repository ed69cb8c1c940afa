//! The serialisable summary of a deployment: what `isogami deploy --json` prints and what the
//! design database will store. Physical lengths (tile positions, u, w) are in the tiling's
//! units; F, U and expansions are dimensionless.

use super::error::{DeployError, ReportField};
use super::frames::FrameRecord;
use super::settings::{DeploySettings, Method};
use super::summary::{poisson_range, summarize_steps};
use super::trajectory::{EndReason, Trajectory};
use crate::kinematics::Mechanism;
use crate::math::Real;
use crate::measure::{BehaviourClass, BehaviourFigures, FrameMeasures};
use serde::{Deserialize, Deserializer, Serialize};

/// Pose of one tile in a frame.
#[derive(Debug, Clone, Copy, Serialize, serde::Deserialize)]
pub struct TilePose {
    /// Centroid x (tiling units).
    pub x: Real,
    /// Centroid y (tiling units).
    pub y: Real,
    /// Rotation from the closed state (radians; tile 0 is held fixed).
    pub theta: Real,
}

/// One frame of the report.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct FrameReport {
    /// Raw step index.
    pub step: usize,
    /// Normalised arc length.
    #[serde(rename = "t")]
    pub t: Real,
    /// Deformation gradient, rows.
    #[serde(rename = "F")]
    pub f: [[Real; 2]; 2],
    /// Tiling vector u (tiling units).
    pub u: [Real; 2],
    /// Tiling vector w (tiling units).
    pub w: [Real; 2],
    /// Tile poses.
    pub tiles: Vec<TilePose>,
    /// All expansion measures.
    pub measures: FrameMeasures,
    /// Largest joint residual relative to the mean edge length.
    pub joint_residual: Real,
    /// Smallest clearance between collision polygons, relative to the mean edge length.
    pub min_clearance: Real,
    /// True for a state inserted between accepted steps `step` and `step + 1` because more
    /// frames were asked for than the trajectory has states: projected onto the joint
    /// constraints and checked like every frame, but not one of the solver's states (summaries
    /// never include it). Absent from the JSON when false.
    #[serde(default, skip_serializing_if = "is_false")]
    pub inserted: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// Summary of the whole trajectory.
///
/// Every summary measure (joint residual, clearance, expansions, area ratio, tile rotation,
/// behaviour class, Poisson-like range) is taken over all accepted states of the trajectory,
/// never over the frames: the same deployment reports bit-identical summaries whatever frames
/// were asked for.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct DeploymentReport {
    /// Design spec string.
    pub design: String,
    /// Method.
    pub method: Method,
    /// Kerf relative to the mean edge length.
    pub kerf: Real,
    /// Mean edge length L (tiling units).
    pub length_scale: Real,
    /// Degrees of freedom of the closed state. 1 for a self-deployable sheet; with several the
    /// path follows the fastest-opening first-order motion (one of a family of paths).
    pub dof: usize,
    /// Why the deployment ended.
    pub end_reason: EndReason,
    /// States of the trajectory, the closed state included (accepted steps + 1).
    pub steps: usize,
    /// Attempted steps, accepted or not, both opening signs together.
    pub attempts: usize,
    /// Arc length of the path (non-dimensional).
    pub arc_length: Real,
    /// Largest joint residual over every accepted state (relative to L).
    pub max_joint_residual: Real,
    /// Smallest clearance over every accepted state (relative to L).
    pub min_clearance: Real,
    /// Behaviour class over every accepted state (None when the sheet does not expand),
    /// decided on the states the Poisson-like range is taken over (see
    /// [`crate::measure::classify_expansions`]).
    pub behaviour: Option<BehaviourClass>,
    /// True when the design lies at a class boundary: its figures are within
    /// [`ClassifyTolerances::boundary`](crate::measure::ClassifyTolerances::boundary) of a
    /// threshold, and a small change of its shape can change its class. Reports written before
    /// this field existed read false.
    #[serde(default)]
    pub behaviour_boundary: bool,
    /// The figures the class was decided on (spread, contraction, margin, the class across the
    /// nearest threshold); absent when there is no class, and in reports written before this
    /// field existed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub behaviour_figures: Option<BehaviourFigures>,
    /// Largest principal expansion reached (over every accepted state).
    pub max_expansion: Real,
    /// Smallest principal expansion reached (over every accepted state).
    pub min_expansion: Real,
    /// Largest area ratio reached (over every accepted state).
    pub max_area_ratio: Real,
    /// Largest tile rotation reached (radians, over every accepted state).
    pub max_tile_rotation: Real,
    /// The Poisson-like range over every accepted state, `[min, max]`, or null when no state
    /// has opened; read it with [`DeploymentReport::poisson_range`]. Reports written before
    /// this field existed lack it (`None` here), and their range is then taken over their
    /// frames, as it was when they were written.
    #[serde(
        rename = "poisson_range",
        default,
        deserialize_with = "present",
        skip_serializing_if = "Option::is_none"
    )]
    pub(crate) poisson: Option<Option<[Real; 2]>>,
    /// The frames: exactly the number asked for, increasing in t, the closed state first and
    /// the final state last (one frame when the trajectory has one state).
    pub frames: Vec<FrameReport>,
}

/// A field that is present reads as `Some`, even when it is null (`Some(None)`); an absent
/// one gets the default `None`.
fn present<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Option<[Real; 2]>>, D::Error> {
    Option::<[Real; 2]>::deserialize(d).map(Some)
}

/// A frame record as the report gives it (lengths in the design's units, not in L).
pub fn frame_report(mech: &Mechanism, f: &FrameRecord) -> FrameReport {
    let l = mech.length_scale;
    let (u, w) = mech.lattice(&f.q);
    FrameReport {
        step: f.step,
        t: f.t,
        f: f.measures.f,
        u: [u.x * l, u.y * l],
        w: [w.x * l, w.y * l],
        tiles: (0..mech.tile_count())
            .map(|i| {
                let (p, th) = mech.pose(&f.q, i);
                TilePose {
                    x: p.x * l,
                    y: p.y * l,
                    theta: th,
                }
            })
            .collect(),
        measures: f.measures.clone(),
        joint_residual: f.joint_residual,
        min_clearance: f.min_clearance,
        inserted: f.inserted,
    }
}

/// Builds the report from checked frame records; the summaries come from every accepted state
/// of `traj` ([`summarize_steps`]), so they do not depend on which frames were picked. Fails
/// only when a state cannot be measured.
pub fn build_report(
    design: &str,
    mech: &Mechanism,
    settings: &DeploySettings,
    traj: &Trajectory,
    frames: &[FrameRecord],
) -> Result<DeploymentReport, DeployError> {
    let l = mech.length_scale;
    let summary = summarize_steps(mech, traj)?;
    let frame_reports = frames.iter().map(|f| frame_report(mech, f)).collect();
    Ok(DeploymentReport {
        design: design.to_string(),
        method: settings.method,
        kerf: settings.contact.kerf,
        length_scale: l,
        dof: traj.dof,
        end_reason: traj.end_reason.clone(),
        steps: traj.steps.len(),
        attempts: traj.attempts,
        arc_length: traj.total_arc(),
        max_joint_residual: summary.max_joint_residual,
        min_clearance: summary.min_clearance,
        behaviour: summary.behaviour,
        behaviour_boundary: summary.behaviour_boundary,
        behaviour_figures: summary.behaviour_figures,
        max_expansion: summary.max_expansion,
        min_expansion: summary.min_expansion,
        max_area_ratio: summary.max_area_ratio,
        max_tile_rotation: summary.max_tile_rotation,
        poisson: Some(summary.poisson_range.map(|(lo, hi)| [lo, hi])),
        frames: frame_reports,
    })
}

impl DeploymentReport {
    /// Smallest and largest Poisson-like ratio −ε_min/ε_max over the accepted states that have
    /// opened (largest principal expansion at least
    /// [`POISSON_OPEN_FRACTION`](super::POISSON_OPEN_FRACTION) of the largest one reached);
    /// None when none has. −1 is isotropic opening, 0 opening along one axis with the other
    /// fixed, positive values shrinking across the opening direction. A report read back from
    /// before the range was stored gives the range over its frames.
    pub fn poisson_range(&self) -> Option<(Real, Real)> {
        match self.poisson {
            Some(range) => range.map(|[lo, hi]| (lo, hi)),
            None => poisson_range(
                self.frames
                    .iter()
                    .map(|f| (f.measures.min_expansion, f.measures.max_expansion)),
                self.max_expansion,
            ),
        }
    }

    /// Checks that every number of the report is finite (a report with NaN or ∞ must never
    /// reach a front end); the error names the first offending field.
    pub fn check_finite(&self) -> Result<(), DeployError> {
        let scalars = [
            ("kerf", self.kerf),
            ("length_scale", self.length_scale),
            ("arc_length", self.arc_length),
            ("max_joint_residual", self.max_joint_residual),
            ("min_clearance", self.min_clearance),
            ("max_expansion", self.max_expansion),
            ("min_expansion", self.min_expansion),
            ("max_area_ratio", self.max_area_ratio),
            ("max_tile_rotation", self.max_tile_rotation),
        ];
        let poisson = self.poisson_range().map_or([0.0; 2], |(lo, hi)| [lo, hi]);
        first_non_finite(
            scalars
                .iter()
                .copied()
                .chain(poisson.map(|v| ("poisson_range", v)))
                .map(|(name, v)| (ReportField { frame: None, name }, v)),
        )?;
        for (k, f) in self.frames.iter().enumerate() {
            let m = &f.measures;
            let mut values: Vec<(&str, Real)> = vec![
                ("t", f.t),
                ("joint_residual", f.joint_residual),
                ("min_clearance", f.min_clearance),
                ("lattice_rotation", m.lattice_rotation),
                ("min_expansion", m.min_expansion),
                ("max_expansion", m.max_expansion),
                ("principal_angle", m.principal_angle),
                ("area_ratio", m.area_ratio),
                ("max_tile_rotation", m.max_tile_rotation),
            ];
            values.extend(f.f.iter().flatten().map(|&v| ("F", v)));
            values.extend(m.u.iter().flatten().map(|&v| ("U", v)));
            values.extend(f.u.iter().chain(&f.w).map(|&v| ("u/w", v)));
            values.extend(m.tile_rotations.iter().map(|&v| ("tile_rotations", v)));
            values.extend(
                f.tiles
                    .iter()
                    .flat_map(|p| [("tiles", p.x), ("tiles", p.y), ("tiles", p.theta)]),
            );
            first_non_finite(values.into_iter().map(|(name, v)| {
                let field = ReportField {
                    frame: Some(k),
                    name,
                };
                (field, v)
            }))?;
        }
        Ok(())
    }
}

fn first_non_finite(values: impl Iterator<Item = (ReportField, Real)>) -> Result<(), DeployError> {
    for (field, value) in values {
        if !value.is_finite() {
            return Err(DeployError::ReportNotFinite { field, value });
        }
    }
    Ok(())
}

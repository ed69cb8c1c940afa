//! The serialisable summary of a deployment: what `isogami deploy --json` prints and what the
//! design database will store. Physical lengths (tile positions, u, w) are in the tiling's
//! units; F, U and expansions are dimensionless.

use super::error::{DeployError, ReportField};
use super::frames::FrameRecord;
use super::settings::{DeploySettings, Method};
use super::trajectory::{EndReason, Trajectory};
use crate::kinematics::Mechanism;
use crate::math::Real;
use crate::measure::{classify, BehaviourClass, FrameMeasures};
use serde::Serialize;

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
}

/// Summary of the whole trajectory.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
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
    /// Behaviour class over the frames (None when the sheet does not expand).
    pub behaviour: Option<BehaviourClass>,
    /// Largest principal expansion reached.
    pub max_expansion: Real,
    /// Smallest principal expansion reached.
    pub min_expansion: Real,
    /// Largest area ratio reached.
    pub max_area_ratio: Real,
    /// Largest tile rotation reached (radians).
    pub max_tile_rotation: Real,
    /// The frames.
    pub frames: Vec<FrameReport>,
}

/// Frames count as open for the Poisson-like ratio when their largest principal expansion
/// reaches this fraction of the largest one of the whole deployment: below it both
/// expansions are so small that their ratio is dominated by solver noise.
pub const POISSON_OPEN_FRACTION: Real = 0.05;

/// Builds the report from checked frame records.
pub fn build_report(
    design: &str,
    mech: &Mechanism,
    settings: &DeploySettings,
    traj: &Trajectory,
    frames: &[FrameRecord],
) -> DeploymentReport {
    let l = mech.length_scale;
    let measures: Vec<FrameMeasures> = frames.iter().map(|f| f.measures.clone()).collect();
    let fold = |init: Real, pick: &dyn Fn(&FrameMeasures) -> Real, max: bool| {
        measures
            .iter()
            .map(pick)
            .fold(init, |a, b| if max { a.max(b) } else { a.min(b) })
    };
    let frame_reports = frames
        .iter()
        .map(|f| {
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
            }
        })
        .collect();
    DeploymentReport {
        design: design.to_string(),
        method: settings.method,
        kerf: settings.contact.kerf,
        length_scale: l,
        dof: traj.dof,
        end_reason: traj.end_reason.clone(),
        steps: traj.steps.len(),
        attempts: traj.attempts,
        arc_length: traj.total_arc(),
        max_joint_residual: traj.max_joint_residual(),
        min_clearance: traj.min_clearance(),
        behaviour: classify(&measures),
        max_expansion: fold(Real::NEG_INFINITY, &|m| m.max_expansion, true),
        min_expansion: fold(Real::INFINITY, &|m| m.min_expansion, false),
        max_area_ratio: fold(Real::NEG_INFINITY, &|m| m.area_ratio, true),
        max_tile_rotation: fold(0.0, &|m| m.max_tile_rotation, true),
        frames: frame_reports,
    }
}

impl DeploymentReport {
    /// Smallest and largest Poisson-like ratio −ε_min/ε_max over the frames that have opened
    /// (largest principal expansion at least [`POISSON_OPEN_FRACTION`] of the largest one
    /// reached); None when no frame has. −1 is isotropic opening, 0 opening along one axis
    /// with the other fixed, positive values shrinking across the opening direction.
    pub fn poisson_range(&self) -> Option<(Real, Real)> {
        if self.max_expansion.is_nan() || self.max_expansion <= 0.0 {
            return None;
        }
        let open = POISSON_OPEN_FRACTION * self.max_expansion;
        self.frames
            .iter()
            .filter(|f| f.measures.max_expansion >= open)
            .filter_map(|f| {
                crate::measure::effective_poisson_ratio(
                    f.measures.min_expansion,
                    f.measures.max_expansion,
                )
            })
            .fold(None, |acc, r| match acc {
                None => Some((r, r)),
                Some((lo, hi)) => Some((Real::min(lo, r), Real::max(hi, r))),
            })
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
        first_non_finite(
            scalars
                .iter()
                .map(|&(name, v)| (ReportField { frame: None, name }, v)),
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

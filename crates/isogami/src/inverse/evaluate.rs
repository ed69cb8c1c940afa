//! One evaluation: is this design (at this kerf) valid for the target, and how good is it?
//!
//! Valid means, in this order (cheap checks first):
//! 1. the static constraints: family, supercell, tile count, kerf ≥ the minimum;
//! 2. well-shaped tiles: the shape parameters give a valid tiling
//!    ([`Tiling::new`](crate::tiling::Tiling::new)) whose prototile passes the exploration's
//!    shape-quality rule ([`shape_quality_problem`]), and the cell builds with the joints;
//! 3. the catalogue's admission rule ([`crate::catalog::assess`]): mobility exactly 1, not
//!    locked at the start, largest principal expansion past the threshold — deployed through
//!    [`crate::api::deploy`], so every frame is checked (joints closed, no overlap, finite);
//! 4. the deployed constraints: rotation margin and hinge clearance (see
//!    [`Constraints`](super::Constraints));
//! 5. every goal can be scored ([`super::objective`]).
//!
//! A design that fails any of these is [`Outcome::Invalid`] with the reason; only a stop
//! requested by the caller is an error.

use super::objective::{score, Score, Unmet};
use super::target::Target;
use crate::catalog::{assess, Assessment, CatalogSettings, Rejection};
use crate::contact::{ContactSettings, MAX_KERF};
use crate::deploy::DeploymentReport;
use crate::export::laser::{laser_sheet, LaserSettings};
use crate::export::{patch_at_with, PatchRequest, Scale, State};
use crate::math::Real;
use crate::tiling::{shape_quality_problem, Tiling};
use crate::topology::Design;
use serde::Serialize;
use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};

/// Why a design is not valid for a target.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Invalidity {
    /// Its family, cell or tile count is excluded by the constraints.
    Excluded {
        /// Which constraint.
        what: &'static str,
    },
    /// The kerf lies outside [min kerf, max kerf].
    Kerf {
        /// The kerf.
        kerf: Real,
        /// Smallest allowed.
        min: Real,
        /// Largest allowed.
        max: Real,
    },
    /// The shape parameters give no valid or no well-shaped tile.
    Shape {
        /// What is wrong.
        problem: String,
    },
    /// The cell does not build with the design's joints.
    Build {
        /// What is wrong.
        problem: String,
    },
    /// The catalogue's rule refuses it (mobility, locked, threshold).
    Rejected {
        /// Why.
        rejection: Rejection,
    },
    /// Analysis or deployment failed.
    Failed {
        /// The error.
        problem: String,
    },
    /// The tiles do not turn by the rotation margin.
    Rotation {
        /// Largest tile rotation reached, degrees.
        reached_deg: Real,
        /// Required, degrees.
        min_deg: Real,
    },
    /// The hinge bridge does not fit.
    Hinge {
        /// The export's message.
        problem: String,
    },
    /// A goal cannot be scored.
    Unmet {
        /// Why.
        unmet: Unmet,
    },
}

impl fmt::Display for Invalidity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Invalidity::Excluded { what } => write!(f, "excluded by the {what} constraint"),
            Invalidity::Kerf { kerf, min, max } => {
                write!(f, "kerf {kerf} outside [{min}, {max}]")
            }
            Invalidity::Shape { problem } => write!(f, "tile shape: {problem}"),
            Invalidity::Build { problem } => write!(f, "cell: {problem}"),
            Invalidity::Rejected { rejection } => write!(f, "{rejection}"),
            Invalidity::Failed { problem } => write!(f, "{problem}"),
            Invalidity::Rotation {
                reached_deg,
                min_deg,
            } => write!(
                f,
                "tiles turn by {reached_deg:.2}° at most, the rotation margin is {min_deg}°"
            ),
            Invalidity::Hinge { problem } => write!(f, "hinge clearance: {problem}"),
            Invalidity::Unmet { unmet } => write!(f, "{unmet}"),
        }
    }
}

/// How an evaluation came out.
#[derive(Debug, Clone)]
pub enum Outcome {
    /// Valid, with its score and deployment report.
    Valid {
        /// The objective and goal values.
        score: Score,
        /// The deployment it was scored on.
        report: Box<DeploymentReport>,
    },
    /// Not valid.
    Invalid(Invalidity),
}

/// One design at one kerf, evaluated.
#[derive(Debug, Clone)]
pub struct Evaluation {
    /// The design.
    pub design: Design,
    /// Kerf it was deployed with (units of L).
    pub kerf: Real,
    /// The outcome.
    pub outcome: Outcome,
}

impl Evaluation {
    /// The objective, if valid.
    pub fn objective(&self) -> Option<Real> {
        match &self.outcome {
            Outcome::Valid { score, .. } => Some(score.objective),
            Outcome::Invalid(_) => None,
        }
    }

    /// True when valid.
    pub fn is_valid(&self) -> bool {
        matches!(self.outcome, Outcome::Valid { .. })
    }
}

/// The caller asked to stop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stopped;

/// Evaluates designs for one target with fixed catalogue settings (threshold, frames,
/// deployment settings; the kerf is set per evaluation).
#[derive(Debug, Clone)]
pub struct Evaluator<'a> {
    /// The target.
    pub target: &'a Target,
    /// Catalogue settings the admission rule and the deployment use.
    pub settings: CatalogSettings,
}

/// Smallest kerf the constraints allow, never below the contact model's.
pub(crate) fn min_kerf(target: &Target) -> Real {
    target
        .constraints
        .min_kerf
        .unwrap_or(crate::contact::MIN_KERF)
}

impl Evaluator<'_> {
    /// Evaluates `design` deployed with `kerf`. Checks `stop` between stages and during the
    /// deployment; a set flag gives `Err(Stopped)`.
    pub fn evaluate(
        &self,
        design: &Design,
        kerf: Real,
        stop: &AtomicBool,
    ) -> Result<Evaluation, Stopped> {
        let outcome = self.outcome(design, kerf, stop)?;
        Ok(Evaluation {
            design: design.clone(),
            kerf,
            outcome,
        })
    }

    fn outcome(&self, design: &Design, kerf: Real, stop: &AtomicBool) -> Result<Outcome, Stopped> {
        let invalid = |i: Invalidity| Ok(Outcome::Invalid(i));
        let c = &self.target.constraints;
        if stop.load(Ordering::Relaxed) {
            return Err(Stopped);
        }
        let tiles = design.family.info().aspect_count
            * usize::from(design.dims.a())
            * usize::from(design.dims.b());
        if !c.admits_cell(design.family, design.dims, tiles) {
            let what = if !c.families.is_empty() && !c.families.contains(&design.family) {
                "family"
            } else if !c.cells.is_empty() && !c.cells.contains(&design.dims) {
                "cell"
            } else {
                "tile count"
            };
            return invalid(Invalidity::Excluded { what });
        }
        let lo = min_kerf(self.target);
        if !(kerf.is_finite() && kerf >= lo && kerf <= MAX_KERF) {
            return invalid(Invalidity::Kerf {
                kerf,
                min: lo,
                max: MAX_KERF,
            });
        }
        let tiling = match Tiling::new(design.family, &design.params) {
            Ok(t) => t,
            Err(e) => {
                return invalid(Invalidity::Shape {
                    problem: e.to_string(),
                })
            }
        };
        if let Some(problem) = shape_quality_problem(tiling.prototile()) {
            return invalid(Invalidity::Shape { problem });
        }
        if let Err(e) = design.cell() {
            return invalid(Invalidity::Build {
                problem: e.to_string(),
            });
        }
        let mut settings = self.settings;
        settings.deploy.contact = ContactSettings {
            kerf,
            dhat: 0.5 * kerf,
            ..settings.deploy.contact
        };
        let report = match assess(design, &settings, &mut |_| !stop.load(Ordering::Relaxed)) {
            Ok(Assessment::Admitted(report)) => report,
            Ok(Assessment::Rejected(rejection)) => {
                return invalid(Invalidity::Rejected { rejection })
            }
            Err(e) if e.is_cancelled() => return Err(Stopped),
            Err(e) => {
                return invalid(Invalidity::Failed {
                    problem: e.to_string(),
                })
            }
        };
        if let Some(min_deg) = c.min_rotation_deg {
            let reached_deg = report.max_tile_rotation.to_degrees();
            if reached_deg < min_deg {
                return invalid(Invalidity::Rotation {
                    reached_deg,
                    min_deg,
                });
            }
        }
        let score = match score(self.target, &report) {
            Ok(s) => s,
            Err(unmet) => return invalid(Invalidity::Unmet { unmet }),
        };
        if let Some(hinge) = c.min_hinge {
            if let Some(problem) = hinge_problem(design, hinge, kerf, stop)? {
                return invalid(Invalidity::Hinge { problem });
            }
        }
        Ok(Outcome::Valid { score, report })
    }
}

/// Why a laser bridge of `hinge` (units of L) does not fit at every joint of a closed 2×2
/// patch cut with `kerf`, if it does not (see [`Constraints`](super::Constraints)).
pub fn hinge_problem(
    design: &Design,
    hinge: Real,
    kerf: Real,
    stop: &AtomicBool,
) -> Result<Option<String>, Stopped> {
    let request = PatchRequest {
        rows: 2,
        cols: 2,
        scale: Scale::EdgeMm(1.0),
        state: State::T(0.0),
        kerf,
        frames: 2,
        // Every joint of the design's cell, as the periodic sheet has them.
        complete: false,
        region: None,
    };
    let patch = match patch_at_with(design, &request, &mut |_| !stop.load(Ordering::Relaxed)) {
        Ok(p) => p,
        Err(crate::export::ExportError::Library(e)) if e.is_cancelled() => return Err(Stopped),
        Err(e) => return Ok(Some(e.to_string())),
    };
    let settings = LaserSettings {
        hinge_mm: hinge,
        kerf_mm: kerf,
        ..LaserSettings::default()
    };
    Ok(laser_sheet(&patch, settings).err().map(|e| e.to_string()))
}

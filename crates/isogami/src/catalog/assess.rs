//! The catalogue's admission rule for one design, public so that every stage that must decide
//! "is this a working design?" (the exploration's deploy-and-threshold and shape stages, the
//! inverse design's screening and refinement) decides it the same way.
//!
//! A design is admitted when it is a one-degree-of-freedom mechanism in its closed state
//! (mobility analysis with the catalogue's tolerance), it is not locked at the start (contact
//! does not block both opening directions, and at least one step is accepted), and its
//! largest principal expansion over the deployment reaches the threshold.

use super::settings::CatalogSettings;
use crate::api::{self, Deployment};
use crate::deploy::{DeploymentReport, EndReason};
use crate::error::Result;
use crate::math::Real;
use crate::topology::Design;
use serde::Serialize;
use std::fmt;

/// Why a design that builds is not admitted.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Rejection {
    /// The closed state does not have exactly one degree of freedom.
    Mobility {
        /// Degrees of freedom found.
        dof: usize,
    },
    /// Contact blocks the opening at once (or no step is accepted).
    Locked,
    /// The sheet does not expand enough.
    BelowThreshold {
        /// Largest principal expansion reached.
        max_expansion: Real,
        /// The threshold.
        threshold: Real,
    },
}

impl fmt::Display for Rejection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rejection::Mobility { dof } => {
                write!(f, "{dof} degrees of freedom in the closed state (needs 1)")
            }
            Rejection::Locked => f.write_str("locked by contact at the start"),
            Rejection::BelowThreshold {
                max_expansion,
                threshold,
            } => write!(
                f,
                "largest principal expansion {max_expansion:.4} is below the threshold {threshold}"
            ),
        }
    }
}

/// The verdict on one design.
#[derive(Debug, Clone)]
pub enum Assessment {
    /// Admitted, with its deployment report.
    Admitted(Box<DeploymentReport>),
    /// Not admitted.
    Rejected(Rejection),
}

/// Decides whether `design` is admitted under `settings` (see the module documentation),
/// deploying it with the catalogue's request. `progress` is the deployment's callback
/// (return `false` to cancel). Errors are those of building, analysing or deploying the
/// design; a design that builds but does not work is [`Assessment::Rejected`].
pub fn assess(
    design: &Design,
    settings: &CatalogSettings,
    progress: crate::deploy::Progress<'_>,
) -> Result<Assessment> {
    Ok(match admit(design, settings, progress)? {
        Admission::Admitted(run) => Assessment::Admitted(Box::new(run.report)),
        Admission::Rejected(r) => Assessment::Rejected(r),
    })
}

/// [`assess`] keeping the whole deployment of an admitted design (its mechanism and
/// trajectory), for the stages that measure more from it.
pub(crate) enum Admission {
    /// Admitted, with its deployment.
    Admitted(Box<Deployment>),
    /// Not admitted.
    Rejected(Rejection),
}

/// [`assess`] with the admitted design's deployment.
pub(crate) fn admit(
    design: &Design,
    settings: &CatalogSettings,
    progress: crate::deploy::Progress<'_>,
) -> Result<Admission> {
    let dof = api::analyze(design, settings.topology.mobility)?
        .mobility
        .dof;
    if dof != 1 {
        return Ok(Admission::Rejected(Rejection::Mobility { dof }));
    }
    // Judged on the trajectory's summaries (which the report repeats), so that the frames —
    // states inserted into short trajectories cost more than the trajectory — are made only
    // for admitted designs.
    let request = settings.deploy_request();
    let path = api::deploy_path(design, &request.settings, progress)?;
    if matches!(path.trajectory.end_reason, EndReason::Locked) || path.trajectory.steps.len() < 2 {
        return Ok(Admission::Rejected(Rejection::Locked));
    }
    let max_expansion = path.summary()?.max_expansion;
    if max_expansion.is_nan() || max_expansion < settings.threshold {
        return Ok(Admission::Rejected(Rejection::BelowThreshold {
            max_expansion,
            threshold: settings.threshold,
        }));
    }
    let run = path.into_deployment(design, request.frames)?;
    Ok(Admission::Admitted(Box::new(run)))
}

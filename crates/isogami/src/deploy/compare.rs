//! The baseline comparison of paper §5 / Fig. 4: how far each method gets on the same design,
//! as a fraction of the rigid-modes trajectory up to its contact limit.

use super::settings::{DeploySettings, Method};
use super::trajectory::{EndReason, Trajectory};
use crate::error::Result;
use crate::kinematics::Mechanism;
use crate::math::Real;
use serde::Serialize;

/// One method's result on a design.
#[derive(Debug, Clone, Serialize)]
pub struct MethodResult {
    /// The method.
    pub method: Method,
    /// Final t measured along the rigid-modes trajectory (1 = its end).
    pub final_t: Real,
    /// Why the method stopped.
    pub end_reason: EndReason,
    /// Accepted states.
    pub steps: usize,
    /// Wall time in milliseconds.
    pub millis: Real,
}

/// Where a state lies along a reference trajectory: the t of the nearest reference state.
fn t_along(reference: &Trajectory, q: &crate::math::DVec) -> Real {
    let k = (0..reference.steps.len())
        .min_by(|&a, &b| {
            let da = (&reference.steps[a].q - q).norm();
            let db = (&reference.steps[b].q - q).norm();
            da.total_cmp(&db)
        })
        .unwrap_or(0);
    reference.t(k)
}

/// Runs rigid modes, NCM and springs on `mech` with otherwise equal settings.
pub fn compare_methods(mech: &Mechanism, settings: &DeploySettings) -> Result<Vec<MethodResult>> {
    let mut out = Vec::new();
    let mut reference: Option<Trajectory> = None;
    for method in [Method::RigidModes, Method::Ncm, Method::Springs] {
        let s = DeploySettings {
            method,
            ..*settings
        };
        let start = std::time::Instant::now();
        let traj = super::deploy(mech, &s, &mut |_| true)?;
        let millis = start.elapsed().as_secs_f64() * 1e3;
        let reference = reference.get_or_insert_with(|| traj.clone());
        let last = &traj.steps.last().expect("at least the closed state").q;
        out.push(MethodResult {
            method,
            final_t: t_along(reference, last),
            end_reason: traj.end_reason.clone(),
            steps: traj.steps.len(),
            millis,
        });
    }
    Ok(out)
}

//! A state between two accepted states of a trajectory, for frame counts above the number of
//! states: a point of the chord between them, projected back onto the joint constraints.
//!
//! The projection is Gauss–Newton with the minimum-norm correction δ = −J⁺c (tile 0 held
//! fixed, J⁺ the pseudo-inverse over the eigenvalues of JᵀJ above the mobility threshold).
//! The correction lies in the row space of J, orthogonal to the first-order motions, so the
//! projected state stays, to first order, at the chord point's place along the path; this is
//! why its t is the chord point's. It needs only the constraints, not a method's step
//! (springs' load steps and NCM's fixed direction would each need their own sub-step), and
//! it is cheap: a few eigen-decompositions of a matrix the size of the state. The result is
//! not trusted: the caller checks it like every frame (joints, exact overlap test).

use super::error::InsertProblem;
use super::settings::DeploySettings;
use super::trajectory::Trajectory;
use crate::kinematics::Mechanism;
use crate::math::{symmetric_eigen, DVec, Real};

/// Gauss–Newton iterations allowed; from a chord point the residual falls quadratically, so a
/// handful suffice and more means the correction is not converging.
pub const PROJECTION_MAX_ITER: usize = 20;

/// The state `fraction` ∈ (0, 1) of the way from accepted state `step` to `step + 1`,
/// projected onto the joint constraints to `settings.joint_tolerance` (the tolerance of an
/// accepted step). Tile 0 keeps its pose, as in every state of the trajectory.
pub fn project_between(
    mech: &Mechanism,
    traj: &Trajectory,
    step: usize,
    fraction: Real,
    settings: &DeploySettings,
) -> Result<DVec, InsertProblem> {
    let (a, b) = (&traj.steps[step].q, &traj.steps[step + 1].q);
    let mut q = a + (b - a) * fraction;
    let n = q.len();
    let mut residual = Real::INFINITY;
    for iteration in 0..=PROJECTION_MAX_ITER {
        let c = mech.residual(&q);
        residual = c.amax();
        if !residual.is_finite() {
            return Err(InsertProblem::NonFinite);
        }
        if residual <= settings.joint_tolerance {
            return Ok(q);
        }
        if iteration == PROJECTION_MAX_ITER {
            break;
        }
        let jac = mech.jacobian(&q);
        let jr = jac.columns(3, n - 3);
        let g = jr.transpose() * &c;
        let spec = symmetric_eigen(jr.transpose() * jr).ok_or(InsertProblem::Eigen)?;
        let lmax = spec.values.last().copied().unwrap_or(0.0);
        let threshold = settings.mobility.rel_tol * lmax.max(1.0);
        let mut delta = DVec::zeros(n - 3);
        for (k, &lambda) in spec.values.iter().enumerate() {
            if lambda > threshold {
                let v = spec.vectors.column(k);
                delta.axpy(v.dot(&g) / lambda, &v, 1.0);
            }
        }
        let mut tail = q.rows_mut(3, n - 3);
        tail -= &delta;
    }
    Err(InsertProblem::NotConverged { residual })
}

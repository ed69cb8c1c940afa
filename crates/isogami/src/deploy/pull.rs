//! Pulling a sheet apart by two of its tiles, as a tester would: tile 0 is held (the solver
//! holds it in every step) and every load step moves the grip tile's centre β further along
//! the line from tile 0's centre. The step is the deployment's own: the Newton solver of
//! E_joints + E_coll + a progress term — here the grip's move along the axis, held to β as
//! stiffly as the joints are closed (the rigid-modes step holds the move along the motion
//! vector instead) — on the same step loop and contact model.
//!
//! A sheet with several degrees of freedom has motions nothing in that energy resists. A
//! weak drag on every coordinate towards where the step started stands for the friction of
//! a sheet on a table: the extra modes, and the tiling vectors of a finite sheet's mechanism
//! (no joint crosses cells, so they move nothing), stay put unless the pull moves them.
//! Restarted passes with a weaker drag remove its bias on the joints. A one-DOF sheet can
//! only follow its motion (or, at a branch point, take the other branch); a floppy one does
//! whatever its extra modes let the pull do. Where pulling no longer moves the grip, the
//! sheet is stalled.

use super::error::DeployError;
use super::march::{unit_displacement, StepInput, StepPolicy, StepTry};
use super::newton::{minimize_cached, Objective};
use super::settings::DeploySettings;
use crate::contact::{ContactModel, PairCache};
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real, Vec2};

/// The drag on every coordinate (the joints' stiffness is 1): strong enough that motions
/// nothing resists (the extra modes of a floppy sheet, the tiling vectors) stay put and the
/// Newton Hessian is positive definite, weak enough that a few restarted passes leave the
/// joints closed far below their tolerance.
const DRAG: Real = 1e-8;

/// Minimisations per load step, each restarting the drag where the last ended.
const PASSES: usize = 4;

/// Each pass's drag over the last's: a pass starts near its answer, so a weaker drag is
/// enough to keep rounding from moving what nothing resists, and its bias on the joints is
/// that much smaller (soft directions near the closed state are barely stiffer than the
/// first drag).
const DRAG_DECAY: Real = 1e-2;

/// The pull load step: tile 0 held, tile `grip` pulled away from it.
pub(super) struct Pull {
    /// The pulled tile (not 0).
    pub grip: usize,
}

/// Distance between tile 0's and tile `grip`'s centres at q, and the unit vector from the
/// first to the second.
pub(super) fn grip_axis(mech: &Mechanism, q: &DVec, grip: usize) -> (Real, Vec2) {
    let (a, _) = mech.pose(q, 0);
    let (b, _) = mech.pose(q, grip);
    let d = b - a;
    let len = d.norm();
    (
        len,
        if len > 0.0 {
            d / len
        } else {
            Vec2::new(1.0, 0.0)
        },
    )
}

impl StepPolicy for Pull {
    fn solve(
        &self,
        mech: &Mechanism,
        contact: &ContactModel,
        settings: &DeploySettings,
        input: &StepInput,
        cache: &mut PairCache,
    ) -> Result<StepTry, DeployError> {
        let StepInput {
            q, clearance, beta, ..
        } = *input;
        let (_, axis) = grip_axis(mech, q, self.grip);
        let g = mech.layout.tile(self.grip);
        let mut dir = DVec::zeros(q.len());
        dir[g] = axis.x;
        dir[g + 1] = axis.y;
        // The grip's move along the axis is held to β as stiffly as the joints are closed;
        // the drag picks, among the states that do it, one near where the step started, and
        // each further pass restarts a weaker drag where the last ended, so that its pull on
        // the joints vanishes.
        let mut from = q.clone();
        let mut start_clearance = Some(clearance);
        let mut out = None;
        let mut drag = DRAG;
        for _ in 0..PASSES {
            let obj = Objective {
                progress: Some((dir.clone(), q.clone(), beta, 1.0)),
                springs: Vec::new(),
                spring_k: 0.0,
                drag: Some((from.clone(), drag)),
            };
            let o = minimize_cached(mech, contact, &obj, &from, start_clearance, 50, cache);
            // Done when the joints are closed; a pass that did not converge is not helped
            // by another (the pull has gone as far as the sheet lets it).
            let done = o.joint_residual <= 0.1 * settings.joint_tolerance || !o.converged;
            from = o.q.clone();
            start_clearance = None;
            drag *= DRAG_DECAY;
            out = Some(o);
            if done {
                break;
            }
        }
        let out = out.expect("at least one pass");
        let direction = unit_displacement(&out.q, q, DVec::zeros(q.len()));
        let moved = (&out.q - q).dot(&dir);
        let progress_error = (moved - beta).abs() / beta;
        Ok(StepTry {
            outcome: out,
            direction,
            nullity: 0,
            progress_error,
        })
    }
}

//! Measures of one deployment frame.

use super::error::MeasureError;
use super::strain::{
    area_ratio, deformation_gradient, effective_poisson_ratio, polar, principal_direction,
    principal_expansions,
};
use crate::kinematics::Mechanism;
use crate::math::{DVec, Mat2, Real, Vec2};
use serde::{Deserialize, Serialize};

/// Everything the browser and the database need about one frame of a deployment.
///
/// Matrices are stored as rows, `[[a, b], [c, d]]`. Angles are in radians.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FrameMeasures {
    /// Deployment parameter (normalised arc length), 0 closed, 1 fully deployed.
    pub t: Real,
    /// Deformation gradient F, [u w] = F [ū w̄], as rows.
    pub f: [[Real; 2]; 2],
    /// Right stretch tensor U of F = RU, as rows (symmetric).
    pub u: [[Real; 2]; 2],
    /// Angle of the macroscopic rotation R: how much the sheet as a whole has turned.
    pub lattice_rotation: Real,
    /// Smallest principal expansion (eigenvalue of U − I).
    pub min_expansion: Real,
    /// Largest principal expansion.
    pub max_expansion: Real,
    /// Direction of the largest expansion in the closed sheet's frame, in (−π/2, π/2];
    /// exactly 0 when the expansion is isotropic, the principal stretches differing by at most
    /// [`ISOTROPIC_STRETCH_TOL`](super::ISOTROPIC_STRETCH_TOL) of their mean (every direction
    /// is principal then; see [`principal_direction`](super::principal_direction)).
    pub principal_angle: Real,
    /// Area ratio det F of the deployed to the closed sheet.
    pub area_ratio: Real,
    /// Rotation of each tile relative to the closed state with the sheet's rigid turn
    /// removed: θᵢ − θᵢ⁰ − `lattice_rotation`. Not wrapped: a tile that turns by 120° reports
    /// 2.09. Independent of how the solver pins the global rotation.
    pub tile_rotations: Vec<Real>,
    /// max |tile_rotations| (0 for a cell without tiles).
    pub max_tile_rotation: Real,
}

impl FrameMeasures {
    /// Measures of the frame at parameter `t` from the closed tiling vectors `u0`, `w0`, the
    /// current ones `u`, `w`, and the closed and current tile angles (same length).
    pub fn new(
        t: Real,
        (u0, w0): (Vec2, Vec2),
        (u, w): (Vec2, Vec2),
        closed_angles: &[Real],
        angles: &[Real],
    ) -> Result<FrameMeasures, MeasureError> {
        if closed_angles.len() != angles.len() {
            return Err(MeasureError::AngleCount {
                closed: closed_angles.len(),
                current: angles.len(),
            });
        }
        if !t.is_finite() {
            return Err(MeasureError::NonFiniteT { t });
        }
        if let Some(i) = (0..angles.len()).find(|&i| !(angles[i] - closed_angles[i]).is_finite()) {
            return Err(MeasureError::NonFiniteAngle { tile: i });
        }
        let f = deformation_gradient(&u0, &w0, &u, &w)?;
        let (r, stretch) = polar(&f)?;
        let turn = r[(1, 0)].atan2(r[(0, 0)]);
        let (min_expansion, max_expansion) = principal_expansions(&stretch);
        let tile_rotations: Vec<Real> = angles
            .iter()
            .zip(closed_angles)
            .map(|(a, a0)| a - a0 - turn)
            .collect();
        let max_tile_rotation = tile_rotations.iter().fold(0.0, |m: Real, r| m.max(r.abs()));
        Ok(FrameMeasures {
            t,
            f: rows(&f),
            u: rows(&stretch),
            lattice_rotation: turn,
            min_expansion,
            max_expansion,
            principal_angle: principal_direction(&stretch),
            area_ratio: area_ratio(&f),
            tile_rotations,
            max_tile_rotation,
        })
    }

    /// Measures of state `q` of `mech` relative to the closed state `q0` (usually
    /// `mech.rest`), at deployment parameter `t`.
    pub fn from_states(
        mech: &Mechanism,
        q0: &DVec,
        q: &DVec,
        t: Real,
    ) -> Result<FrameMeasures, MeasureError> {
        let n = mech.layout.len();
        if q0.len() != n || q.len() != n {
            return Err(MeasureError::StateLength {
                closed: q0.len(),
                current: q.len(),
                unknowns: n,
            });
        }
        let angles =
            |q: &DVec| -> Vec<Real> { (0..mech.tile_count()).map(|i| mech.pose(q, i).1).collect() };
        FrameMeasures::new(
            t,
            mech.lattice(q0),
            mech.lattice(q),
            &angles(q0),
            &angles(q),
        )
    }

    /// F as a matrix.
    pub fn f_matrix(&self) -> Mat2 {
        matrix(&self.f)
    }

    /// U as a matrix.
    pub fn u_matrix(&self) -> Mat2 {
        matrix(&self.u)
    }

    /// −ε_min/ε_max at this frame (see [`effective_poisson_ratio`]).
    pub fn poisson_ratio(&self) -> Option<Real> {
        effective_poisson_ratio(self.min_expansion, self.max_expansion)
    }
}

fn rows(m: &Mat2) -> [[Real; 2]; 2] {
    [[m[(0, 0)], m[(0, 1)]], [m[(1, 0)], m[(1, 1)]]]
}

fn matrix(r: &[[Real; 2]; 2]) -> Mat2 {
    Mat2::new(r[0][0], r[0][1], r[1][0], r[1][1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{rotation, vec2};

    #[test]
    fn rotations_are_relative_to_the_sheet_turn() {
        let (u0, w0) = (vec2(2.0, 0.0), vec2(0.0, 2.0));
        // Rotating squares at φ = 0.4, sheet turned by 0.25 as a whole.
        let (phi, turn) = (0.4_f64, 0.25);
        let m = rotation(turn) * (phi.cos() + phi.sin());
        let closed = [0.0, 0.0, 0.0, 0.0];
        let now = [turn + phi, turn - phi, turn - phi, turn + phi];
        let fm = FrameMeasures::new(0.5, (u0, w0), (m * u0, m * w0), &closed, &now).unwrap();
        assert!((fm.lattice_rotation - turn).abs() < 1e-14);
        for (r, want) in fm.tile_rotations.iter().zip([phi, -phi, -phi, phi]) {
            assert!((r - want).abs() < 1e-14);
        }
        assert!((fm.max_tile_rotation - phi).abs() < 1e-14);
        assert!((fm.min_expansion - fm.max_expansion).abs() < 1e-14);
        assert!((fm.poisson_ratio().unwrap() + 1.0).abs() < 1e-12);
        assert!((fm.f_matrix() - m).norm() < 1e-14);
        let json = serde_json::to_string(&fm).unwrap();
        assert!(json.contains("\"f\":[["), "{json}");
        let back: FrameMeasures = serde_json::from_str(&json).unwrap();
        assert_eq!(back, fm);
    }

    #[test]
    fn mismatched_angles_are_an_error() {
        let (u0, w0) = (vec2(1.0, 0.0), vec2(0.0, 1.0));
        assert!(FrameMeasures::new(0.0, (u0, w0), (u0, w0), &[0.0], &[]).is_err());
        assert!(FrameMeasures::new(0.0, (u0, w0), (u0, w0), &[0.0], &[Real::NAN]).is_err());
        assert_eq!(
            FrameMeasures::new(0.0, (u0, w0), (u0, w0), &[0.0, 0.0], &[0.0]).unwrap_err(),
            MeasureError::AngleCount {
                closed: 2,
                current: 1
            }
        );
        assert_eq!(
            FrameMeasures::new(0.0, (u0, w0), (u0, w0), &[0.0, 0.0], &[0.0, Real::NAN])
                .unwrap_err(),
            MeasureError::NonFiniteAngle { tile: 1 }
        );
    }
}

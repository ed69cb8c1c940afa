//! Finite deployment: a one-DOF finite sheet opening, with contact among its own tiles only,
//! to its contact limit.
//!
//! A sheet whose one motion is the periodic one (a completed sheet, or a raw region that
//! happens to be one-DOF) has, at every state of its motion, the configuration of the
//! periodic mechanism's state placed at its tiles' cells ([`FiniteSheet::poses`]). What the
//! free boundary changes is which tiles can touch: only pairs of tiles the sheet holds. So
//! the finite deployment is the periodic deployment of the design's mechanism — the same
//! step policy, Newton solver, settings and contact model — with the contact model
//! restricted to the sheet's own pairs ([`sheet_pairs`],
//! [`crate::contact::ContactModel::restricted_to`]). A sheet that lacks the pair blocking the
//! periodic sheet opens further; one that holds it stops where the periodic sheet stops.
//!
//! That reduction holds while the sheet stays one-DOF with the periodic motion; it is
//! checked, not assumed: [`check_states`] counts the sheet's degrees of freedom (sparse
//! kernel, [`super::sheet_mobility`]) at states along the way. The measures here
//! ([`SheetMeasures`]) are the finite sheet's own: the area of its tiles' convex hull and
//! the principal stretches of its tile centres, against the closed sheet.

use super::error::FiniteError;
use super::mobility::{periodic_velocity, sheet_mobility};
use super::sheet::FiniteSheet;
use crate::contact::CandidatePair;
use crate::deploy::Trajectory;
use crate::geometry::{convex_hull, signed_area};
use crate::kinematics::Mechanism;
use crate::math::{rotation, DVec, Real, Vec2};
use crate::mobility::{analyze, MobilitySettings};
use nalgebra::Matrix2;
use serde::Serialize;
use std::collections::HashSet;

/// Every pair of tiles the sheet holds, as the periodic contact model names it: tile `a` of
/// the centre cell against tile `b` of the cell at their cells' difference (canonical
/// orientation, each kind once). Two tiles of the sheet touch exactly when their pair is
/// listed here and the periodic model's pair touches.
pub fn sheet_pairs(sheet: &FiniteSheet) -> Vec<CandidatePair> {
    let mut seen = HashSet::new();
    for (i, a) in sheet.tiles.iter().enumerate() {
        for b in &sheet.tiles[i + 1..] {
            let offset = [b.cell[0] - a.cell[0], b.cell[1] - a.cell[1]];
            if let Some(p) = CandidatePair::canonical(a.tile, b.tile, offset) {
                seen.insert(p);
            }
        }
    }
    let mut pairs: Vec<CandidatePair> = seen.into_iter().collect();
    pairs.sort_by_key(|p| (p.a, p.b, p.offset));
    pairs
}

/// The finite sheet's own opening measures at one state.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct SheetMeasures {
    /// Area of the convex hull of every tile vertex over the closed sheet's.
    pub hull_area_ratio: Real,
    /// Principal stretches (larger first) of the best affine map of the tile centres from the
    /// closed sheet to this state: how much the region as a whole stretches each way.
    pub stretches: [Real; 2],
}

/// World vertices of every tile of `sheet` at the periodic state `q` (units of L).
pub fn sheet_polygons(sheet: &FiniteSheet, mech: &Mechanism, q: &DVec) -> Vec<Vec<Vec2>> {
    sheet
        .tiles
        .iter()
        .zip(sheet.poses(mech, q))
        .map(|(t, (p, th))| {
            let r = rotation(th);
            mech.tile_shapes[t.tile].iter().map(|v| p + r * v).collect()
        })
        .collect()
}

/// What the measures of a sheet are taken against: its closed hull area and tile centres,
/// computed once per deployment rather than at every state.
#[derive(Debug, Clone)]
pub struct ClosedSheet {
    hull_area: Real,
    centres: Vec<Vec2>,
}

/// Area of the convex hull of every tile vertex of `sheet` at `q`.
fn hull_area(sheet: &FiniteSheet, mech: &Mechanism, q: &DVec) -> Real {
    let points: Vec<Vec2> = sheet_polygons(sheet, mech, q)
        .into_iter()
        .flatten()
        .collect();
    signed_area(&convex_hull(&points)).abs()
}

impl ClosedSheet {
    /// `sheet` at the closed state `rest`. `None` when it has fewer than three tiles or its
    /// closed hull has no area.
    pub fn of(sheet: &FiniteSheet, mech: &Mechanism, rest: &DVec) -> Option<ClosedSheet> {
        let hull_area = hull_area(sheet, mech, rest);
        if sheet.len() < 3 || hull_area.is_nan() || hull_area <= 0.0 {
            return None;
        }
        Some(ClosedSheet {
            hull_area,
            centres: centres(&sheet.poses(mech, rest)),
        })
    }

    /// [`SheetMeasures`] of `sheet` at `q` against this closed sheet (`None` when not finite).
    pub fn measures(
        &self,
        sheet: &FiniteSheet,
        mech: &Mechanism,
        q: &DVec,
    ) -> Option<SheetMeasures> {
        let ratio = hull_area(sheet, mech, q) / self.hull_area;
        let stretches = centre_stretches(&self.centres, &centres(&sheet.poses(mech, q)))?;
        (ratio.is_finite() && stretches.iter().all(|s| s.is_finite())).then_some(SheetMeasures {
            hull_area_ratio: ratio,
            stretches,
        })
    }
}

fn centres(poses: &[(Vec2, Real)]) -> Vec<Vec2> {
    poses.iter().map(|&(p, _)| p).collect()
}

/// Singular values of the least-squares F with F·(x − x̄) ≈ y − ȳ.
fn centre_stretches(x: &[Vec2], y: &[Vec2]) -> Option<[Real; 2]> {
    let n = x.len() as Real;
    let xm = x.iter().sum::<Vec2>() / n;
    let ym = y.iter().sum::<Vec2>() / n;
    let (mut yx, mut xx) = (Matrix2::zeros(), Matrix2::zeros());
    for (a, b) in x.iter().zip(y) {
        let (a, b) = (a - xm, b - ym);
        yx += b * a.transpose();
        xx += a * a.transpose();
    }
    let f = yx * xx.try_inverse()?;
    let s = f.singular_values();
    Some([s[0].max(s[1]), s[0].min(s[1])])
}

/// The sheet's mobility at one state of its deployment.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct StateCheck {
    /// Step index in the finite deployment.
    pub step: usize,
    /// Its t (normalised arc length of the finite deployment).
    pub t: Real,
    /// Degrees of freedom of the sheet there.
    pub dof: usize,
    /// Whether the periodic motion is one of its motions there.
    pub follows_periodic: bool,
}

/// The sheet's degrees of freedom at `count` states spread evenly over the inside of `traj`:
/// neither the closed state nor the last, which are often singular configurations (the
/// closed sheet always; rotating squares' last state is its turning point). The periodic
/// motion compared with is the mechanism's at that state ([`crate::mobility::analyze`]).
pub fn check_states(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    traj: &Trajectory,
    count: usize,
    settings: MobilitySettings,
) -> Result<Vec<StateCheck>, FiniteError> {
    let last = traj.steps.len().saturating_sub(1);
    if last < 2 || count == 0 {
        return Ok(Vec::new());
    }
    let mut picks: Vec<usize> = (1..=count)
        .map(|k| ((k * last) / (count + 1)).clamp(1, last - 1))
        .collect();
    picks.dedup();
    picks
        .into_iter()
        .map(|step| state_check(sheet, mech, traj, step, settings))
        .collect()
}

/// The sheet's degrees of freedom at accepted state `step` of `traj`, against the
/// mechanism's periodic motion there ([`crate::mobility::analyze`]).
pub fn state_check(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    traj: &Trajectory,
    step: usize,
    settings: MobilitySettings,
) -> Result<StateCheck, FiniteError> {
    let q = &traj.steps[step].q;
    let motion = analyze(mech, q, settings)
        .map_err(|_| FiniteError::Eigen)?
        .motion
        .map_or_else(|| DVec::zeros(q.len()), |m| m.vector);
    let poses = sheet.poses(mech, q);
    let periodic = periodic_velocity(sheet, mech, &motion);
    let m = sheet_mobility(sheet, mech, &poses, Some(&periodic), crate::stop::NEVER)?;
    Ok(StateCheck {
        step,
        t: traj.t(step),
        dof: m.dof,
        follows_periodic: m.follows_periodic,
    })
}

/// How far the sheet's tiles are from where the periodic deployment puts them, over the
/// states both deployments share.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct PeriodicAgreement {
    /// States compared (the closed state first): the finite and periodic deployments take
    /// the same steps until contact makes them differ.
    pub compared_steps: usize,
    /// t of the periodic deployment at the last compared state.
    pub until_periodic_t: Real,
    /// Largest distance between a tile's centre in the two (units of L).
    pub max_position_deviation: Real,
    /// Largest difference of a tile's angle (radians).
    pub max_angle_deviation: Real,
}

/// Compares the finite deployment `finite` with the periodic one `periodic` state by state,
/// while both took the same step (equal arc length to 1e-9 relative) and neither has a
/// barrier active (clearance at least `dhat` in both): past the first contact the two sheets
/// differ by design.
pub fn periodic_agreement(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    finite: &Trajectory,
    periodic: &Trajectory,
    dhat: Real,
) -> PeriodicAgreement {
    let mut out = PeriodicAgreement {
        compared_steps: 0,
        until_periodic_t: 0.0,
        max_position_deviation: 0.0,
        max_angle_deviation: 0.0,
    };
    for (k, (f, p)) in finite.steps.iter().zip(&periodic.steps).enumerate() {
        let same_step = (f.arc - p.arc).abs() <= 1e-9 * p.arc.max(1.0);
        if !same_step || f.min_clearance < dhat || p.min_clearance < dhat {
            break;
        }
        for (a, b) in sheet.poses(mech, &f.q).iter().zip(sheet.poses(mech, &p.q)) {
            out.max_position_deviation = out.max_position_deviation.max((a.0 - b.0).norm());
            out.max_angle_deviation = out.max_angle_deviation.max((a.1 - b.1).abs());
        }
        out.compared_steps = k + 1;
        out.until_periodic_t = periodic.t(k);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn canonical_pairs_name_each_kind_once() {
        use super::super::sheet::SheetTile;
        let t = |c: [i32; 2], tile| SheetTile { cell: c, tile };
        let sheet = FiniteSheet {
            tiles: vec![t([0, 0], 0), t([1, 0], 0), t([0, 0], 1), t([2, 0], 1)],
            joints: Vec::new(),
        };
        let pairs = sheet_pairs(&sheet);
        let want = [
            CandidatePair::canonical(0, 0, [1, 0]).unwrap(),
            CandidatePair::canonical(0, 1, [0, 0]).unwrap(),
            CandidatePair::canonical(0, 1, [2, 0]).unwrap(),
            CandidatePair::canonical(0, 1, [-1, 0]).unwrap(),
            CandidatePair::canonical(0, 1, [1, 0]).unwrap(),
            CandidatePair::canonical(1, 1, [2, 0]).unwrap(),
        ];
        assert_eq!(pairs.len(), want.len(), "{pairs:?}");
        for w in want {
            assert!(pairs.contains(&w), "{w:?} missing from {pairs:?}");
        }
    }

    #[test]
    fn stretches_of_an_affine_map_are_its_singular_values() {
        let x: Vec<Vec2> = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (2.0, 3.0)]
            .iter()
            .map(|&(a, b)| vec2(a, b))
            .collect();
        // F = rotation(0.3) · diag(2, 0.5)
        let f = rotation(0.3) * Matrix2::new(2.0, 0.0, 0.0, 0.5);
        let y: Vec<Vec2> = x.iter().map(|p| f * p + vec2(5.0, -1.0)).collect();
        let s = centre_stretches(&x, &y).unwrap();
        assert!(
            (s[0] - 2.0).abs() < 1e-12 && (s[1] - 0.5).abs() < 1e-12,
            "{s:?}"
        );
    }
}

//! The graded sheet checked the other way: does its closed tiling really open, as a
//! mechanism of its own, into the optimised opened state?
//!
//! The path is followed from the opened state back to the closed one: the mean relative
//! rotation across the pins (the [`Problem`]'s opening) is stepped down to zero, and at every
//! step the pins are closed again over the tile poses alone, the closed shapes held. At every
//! state the check counts the degrees of freedom (the rank of the pins' Jacobian, rigid
//! motions taken out) and looks for two opened tiles whose interiors overlap. The path
//! reaches the closed tiling when, at zero opening, every tile has turned back by the same
//! angle (the sheet is the closed tiling moved rigidly).

use super::model::{GradedSheet, OpenedPose};
use super::problem::{Problem, PROJECTION_STIFFNESS};
pub use super::rank::{dof, RANK_TOLERANCE};
use crate::geometry::{interiors_overlap, is_simple_problem, overlap_depth};
use crate::math::{DVec, Real};
use crate::stop::KeepGoing;
use serde::{Deserialize, Serialize};

/// One state of the path.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PathState {
    /// Its opening as a fraction of the optimised state's (1: optimised, 0: closed).
    pub opening: Real,
    /// Largest pin gap after closing the pins (length scales).
    pub joint_gap: Real,
    /// Degrees of freedom (up to [`super::rank::MAX_COUNTED`]; None: the count failed).
    pub dof: Option<usize>,
    /// The two smallest singular values of the pins' Jacobian past the rigid motions,
    /// relative to the largest (the mechanism's mode, then the next).
    pub smallest: Option<[Real; 2]>,
    /// The pair of tiles whose opened interiors overlap deepest, if any.
    pub overlap: Option<(usize, usize)>,
    /// How deep that pair overlaps: the deepest a point of one tile's boundary lies inside
    /// the other (length scales; 0 without an overlap). Absent from checks written before it
    /// was measured: 0.
    #[serde(default)]
    pub overlap_depth: Real,
    /// The tiles' poses at this state (the closed shapes placed: what a player draws).
    pub poses: Vec<OpenedPose>,
}

impl PathState {
    /// Whether its pins are closed (gap under [`PIN_TOLERANCE`]).
    pub fn pins_closed(&self) -> bool {
        self.joint_gap < PIN_TOLERANCE
    }
}

/// The path from the optimised state to the closed tiling.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PathCheck {
    /// The states, optimised first.
    pub states: Vec<PathState>,
    /// Largest difference between two tiles' rotations at zero opening (radians): zero when
    /// the path reaches the closed tiling.
    pub closed_spread: Real,
    /// Closed tiles that are not simple polygons (an edge crossing another of the same tile):
    /// the cut pattern is then no tiling. Absent from checks written before it was checked:
    /// none.
    #[serde(default)]
    pub self_intersecting: Vec<usize>,
    /// Every closed tile is a simple polygon, every state has closed pins and no overlap, one
    /// DOF where counted from [`DOF_FROM_OPENING`] open, and the path ends in the closed
    /// tiling.
    pub reached: bool,
    /// The gap under which a pin counts as closed ([`PIN_TOLERANCE`]), and the opening from
    /// which a state must have one DOF ([`DOF_FROM_OPENING`]): carried with the check, so
    /// that a reader of its JSON (the browser page) judges its states as the library does.
    /// Absent from checks written before they were carried: the constants.
    #[serde(default = "pin_tolerance")]
    pub pin_tolerance: Real,
    /// See `pin_tolerance`.
    #[serde(default = "dof_from_opening")]
    pub dof_from_opening: Real,
}

fn pin_tolerance() -> Real {
    PIN_TOLERANCE
}

fn dof_from_opening() -> Real {
    DOF_FROM_OPENING
}

impl Default for PathCheck {
    /// No states, not reached (a path not checked yet).
    fn default() -> Self {
        PathCheck {
            states: Vec::new(),
            closed_spread: 0.0,
            self_intersecting: Vec::new(),
            reached: false,
            pin_tolerance: PIN_TOLERANCE,
            dof_from_opening: DOF_FROM_OPENING,
        }
    }
}

impl PathCheck {
    /// The state whose tiles overlap deepest (the first of equals; None without an overlap).
    pub fn deepest_overlap(&self) -> Option<&PathState> {
        self.states
            .iter()
            .filter(|s| s.overlap.is_some())
            .reduce(|a, b| {
                if b.overlap_depth > a.overlap_depth {
                    b
                } else {
                    a
                }
            })
    }

    /// The state whose pins open widest (the first of equals; None for no states).
    pub fn widest_gap(&self) -> Option<&PathState> {
        self.states
            .iter()
            .reduce(|a, b| if b.joint_gap > a.joint_gap { b } else { a })
    }
}

/// States at least this open (as a fraction of the optimised one) must have one DOF. The
/// closed tiling is a singular configuration: close to it the sheet's second singular value
/// falls towards zero with the opening (measured on graded rotating squares, 10×10 tiles:
/// 3.6e-4 of the largest at 15 % open, 2.3e-4 at 10 %, 9.8e-5 at 5 %; 20×20 tiles: 1.1e-4
/// at 20 %, 5.9e-5 at 10 %, 3.5e-5 at 5 %; the mode stays near 1e-8), so a count there
/// says how near the closed state is, not that another motion exists. Those states are
/// still counted and reported, and must close their pins without overlap.
pub const DOF_FROM_OPENING: Real = 0.1;

/// Pins are closed when their gap is below this (length scales: 20 nm on a 20 mm tile).
pub const PIN_TOLERANCE: Real = 1e-6;

/// Overlaps shallower than this are ignored (length scales): pins closed to
/// [`PIN_TOLERANCE`] let two pinned tiles' edges cross by about that much beside the pin.
pub const OVERLAP_TOLERANCE: Real = 1e-5;

/// Follows the path of `sheet` in `steps` steps (at least 2).
pub fn check_path(
    sheet: &GradedSheet,
    problem: &Problem,
    steps: usize,
    keep_going: KeepGoing<'_>,
) -> Result<PathCheck, crate::Error> {
    let steps = steps.max(2);
    // Near the closed tiling (a singular configuration: the pins alone admit other branches
    // there) the turning rows keep the branch, weighed as in the fit's first stage; further
    // open the pins dominate them as at the fit's end.
    let mut stiff = problem.projection(PROJECTION_STIFFNESS);
    let mut near_closed = problem.projection(1.0);
    let target = *problem.openings.last().expect("a problem has a state");
    let mut work = sheet.clone();
    work.path.clear();
    let mut z = Problem::pack(&work);
    let nodes = sheet.nodes.len();
    let mut states = Vec::with_capacity(steps + 1);
    let mut previous: Option<DVec> = None;
    for k in 0..=steps {
        let fraction = 1.0 - k as Real / steps as Real;
        let problem = if fraction < DOF_FROM_OPENING {
            &mut near_closed
        } else {
            &mut stiff
        };
        problem.openings = vec![target * fraction];
        // Secant predictor: the next state is guessed along the last step, so the correction
        // stays on the branch being followed.
        let here = z.clone();
        if let Some(before) = &previous {
            z = &z + (&z - before);
        }
        super::solve::project(problem, &mut z, 2 * nodes, 100, keep_going)?;
        previous = Some(here);
        Problem::unpack(&mut work, &z);
        let counted = dof(&work);
        let deepest = overlap(&work);
        states.push(PathState {
            opening: fraction,
            joint_gap: work.joint_gap(),
            dof: counted.map(|c| c.0),
            smallest: counted.map(|c| c.1),
            overlap: deepest.map(|d| d.0),
            overlap_depth: deepest.map_or(0.0, |d| d.1),
            poses: work.opened.clone(),
        });
    }
    let thetas: Vec<Real> = work.opened.iter().map(|p| p.theta).collect();
    let (lo, hi) = thetas
        .iter()
        .fold((Real::MAX, Real::MIN), |(l, h), &t| (l.min(t), h.max(t)));
    let closed_spread = hi - lo;
    let self_intersecting = self_intersecting(sheet);
    let reached = closed_spread < 1e-6
        && self_intersecting.is_empty()
        && states.iter().all(|s| {
            s.pins_closed()
                && s.overlap.is_none()
                && (s.opening < DOF_FROM_OPENING || s.dof.is_none_or(|d| d == 1))
        });
    Ok(PathCheck {
        states,
        closed_spread,
        self_intersecting,
        reached,
        pin_tolerance: PIN_TOLERANCE,
        dof_from_opening: DOF_FROM_OPENING,
    })
}

/// The closed tiles of `sheet` that are not simple polygons at [`OVERLAP_TOLERANCE`].
pub fn self_intersecting(sheet: &GradedSheet) -> Vec<usize> {
    (0..sheet.tiles.len())
        .filter(|&i| is_simple_problem(&sheet.closed_polygon(i), OVERLAP_TOLERANCE).is_some())
        .collect()
}

/// The pair of tiles whose opened interiors overlap deepest (pinned neighbours touch only at
/// their pin), with the depth ([`overlap_depth`]), if any pair overlaps.
pub fn overlap(sheet: &GradedSheet) -> Option<((usize, usize), Real)> {
    let polys: Vec<_> = (0..sheet.tiles.len())
        .map(|i| sheet.opened_polygon(i))
        .collect();
    let boxes: Vec<_> = polys
        .iter()
        .map(|p| {
            p.iter().fold(
                (Real::MAX, Real::MAX, Real::MIN, Real::MIN),
                |(a, b, c, d), v| (a.min(v.x), b.min(v.y), c.max(v.x), d.max(v.y)),
            )
        })
        .collect();
    let mut deepest: Option<((usize, usize), Real)> = None;
    for i in 0..polys.len() {
        for k in i + 1..polys.len() {
            let (a, b) = (boxes[i], boxes[k]);
            if a.2 < b.0 || b.2 < a.0 || a.3 < b.1 || b.3 < a.1 {
                continue;
            }
            if interiors_overlap(&polys[i], &polys[k], OVERLAP_TOLERANCE) {
                let depth = overlap_depth(&polys[i], &polys[k], OVERLAP_TOLERANCE);
                if deepest.is_none_or(|d| depth > d.1) {
                    deepest = Some(((i, k), depth));
                }
            }
        }
    }
    deepest
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A check's JSON carries the measures its states were judged by, under the names the
    /// browser page reads; a check written before they were carried reads back with the
    /// library's.
    #[test]
    fn a_checks_json_carries_the_measures_it_was_judged_by() {
        let check = PathCheck {
            states: Vec::new(),
            closed_spread: 0.0,
            self_intersecting: Vec::new(),
            reached: true,
            pin_tolerance: PIN_TOLERANCE,
            dof_from_opening: DOF_FROM_OPENING,
        };
        let json = serde_json::to_value(&check).unwrap();
        assert_eq!(json["pin_tolerance"], PIN_TOLERANCE);
        assert_eq!(json["dof_from_opening"], DOF_FROM_OPENING);
        let old = serde_json::json!({ "states": [], "closed_spread": 0.0, "reached": true });
        let read: PathCheck = serde_json::from_value(old).unwrap();
        assert_eq!(read, check);
    }
}

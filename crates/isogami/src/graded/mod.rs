//! Graded sheets (issue 25): a finite sheet whose tiles each have their own shape, chosen so
//! that the sheet opens into a target outline.
//!
//! - [`model`]: the graded sheet — closed nodes shared by the tiles (found combinatorially),
//!   the design's pins, one opened pose per tile; plain serialisable data;
//! - [`target`]: the target outline, as a radius in every direction;
//! - [`problem`]: the residuals (pins, mean opening, fit, smoothness, shape bounds) and their
//!   exact sparse Jacobian;
//! - [`solve`]: Levenberg–Marquardt on the sparse normal equations (faer's Cholesky), then a
//!   projection that closes every pin exactly with the closed shapes held.
//!
//! The start is the design's own finite sheet (completed to one degree of freedom, issue 15)
//! at its opened state, the target scaled to the area that sheet covers open.

pub mod error;
pub mod model;
pub mod problem;
pub mod solve;
pub mod target;

pub use error::GradedError;
pub use model::{GradedJoint, GradedSheet, GradedTile, OpenedPose};
pub use problem::{Problem, Weights};
pub use solve::{optimise, GradedReport, SolveSettings};
pub use target::{parse_outline, Outline};

use crate::api::{resolve_design, SheetRequest};
use crate::finite::{Region, SheetTile};
use crate::geometry::signed_area;
use crate::math::{Real, Vec2};
use crate::stop::KeepGoing;
use std::collections::HashMap;

/// What to grade and towards what.
#[derive(Debug, Clone, PartialEq)]
pub struct GradedRequest {
    /// The design (spec or name).
    pub design: String,
    /// Cells along w.
    pub rows: usize,
    /// Cells along u.
    pub cols: usize,
    /// The target outline of the opened sheet.
    pub outline: Outline,
    /// The opened state, as the periodic deployment's t (1: its contact limit).
    pub t: Real,
    /// Complete the region to a one-DOF sheet first (issue 15).
    pub complete: bool,
    /// Residual weights.
    pub weights: Weights,
    /// Solver settings.
    pub solve: SolveSettings,
}

impl Default for GradedRequest {
    fn default() -> Self {
        GradedRequest {
            design: "rotating-squares".into(),
            rows: 4,
            cols: 4,
            outline: Outline::Disc,
            t: 1.0,
            complete: true,
            weights: Weights::default(),
            solve: SolveSettings::default(),
        }
    }
}

/// Largest region side, in cells.
pub const MAX_GRADED_CELLS: usize = 64;

/// The ungraded start and the problem of a request.
pub fn setup(request: &GradedRequest) -> Result<(GradedSheet, Problem), crate::Error> {
    let bad = |m: String| -> crate::Error { GradedError::BadSetting(m).into() };
    if request.rows == 0 || request.cols == 0 {
        return Err(
            GradedError::BadRegion("a region has at least one cell each way".into()).into(),
        );
    }
    if request.rows > MAX_GRADED_CELLS || request.cols > MAX_GRADED_CELLS {
        return Err(GradedError::BadRegion(format!(
            "{}x{} cells: at most {MAX_GRADED_CELLS} each way",
            request.rows, request.cols
        ))
        .into());
    }
    if !(request.t.is_finite() && request.t > 0.0 && request.t <= 1.0) {
        return Err(bad(format!(
            "t = {} must be in (0, 1] (an opened state)",
            request.t
        )));
    }
    let outline = request.outline.clone().validated()?;
    let design = resolve_design(&request.design)?;
    let cell = design.cell()?;
    let sheet_request = SheetRequest {
        region: Region::Cells {
            rows: request.rows,
            cols: request.cols,
        },
        // Degrees of freedom are counted at a generic opened state (a fully opened state can
        // be a singular one: rotating squares at their largest area gain a mode).
        t: request.t.min(SheetRequest::default().t),
        complete: request.complete,
        ..SheetRequest::default()
    };
    let (mech, path, analysis) =
        crate::api::finite::deployed_sheet(&design, &sheet_request, &mut |_| true)?;
    let traj = &path.trajectory;
    let k = (0..traj.steps.len())
        .min_by(|&a, &b| {
            (traj.t(a) - request.t)
                .abs()
                .total_cmp(&(traj.t(b) - request.t).abs())
        })
        .expect("a deployment has states");
    if k == 0 {
        return Err(GradedError::Design("the design does not open".into()).into());
    }
    let q = traj.steps[k].q.clone();
    let sheet = analysis.sheet();
    let graded = GradedSheet::ungraded(&design.to_string(), &cell, &mech, sheet, &q)?;
    let problem = problem_of(&graded, outline, request.weights);
    Ok((graded, problem))
}

/// The problem of an ungraded start.
pub fn problem_of(graded: &GradedSheet, outline: Outline, weights: Weights) -> Problem {
    let tiles: Vec<Vec<usize>> = graded.tiles.iter().map(|t| t.nodes.clone()).collect();
    let joints: Vec<(usize, usize, usize)> =
        graded.joints.iter().map(|j| (j.a, j.b, j.node)).collect();
    let rel: Vec<Real> = joints
        .iter()
        .map(|&(a, b, _)| graded.opened[b].theta - graded.opened[a].theta)
        .collect();
    let joint_signs: Vec<Real> = rel
        .iter()
        .map(|&r| if r.abs() > 1e-9 { r.signum() } else { 0.0 })
        .collect();
    let opening = rel
        .iter()
        .zip(&joint_signs)
        .map(|(r, s)| r * s)
        .sum::<Real>()
        / joints.len().max(1) as Real;
    // The outline: per boundary tile, its boundary corner farthest out at the start.
    let boundary = graded.boundary_corners();
    let mut best: HashMap<usize, (usize, Real)> = HashMap::new();
    for &(i, v) in &boundary {
        let r = graded.opened_polygon(i)[v].norm();
        let slot = best.entry(i).or_insert((v, r));
        if r > slot.1 {
            *slot = (v, r);
        }
    }
    let mut tips = Vec::new();
    let mut inside = Vec::new();
    for &(i, v) in &boundary {
        let node = graded.tiles[i].nodes[v];
        if best[&i].0 == v {
            tips.push((i, node));
        } else {
            inside.push((i, node));
        }
    }
    let points: Vec<Vec2> = tips
        .iter()
        .map(|&(i, n)| graded.opened_corner(i, n))
        .collect();
    let scale = (hull_area(&points) / outline.area()).sqrt();
    let index: HashMap<SheetTile, usize> = graded
        .tiles
        .iter()
        .enumerate()
        .map(|(i, t)| {
            (
                SheetTile {
                    cell: t.cell,
                    tile: t.tile,
                },
                i,
            )
        })
        .collect();
    let mut neighbours = Vec::new();
    for (i, t) in graded.tiles.iter().enumerate() {
        for d in [[1, 0], [0, 1]] {
            let other = SheetTile {
                cell: [t.cell[0] + d[0], t.cell[1] + d[1]],
                tile: t.tile,
            };
            if let Some(&j) = index.get(&other) {
                if graded.tiles[j].nodes.len() == t.nodes.len() {
                    neighbours.push((i, j));
                }
            }
        }
    }
    let start: Vec<Vec2> = (0..graded.nodes.len()).map(|n| graded.node(n)).collect();
    let corner_start = tiles
        .iter()
        .map(|t| {
            let m = t.len();
            (0..m)
                .map(|v| {
                    model::corner_cross(
                        start[t[(v + m - 1) % m]],
                        start[t[v]],
                        start[t[(v + 1) % m]],
                    )
                })
                .collect()
        })
        .collect();
    let edge_start = tiles
        .iter()
        .map(|t| {
            let m = t.len();
            (0..m)
                .map(|v| (start[t[(v + 1) % m]] - start[t[v]]).norm())
                .collect()
        })
        .collect();
    Problem {
        tiles,
        joints,
        joint_signs,
        opening,
        tips,
        inside,
        outline,
        scale,
        neighbours,
        start,
        corner_start,
        edge_start,
        weights,
        full: true,
    }
}

/// Area of the convex hull of `points`.
fn hull_area(points: &[Vec2]) -> Real {
    let mut p: Vec<Vec2> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    if p.len() < 3 {
        return 0.0;
    }
    let turn = |o: Vec2, a: Vec2, b: Vec2| crate::math::cross(&(a - o), &(b - o));
    let mut hull: Vec<Vec2> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Vec2>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    signed_area(&hull)
}

/// Grades a design's finite sheet towards a target: the optimised sheet and its report.
pub fn grade(
    request: &GradedRequest,
    progress: &mut dyn FnMut(usize, Real) -> bool,
    keep_going: KeepGoing<'_>,
) -> Result<(GradedSheet, GradedReport), crate::Error> {
    let (mut sheet, mut problem) = setup(request)?;
    let report = optimise(
        &mut sheet,
        &mut problem,
        &request.solve,
        progress,
        keep_going,
    )?;
    Ok((sheet, report))
}

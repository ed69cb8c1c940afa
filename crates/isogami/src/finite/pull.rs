//! A finite sheet as a mechanism of its own, pulled apart by two of its tiles as a tester
//! would, and how far its tiles leave the periodic motion.
//!
//! A sheet with more than one degree of freedom has no one motion to follow: what it does
//! depends on how it is held. [`sheet_mechanism`] makes the sheet a [`Mechanism`] whose
//! tiles are the sheet's (the grip that is held first) and whose joints are the sheet's,
//! none across cells, with tiling vectors so long that no two copies of the sheet come near
//! each other; `deploy::pull_with` then pulls it on the deployment's own step loop, Newton
//! solver and contact model. [`motion_deviation`] measures each pulled state against the
//! periodic motion: the largest distance between a tile vertex and where the periodic motion
//! puts it, after the best rigid alignment of the whole sheet and at the periodic state
//! (projected onto the joints between accepted states) that fits best.

use super::error::FiniteError;
use super::sheet::{FiniteSheet, SheetJoint, SheetTile};
use crate::deploy::{project_between, DeploySettings, Trajectory};
use crate::kinematics::{Joint, Mechanism, StateLayout};
use crate::math::{rotation, DVec, Real, Vec2};
use serde::Serialize;

/// A tile leaves the periodic motion when a vertex of it is this far (units of L) from where
/// the motion puts it.
pub const LEAVE_TOLERANCE: Real = 1e-2;

/// Golden-section iterations refining the periodic state nearest a pulled state.
const REFINE_ITERATIONS: usize = 48;

/// A finite sheet as a mechanism of its own.
#[derive(Debug, Clone)]
pub struct SheetMechanism {
    /// The mechanism: tile k is the sheet's tile `order[k]`; tile 0 is the held grip.
    pub mech: Mechanism,
    /// The sheet tile of each mechanism tile.
    pub order: Vec<usize>,
    /// The mechanism's tiles as a sheet of one cell (for the sheet measures).
    pub sheet: FiniteSheet,
}

impl SheetMechanism {
    /// Poses of the sheet's tiles, in the sheet's order, at state q of [`Self::mech`].
    pub fn poses(&self, q: &DVec) -> Vec<(Vec2, Real)> {
        let mut out = vec![(Vec2::zeros(), 0.0); self.order.len()];
        for (k, &t) in self.order.iter().enumerate() {
            out[t] = self.mech.pose(q, k);
        }
        out
    }

    /// The state of [`Self::mech`] with the sheet's tiles where the periodic state `q` of
    /// `periodic` (the mechanism the sheet was cut from) puts them.
    pub fn state_at(&self, sheet: &FiniteSheet, periodic: &Mechanism, q: &DVec) -> DVec {
        let poses = sheet.poses(periodic, q);
        let layout = self.mech.layout;
        let mut out = self.mech.rest.clone();
        for (k, &t) in self.order.iter().enumerate() {
            let (p, th) = poses[t];
            out[layout.tile(k)] = p.x;
            out[layout.tile(k) + 1] = p.y;
            out[layout.tile(k) + 2] = th;
        }
        out
    }

    /// The mechanism tile of sheet tile `t`.
    pub fn tile_of(&self, t: usize) -> usize {
        self.order
            .iter()
            .position(|&s| s == t)
            .expect("every sheet tile is a mechanism tile")
    }
}

/// `sheet` of the periodic mechanism `mech` as a mechanism of its own, with sheet tile
/// `held` first, starting (its `rest`) where the periodic state `start` puts the tiles.
pub fn sheet_mechanism(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    held: usize,
    start: &DVec,
) -> Result<SheetMechanism, FiniteError> {
    let n = sheet.len();
    if held >= n {
        return Err(FiniteError::BadRequest(format!(
            "grip tile {held} is not a tile of the sheet (it has {n})"
        )));
    }
    let order: Vec<usize> = std::iter::once(held)
        .chain((0..n).filter(|&t| t != held))
        .collect();
    let mut place = vec![0; n];
    for (k, &t) in order.iter().enumerate() {
        place[t] = k;
    }
    let poses = sheet.poses(mech, start);
    let layout = StateLayout { tiles: n };
    let mut rest = DVec::zeros(layout.len());
    let (mut lo, mut hi) = (Vec2::repeat(Real::INFINITY), Vec2::repeat(-Real::INFINITY));
    let mut reach: Real = 0.0;
    for (k, &t) in order.iter().enumerate() {
        let (p, th) = poses[t];
        rest[layout.tile(k)] = p.x;
        rest[layout.tile(k) + 1] = p.y;
        rest[layout.tile(k) + 2] = th;
        lo = lo.inf(&p);
        hi = hi.sup(&p);
        let shape = &mech.tile_shapes[sheet.tiles[t].tile];
        reach = reach.max(shape.iter().map(|v| v.norm()).fold(0.0, Real::max));
    }
    // Copies of the sheet this far apart never meet, however it opens: its tiles stay within
    // the sheet's diameter plus two tile reaches even when pulled straight, and ten times
    // that leaves room for a sheet that stretches (the deployment's own stretch limit ends a
    // run long before).
    let span = 10.0 * ((hi - lo).norm() + 2.0 * reach + 1.0);
    rest[layout.u()] = span;
    rest[layout.w() + 1] = span;
    let joints = sheet
        .joints
        .iter()
        .map(|j| {
            let joint = mech.joints[j.joint];
            Joint {
                tile_a: place[j.a],
                tile_b: place[j.b],
                offset: [0.0, 0.0],
                ..joint
            }
        })
        .collect();
    let tile_shapes = order
        .iter()
        .map(|&t| mech.tile_shapes[sheet.tiles[t].tile].clone())
        .collect();
    let own = Mechanism {
        layout,
        joints,
        tile_shapes,
        length_scale: mech.length_scale,
        rest,
    };
    let as_sheet = FiniteSheet {
        tiles: (0..n)
            .map(|k| SheetTile {
                cell: [0, 0],
                tile: k,
            })
            .collect(),
        joints: own
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| SheetJoint {
                a: j.tile_a,
                b: j.tile_b,
                joint: i,
            })
            .collect(),
    };
    Ok(SheetMechanism {
        mech: own,
        order,
        sheet: as_sheet,
    })
}

/// The two tiles a tester would hold to pull the sheet open: of the tiles in the sheet's
/// largest piece held by at least two pins, the two furthest apart along the direction in
/// which the periodic motion stretches the sheet most from the closed state to `opened` (a
/// periodic state of `mech`); among tiles within half a length unit of an end, the one
/// nearest the sheet's middle line (then the lower index). `None` when fewer than two tiles
/// qualify or the sheet does not stretch.
pub fn default_grips(sheet: &FiniteSheet, mech: &Mechanism, opened: &DVec) -> Option<[usize; 2]> {
    let closed = sheet.poses(mech, &mech.rest);
    let open = sheet.poses(mech, opened);
    let axis = stretch_axis(&closed, &open)?;
    let pins = sheet.pins();
    let largest = sheet.in_largest_piece();
    let held: Vec<usize> = (0..sheet.len())
        .filter(|&t| pins[t] >= 2 && largest[t])
        .collect();
    if held.len() < 2 {
        return None;
    }
    let along = |t: usize| closed[t].0.dot(&axis);
    let across = |t: usize| closed[t].0.x * -axis.y + closed[t].0.y * axis.x;
    let (lo, hi) = held
        .iter()
        .fold((Real::INFINITY, -Real::INFINITY), |(a, b), &t| {
            (a.min(across(t)), b.max(across(t)))
        });
    let mid = 0.5 * (lo + hi);
    let end = |sign: Real| -> usize {
        let far = held
            .iter()
            .map(|&t| sign * along(t))
            .fold(-Real::INFINITY, Real::max);
        held.iter()
            .copied()
            .filter(|&t| sign * along(t) >= far - 0.5)
            .min_by(|&a, &b| {
                (across(a) - mid)
                    .abs()
                    .total_cmp(&(across(b) - mid).abs())
                    .then(a.cmp(&b))
            })
            .expect("the furthest tile is at the end")
    };
    let (a, b) = (end(-1.0), end(1.0));
    (a != b).then_some([a, b])
}

/// The unit direction (in the closed sheet) that the best affine map of the tile centres
/// from `closed` to `open` stretches most.
fn stretch_axis(closed: &[(Vec2, Real)], open: &[(Vec2, Real)]) -> Option<Vec2> {
    let n = closed.len() as Real;
    let xm = closed.iter().map(|p| p.0).sum::<Vec2>() / n;
    let ym = open.iter().map(|p| p.0).sum::<Vec2>() / n;
    let (mut yx, mut xx) = (nalgebra::Matrix2::zeros(), nalgebra::Matrix2::zeros());
    for (a, b) in closed.iter().zip(open) {
        let (a, b) = (a.0 - xm, b.0 - ym);
        yx += b * a.transpose();
        xx += a * a.transpose();
    }
    let f = yx * xx.try_inverse()?;
    let svd = f.svd(false, true);
    let v_t = svd.v_t?;
    let k = if svd.singular_values[0] >= svd.singular_values[1] {
        0
    } else {
        1
    };
    let axis = Vec2::new(v_t[(k, 0)], v_t[(k, 1)]);
    (axis.norm() > 0.0 && axis.iter().all(|x| x.is_finite())).then(|| axis.normalize())
}

/// How far a sheet's tiles are from the periodic motion at one state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionDeviation {
    /// Largest vertex distance over every tile (units of L).
    pub max: Real,
    /// Per tile (sheet order), its largest vertex distance (units of L).
    pub tiles: Vec<Real>,
    /// t of the periodic state that fits best.
    pub periodic_t: Real,
}

/// Vertices of every tile at `poses` (sheet order).
fn vertices(sheet: &FiniteSheet, mech: &Mechanism, poses: &[(Vec2, Real)]) -> Vec<Vec<Vec2>> {
    sheet
        .tiles
        .iter()
        .zip(poses)
        .map(|(t, &(p, th))| {
            let r = rotation(th);
            mech.tile_shapes[t.tile].iter().map(|v| p + r * v).collect()
        })
        .collect()
}

/// Per tile, the largest distance between its vertices in `a` and in `b` after the rigid
/// motion that best maps the tile centres of `a` onto those of `b` (least squares), fitted
/// again on the half of the tiles that fit best: flaps that swing away do not drag the fit
/// of the tiles that follow.
fn aligned_distances(
    centres_a: &[Vec2],
    a: &[Vec<Vec2>],
    centres_b: &[Vec2],
    b: &[Vec<Vec2>],
) -> Vec<Real> {
    let all = vec![true; centres_a.len()];
    let first = distances_after_fit(centres_a, a, centres_b, b, &all);
    let mut sorted = first.clone();
    sorted.sort_by(Real::total_cmp);
    let median = sorted[(sorted.len() - 1) / 2];
    let best: Vec<bool> = first.iter().map(|&d| d <= median).collect();
    distances_after_fit(centres_a, a, centres_b, b, &best)
}

/// [`aligned_distances`] with the rigid motion fitted on the tiles marked `fit`.
fn distances_after_fit(
    centres_a: &[Vec2],
    a: &[Vec<Vec2>],
    centres_b: &[Vec2],
    b: &[Vec<Vec2>],
    fit: &[bool],
) -> Vec<Real> {
    let chosen = || {
        centres_a
            .iter()
            .zip(centres_b)
            .zip(fit)
            .filter(|(_, &f)| f)
            .map(|(p, _)| p)
    };
    let n = chosen().count().max(1) as Real;
    let ma = chosen().map(|(x, _)| x).sum::<Vec2>() / n;
    let mb = chosen().map(|(_, y)| y).sum::<Vec2>() / n;
    let (mut dot, mut cross) = (0.0, 0.0);
    for (x, y) in chosen() {
        let (x, y) = (x - ma, y - mb);
        dot += x.dot(&y);
        cross += x.x * y.y - x.y * y.x;
    }
    let r = rotation(cross.atan2(dot));
    a.iter()
        .zip(b)
        .map(|(pa, pb)| {
            pa.iter()
                .zip(pb)
                .map(|(va, vb)| (r * (va - ma) + mb - vb).norm())
                .fold(0.0, Real::max)
        })
        .collect()
}

/// How far the sheet at tile poses `poses` is from the periodic motion `periodic` (a
/// trajectory of `mech`): the accepted state that fits best, then the best state between its
/// neighbours (projected onto the joints, [`project_between`]) by golden-section search.
pub fn motion_deviation(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    periodic: &Trajectory,
    settings: &DeploySettings,
    poses: &[(Vec2, Real)],
) -> MotionDeviation {
    let centres: Vec<Vec2> = poses.iter().map(|&(p, _)| p).collect();
    let verts = vertices(sheet, mech, poses);
    let against = |q: &DVec| -> Vec<Real> {
        let other = sheet.poses(mech, q);
        let oc: Vec<Vec2> = other.iter().map(|&(p, _)| p).collect();
        aligned_distances(&centres, &verts, &oc, &vertices(sheet, mech, &other))
    };
    let worst = |d: &[Real]| d.iter().copied().fold(0.0, Real::max);
    let steps = &periodic.steps;
    let (mut best_k, mut best) = (0, against(&steps[0].q));
    for (k, s) in steps.iter().enumerate().skip(1) {
        let d = against(&s.q);
        if worst(&d) < worst(&best) {
            (best_k, best) = (k, d);
        }
    }
    // The arc position s in [k − 1, k + 1] (in steps) nearest the pulled state.
    let last = steps.len() - 1;
    let at = |s: Real| -> Option<(Vec<Real>, Real)> {
        let k = (s.floor() as usize).min(last.saturating_sub(1));
        let f = s - k as Real;
        let q = if f <= 0.0 || last == 0 {
            steps[k].q.clone()
        } else if f >= 1.0 {
            steps[k + 1].q.clone()
        } else {
            project_between(mech, periodic, k, f, settings).ok()?
        };
        let t = periodic.t(k) + f * (periodic.t((k + 1).min(last)) - periodic.t(k));
        Some((against(&q), t))
    };
    let mut out = (best.clone(), periodic.t(best_k));
    if last > 0 {
        let (mut lo, mut hi) = (
            best_k.saturating_sub(1) as Real,
            (best_k + 1).min(last) as Real,
        );
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let value = |s: Real| at(s).map_or(Real::INFINITY, |(d, _)| worst(&d));
        let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        let (mut f1, mut f2) = (value(x1), value(x2));
        for _ in 0..REFINE_ITERATIONS {
            if f1 < f2 {
                hi = x2;
                (x2, f2) = (x1, f1);
                x1 = hi - g * (hi - lo);
                f1 = value(x1);
            } else {
                lo = x1;
                (x1, f1) = (x2, f2);
                x2 = lo + g * (hi - lo);
                f2 = value(x2);
            }
        }
        if let Some((d, t)) = at(if f1 < f2 { x1 } else { x2 }) {
            if worst(&d) < worst(&out.0) {
                out = (d, t);
            }
        }
    }
    MotionDeviation {
        max: worst(&out.0),
        tiles: out.0,
        periodic_t: out.1,
    }
}

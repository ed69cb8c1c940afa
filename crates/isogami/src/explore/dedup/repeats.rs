//! Step 2 of deduplication: a design on an a×b cell that is invariant under i·t1 (i a proper
//! divisor of a) or j·t2, and whose motion is periodic under that translation too, is the
//! repeat of a design on the smaller (i×b or a×j) cell, which has fewer edges and is explored
//! itself. Orbit representatives are tested against the images of these translations under
//! the symmetries, so that the test does not depend on which member represents the orbit.
//! (Invariant joints with an anti-periodic motion are a genuinely new, period-doubling motion
//! and are kept.)

use super::lattice::{edge_ends, Lattice};
use super::motion::MOTION_TOL;
use super::symmetry::{try_symmetry, Symmetry};
use crate::cell::UnitCell;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Mat2, Vec2};
use crate::topology::JointChoice;

/// True when `joints` and the motion `v` are both invariant under the translation by `t`
/// (world units of the cell; a symmetry of the sheet): the design repeats a smaller one.
/// Testing many designs of one cell, prepare the translation once ([`RepeatTest`]).
pub fn is_repeat(
    cell: &UnitCell,
    mech: &Mechanism,
    joints: &[JointChoice],
    v: &DVec,
    t: Vec2,
) -> bool {
    RepeatTest::new(cell, t).holds(mech, joints, v)
}

/// One translation of [`repeat_translations`] prepared for the designs of one cell: what it
/// does to the cell's edges and to its tiles depends on the cell alone.
#[derive(Debug, Clone)]
pub struct RepeatTest {
    t: Vec2,
    /// The symmetry the translation induces on the edges; `None`: it is not a symmetry of
    /// the sheet, and no design repeats under it.
    symmetry: Option<Symmetry>,
    /// Per tile i, the tile j and cell offset k with centroid_i + t = centroid_j + k·(u, w);
    /// `None` when some tile has no such image.
    images: Option<Vec<(usize, [i32; 2])>>,
}

impl RepeatTest {
    /// Prepares the translation by `t` on `cell`.
    pub fn new(cell: &UnitCell, t: Vec2) -> RepeatTest {
        let lat = Lattice::new(cell);
        let ends = edge_ends(cell);
        let symmetry = try_symmetry(&lat, &ends, &Mat2::identity(), &t, true);
        let images = cell
            .tiles
            .iter()
            .map(|tile| {
                let target = tile.centroid + t;
                cell.tiles
                    .iter()
                    .enumerate()
                    .find_map(|(j, o)| lat.coords(&(target - o.centroid)).map(|k| (j, k)))
            })
            .collect();
        RepeatTest {
            t,
            symmetry,
            images,
        }
    }

    /// True when `joints` and the motion `v` (of a design on the prepared cell; `mech`: any
    /// mechanism of it) are both invariant under the translation.
    pub fn holds(&self, mech: &Mechanism, joints: &[JointChoice], v: &DVec) -> bool {
        let Some(sym) = &self.symmetry else {
            return false;
        };
        if !sym.fixes(joints) {
            return false;
        }
        // Motion periodicity: v_π(i) + k·(u̇, ẇ) = v_i + L̇ t and ω_π(i) = ω_i for every tile.
        let l = mech.layout;
        let scale = mech.length_scale;
        let (u, w) = mech.lattice(&mech.rest);
        let basis = Mat2::new(u.x, w.x, u.y, w.y);
        let du = Vec2::new(v[l.u()], v[l.u() + 1]);
        let dw = Vec2::new(v[l.w()], v[l.w() + 1]);
        let Some(inv) = basis.try_inverse() else {
            return false;
        };
        let grad = Mat2::new(du.x, dw.x, du.y, dw.y) * inv;
        let lt = grad * (self.t / scale);
        let Some(images) = &self.images else {
            return false;
        };
        images.iter().enumerate().all(|(i, &(j, k))| {
            let vi = Vec2::new(v[l.tile(i)], v[l.tile(i) + 1]);
            let vj = Vec2::new(v[l.tile(j)], v[l.tile(j) + 1]);
            let lhs = vj + du * f64::from(k[0]) + dw * f64::from(k[1]);
            (lhs - vi - lt).norm() <= MOTION_TOL
                && (v[l.tile(j) + 2] - v[l.tile(i) + 2]).abs() <= MOTION_TOL
        })
    }
}

/// The translations whose invariance makes a design a repeat of a smaller explored cell: i·t1
/// for proper divisors i of a and j·t2 for proper divisors j of b (t1 = u/a, t2 = w/b), and
/// their images M·i·t1, M·j·t2 under the linear part of every symmetry (an orbit's
/// representative is invariant under the conjugate of its sibling's translation), reduced
/// modulo the supercell lattice and without repetition.
pub fn repeat_translations(cell: &UnitCell, symmetries: &[Symmetry]) -> Vec<Vec2> {
    let (a, b) = (i32::from(cell.dims.a()), i32::from(cell.dims.b()));
    // Fractional lattice coordinates (numerator over a common denominator a·b).
    let den = a * b;
    let mut base: Vec<[i32; 2]> = Vec::new();
    base.extend((1..a).filter(|i| a % i == 0).map(|i| [i * b, 0]));
    base.extend((1..b).filter(|j| b % j == 0).map(|j| [0, j * a]));
    let mut seen: Vec<[i32; 2]> = Vec::new();
    for s in symmetries {
        for c in &base {
            let l = s.lattice;
            let img = [
                (c[0] * l[0][0] + c[1] * l[1][0]).rem_euclid(den),
                (c[0] * l[0][1] + c[1] * l[1][1]).rem_euclid(den),
            ];
            if img != [0, 0] && !seen.contains(&img) {
                seen.push(img);
            }
        }
    }
    seen.sort_unstable();
    let den = f64::from(den);
    seen.iter()
        .map(|c| cell.u * (f64::from(c[0]) / den) + cell.w * (f64::from(c[1]) / den))
        .collect()
}

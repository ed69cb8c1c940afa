//! Removing duplicate designs of one cell (paper §4.1, third eigen-analysis check), in three
//! steps, the first two keeping the lexicographically smallest joint string (= smallest spec,
//! since family, parameters and cell are shared), the third the design with the most pin
//! joints (ties: the smallest spec):
//!
//! 1. **Symmetry.** The symmetry group of the sheet — every isometry of the plane that maps
//!    the cell's edge network onto itself modulo the supercell lattice and maps that lattice
//!    onto itself — is computed geometrically: each candidate maps edge 0 onto some edge (two
//!    directions, proper or improper), and is kept when every edge lands on an edge. This
//!    covers translations inside the supercell (cyclic shifts of the copies), rotations,
//!    reflections and glides of the straight-edged default tiling (including symmetries the
//!    default shape has beyond its isohedral type's). A joint at endpoint A of edge e moves to
//!    the image endpoint of the image edge. Designs in one orbit are one, represented by the
//!    orbit's smallest joint string ([`SymmetryGroup::canonical_key`]); the same group acting on
//!    joint masks lets the expansion visit one mask per orbit.
//! 2. **Repeats.** A design on an a×b cell that is invariant under i·t1 (i a proper divisor of
//!    a) or j·t2, and whose motion is periodic under that translation too, is the repeat of a
//!    design on the smaller (i×b or a×j) cell, which has fewer edges and is explored itself.
//!    Orbit representatives are tested against the images of these translations under the
//!    symmetries, so that the test does not depend on which member represents the orbit.
//!    (Invariant joints with an anti-periodic motion are a genuinely new, period-doubling
//!    motion and are kept.)
//! 3. **Same motion.** Two designs whose motions agree are one. The comparison uses an
//!    invariant that does not depend on which tile is fixed, on the tile or edge order, on the
//!    sign or scale of the motion vector, or on an isometry of the sheet: the sorted multiset,
//!    over all unique edges, of (|ω_b − ω_a|, smaller and larger |relative velocity| at the
//!    two endpoints), plus |tr D| and det D of the symmetric part D of the lattice velocity
//!    gradient [u̇ ẇ][u w]⁻¹, normalised to unit length. Invariants match when every entry
//!    agrees to [`MOTION_TOL`].
//!
//! Not covered: designs on different cells (e.g. a 2×1 design and its 90°-rotated 1×2 twin, or
//! a 2×2 design invariant only under t1 + t2), symmetries of the isohedral type that the
//! default shape does not have, and invariants that tie within noise but sort differently
//! (sort keys are rounded to 1e-8; such a miss keeps a duplicate, never drops a design).
//! Plain data in and out; no I/O.

use super::separate::{edge_rates, separation, Separation};
use crate::cell::{End, UnitCell};
use crate::kinematics::Mechanism;
use crate::math::{cross, DVec, Mat2, Vec2};
use crate::mobility::{analyze, Mobility, MobilitySettings};
use crate::topology::JointChoice;
use serde::Serialize;
use std::collections::BTreeSet;

/// Entry-wise tolerance of the normalised motion invariant, and of the periodicity test of
/// the repeat check (on the unit motion vector).
pub const MOTION_TOL: f64 = 1e-6;

/// Geometric matching tolerance, relative to the mean edge length.
const GEOM_REL_TOL: f64 = 1e-6;

/// One symmetry of the sheet acting on the cell's unique edges.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Symmetry {
    /// Edge e goes to edge `edge_map[e]`.
    pub edge_map: Vec<usize>,
    /// True when endpoint A of e goes to endpoint B of its image.
    pub swap: Vec<bool>,
    /// Orientation-preserving.
    pub proper: bool,
    /// Action of the linear part on the supercell lattice: M·u = l[0][0]·u + l[0][1]·w and
    /// M·w = l[1][0]·u + l[1][1]·w.
    pub lattice: [[i32; 2]; 2],
}

impl Symmetry {
    /// The image of a joint assignment.
    pub fn apply(&self, joints: &[JointChoice]) -> Vec<JointChoice> {
        let mut out = vec![JointChoice::None; joints.len()];
        for (e, &j) in joints.iter().enumerate() {
            out[self.edge_map[e]] = if self.swap[e] { swapped(j) } else { j };
        }
        out
    }
}

fn swapped(j: JointChoice) -> JointChoice {
    match j {
        JointChoice::A => JointChoice::B,
        JointChoice::B => JointChoice::A,
        other => other,
    }
}

/// The joint string of an assignment (the JOINTS field of a spec).
pub fn joint_string(joints: &[JointChoice]) -> String {
    joints.iter().map(|j| j.to_char()).collect()
}

/// Lattice helper: coordinates of points in the basis (u, w) and membership tests.
struct Lattice {
    u: Vec2,
    w: Vec2,
    det: f64,
    tol: f64,
}

impl Lattice {
    fn new(cell: &UnitCell) -> Lattice {
        Lattice {
            u: cell.u,
            w: cell.w,
            det: cross(&cell.u, &cell.w),
            tol: GEOM_REL_TOL * cell.mean_edge_length(),
        }
    }

    /// The integer lattice coordinates of `p`, if `p` is a lattice vector.
    fn coords(&self, p: &Vec2) -> Option<[i32; 2]> {
        let a = (cross(p, &self.w) / self.det).round();
        let b = (cross(&self.u, p) / self.det).round();
        if (p - (self.u * a + self.w * b)).norm() <= self.tol && a.abs() < 1e6 && b.abs() < 1e6 {
            Some([a as i32, b as i32])
        } else {
            None
        }
    }
}

/// Every symmetry of the sheet that preserves the supercell lattice, modulo that lattice,
/// identity first. Computed from the cell's geometry (see the module docs).
pub fn sheet_symmetries(cell: &UnitCell) -> Vec<Symmetry> {
    let lat = Lattice::new(cell);
    let ends: Vec<(Vec2, Vec2)> = (0..cell.edges.len())
        .map(|e| (cell.endpoint(e, End::A), cell.endpoint(e, End::B)))
        .collect();
    let mut out: Vec<Symmetry> = Vec::new();
    let Some(&(a0, b0)) = ends.first() else {
        return out;
    };
    let d0 = b0 - a0;
    let len2 = d0.norm_squared();
    for &(x, y) in &ends {
        for (p, q) in [(x, y), (y, x)] {
            let d = q - p;
            if (d.norm_squared() - len2).abs() > 2.0 * lat.tol * d0.norm() {
                continue;
            }
            let (c, s) = (d0.dot(&d) / len2, cross(&d0, &d) / len2);
            let proper = Mat2::new(c, -s, s, c);
            let (c2, s2) = (
                (d0.x * d.x - d0.y * d.y) / len2,
                (d0.x * d.y + d0.y * d.x) / len2,
            );
            let improper = Mat2::new(c2, s2, s2, -c2);
            for (m, is_proper) in [(proper, true), (improper, false)] {
                let t = p - m * a0;
                if let Some(sym) = try_symmetry(&lat, &ends, &m, &t, is_proper) {
                    if !out.contains(&sym) {
                        out.push(sym);
                    }
                }
            }
        }
    }
    // A fixed order; the identity (edge_map 0, 1, 2, …, no swaps) sorts first.
    out.sort_by(|a, b| (&a.edge_map, &a.swap, !a.proper).cmp(&(&b.edge_map, &b.swap, !b.proper)));
    out
}

#[cfg(test)]
fn is_identity(s: &Symmetry) -> bool {
    s.edge_map.iter().enumerate().all(|(k, &e)| k == e)
}

/// The edge action of x ↦ m·x + t, if it maps the lattice and the edge network onto
/// themselves.
fn try_symmetry(
    lat: &Lattice,
    ends: &[(Vec2, Vec2)],
    m: &Mat2,
    t: &Vec2,
    proper: bool,
) -> Option<Symmetry> {
    let lattice = [lat.coords(&(m * lat.u))?, lat.coords(&(m * lat.w))?];
    let n = ends.len();
    let mut edge_map = vec![usize::MAX; n];
    let mut swap = vec![false; n];
    let mut used = vec![false; n];
    for (e, &(a, b)) in ends.iter().enumerate() {
        let (ga, gb) = (m * a + t, m * b + t);
        let hit = ends.iter().enumerate().find_map(|(f, &(fa, fb))| {
            for (pa, pb, sw) in [(fa, fb, false), (fb, fa, true)] {
                let shift = ga - pa;
                if lat.coords(&shift).is_some() && (gb - pb - shift).norm() <= lat.tol {
                    return Some((f, sw));
                }
            }
            None
        });
        let (f, sw) = hit?;
        if used[f] {
            return None;
        }
        used[f] = true;
        edge_map[e] = f;
        swap[e] = sw;
    }
    Some(Symmetry {
        edge_map,
        swap,
        proper,
        lattice,
    })
}

/// The sheet's symmetry group acting on joint assignments, with assignments encoded as
/// base-3 keys (edge 0 most significant; `-` = 0, `a` = 1, `b` = 2) whose numeric order is
/// the order of joint strings.
#[derive(Debug, Clone, PartialEq)]
pub struct SymmetryGroup {
    /// The symmetries, identity first.
    pub symmetries: Vec<Symmetry>,
    /// Place value of each edge's digit.
    place: Vec<u64>,
}

impl SymmetryGroup {
    /// The group of `cell` (see [`sheet_symmetries`]). Keys are exact for m ≤ 40 edges (they
    /// saturate beyond).
    pub fn new(cell: &UnitCell) -> SymmetryGroup {
        let m = cell.edges.len();
        let place = (0..m)
            .map(|e| 3u64.saturating_pow((m - 1 - e) as u32))
            .collect();
        SymmetryGroup {
            symmetries: sheet_symmetries(cell),
            place,
        }
    }

    /// Number of symmetries.
    pub fn len(&self) -> usize {
        self.symmetries.len()
    }

    /// True when no symmetry was found (only for a cell without edges).
    pub fn is_empty(&self) -> bool {
        self.symmetries.is_empty()
    }

    /// The key of an assignment.
    pub fn key(&self, joints: &[JointChoice]) -> u64 {
        joints.iter().zip(&self.place).fold(0u64, |acc, (&j, &p)| {
            acc.saturating_add(digit(j).saturating_mul(p))
        })
    }

    /// The assignment of a key.
    pub fn joints_of(&self, key: u64) -> Vec<JointChoice> {
        self.place
            .iter()
            .map(|&p| match key / p % 3 {
                0 => JointChoice::None,
                1 => JointChoice::A,
                _ => JointChoice::B,
            })
            .collect()
    }

    /// The smallest key in the orbit of `joints` (the lexicographically smallest joint
    /// string), and the orbit's size.
    pub fn canonical_key(&self, joints: &[JointChoice]) -> (u64, usize) {
        let mut images: Vec<u64> = self
            .symmetries
            .iter()
            .map(|s| {
                joints.iter().enumerate().fold(0u64, |acc, (e, &j)| {
                    let j = if s.swap[e] { swapped(j) } else { j };
                    acc.saturating_add(digit(j).saturating_mul(self.place[s.edge_map[e]]))
                })
            })
            .collect();
        images.sort_unstable();
        images.dedup();
        (images.first().copied().unwrap_or(0), images.len().max(1))
    }

    /// The smallest image of a joint mask (bit k = edge k) and the mask's orbit size.
    pub fn mask_orbit(&self, mask: u32) -> (u32, usize) {
        let mut images: Vec<u32> = self
            .symmetries
            .iter()
            .map(|s| {
                (0..s.edge_map.len())
                    .filter(|&e| mask >> e & 1 == 1)
                    .fold(0u32, |acc, e| acc | 1 << s.edge_map[e])
            })
            .collect();
        images.sort_unstable();
        images.dedup();
        (images.first().copied().unwrap_or(mask), images.len().max(1))
    }
}

fn digit(j: JointChoice) -> u64 {
    match j {
        JointChoice::None => 0,
        JointChoice::A => 1,
        // `Both` never occurs in explored designs; it shares B's digit.
        JointChoice::B | JointChoice::Both => 2,
    }
}

/// A tile-fixing-independent, order-independent fingerprint of a first-order motion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionInvariant {
    /// Normalised entries (see the module docs).
    pub values: Vec<f64>,
}

impl MotionInvariant {
    /// True when both have the same length and agree entry-wise to `tol`.
    pub fn matches(&self, other: &MotionInvariant, tol: f64) -> bool {
        self.values.len() == other.values.len()
            && self
                .values
                .iter()
                .zip(&other.values)
                .all(|(a, b)| (a - b).abs() <= tol)
    }
}

/// Width of the buckets of [`MotionIndex`] on the sum of an invariant's entries. Entries that
/// agree to `tol` give sums that agree to `len · tol` ≤ 1e-4 for `tol` ≤ 1e-6 and up to 100
/// entries, less than a bucket, so neighbouring buckets hold every possible match.
const BUCKET: f64 = 1e-3;

/// Motion invariants indexed for matching: buckets on (length, sum of entries), so a lookup
/// compares against a few candidates instead of all.
#[derive(Debug, Clone, Default)]
pub struct MotionIndex {
    items: Vec<MotionInvariant>,
    buckets: std::collections::HashMap<(usize, i64), Vec<usize>>,
}

impl MotionIndex {
    /// An empty index.
    pub fn new() -> MotionIndex {
        MotionIndex::default()
    }

    fn bucket(inv: &MotionInvariant) -> i64 {
        (inv.values.iter().sum::<f64>() / BUCKET).floor() as i64
    }

    /// The smallest id of a stored invariant that matches `inv` to `tol` (≤ 1e-6).
    pub fn find(&self, inv: &MotionInvariant, tol: f64) -> Option<usize> {
        let b = Self::bucket(inv);
        let len = inv.values.len();
        (b - 1..=b + 1)
            .filter_map(|k| self.buckets.get(&(len, k)))
            .flatten()
            .copied()
            .filter(|&i| self.items[i].matches(inv, tol))
            .min()
    }

    /// Stores `inv` and returns its id (ids count up from 0).
    pub fn insert(&mut self, inv: MotionInvariant) -> usize {
        let id = self.items.len();
        self.buckets
            .entry((inv.values.len(), Self::bucket(&inv)))
            .or_default()
            .push(id);
        self.items.push(inv);
        id
    }
}

/// The motion invariant of state velocity `v` on `cell` (`mech`: any mechanism of the cell).
pub fn motion_invariant(cell: &UnitCell, mech: &Mechanism, v: &DVec) -> MotionInvariant {
    let rates = edge_rates(cell, mech, v);
    let mut tuples: Vec<[f64; 3]> = rates
        .iter()
        .map(|r| {
            let da = Vec2::new(r.relative[0][0], r.relative[0][1]).norm();
            let db = Vec2::new(r.relative[1][0], r.relative[1][1]).norm();
            [r.rotation.abs(), da.min(db), da.max(db)]
        })
        .collect();
    let d = strain_rate(mech, v);
    let linear_norm = (tuples
        .iter()
        .flat_map(|t| t.iter())
        .map(|x| x * x)
        .sum::<f64>()
        + d.trace().powi(2))
    .sqrt();
    let s = if linear_norm > 0.0 { linear_norm } else { 1.0 };
    for t in &mut tuples {
        for x in t.iter_mut() {
            *x /= s;
        }
    }
    let key = |t: &[f64; 3]| t.map(|x| (x * 1e8).round() as i64);
    tuples.sort_by_key(key);
    let mut values: Vec<f64> = tuples.into_iter().flatten().collect();
    values.push(d.trace().abs() / s);
    values.push(d.determinant() / (s * s));
    MotionInvariant { values }
}

/// Symmetric part of the lattice velocity gradient [u̇ ẇ][u w]⁻¹ at the closed state.
fn strain_rate(mech: &Mechanism, v: &DVec) -> Mat2 {
    let (u, w) = mech.lattice(&mech.rest);
    let l = mech.layout;
    let basis = Mat2::new(u.x, w.x, u.y, w.y);
    let rates = Mat2::new(v[l.u()], v[l.w()], v[l.u() + 1], v[l.w() + 1]);
    let grad = rates * basis.try_inverse().unwrap_or_else(Mat2::zeros);
    (grad + grad.transpose()) * 0.5
}

/// True when `joints` and the motion `v` are both invariant under the translation by `t`
/// (world units of the cell; a symmetry of the sheet): the design repeats a smaller one.
pub fn is_repeat(
    cell: &UnitCell,
    mech: &Mechanism,
    joints: &[JointChoice],
    v: &DVec,
    t: Vec2,
) -> bool {
    let lat = Lattice::new(cell);
    let ends: Vec<(Vec2, Vec2)> = (0..cell.edges.len())
        .map(|e| (cell.endpoint(e, End::A), cell.endpoint(e, End::B)))
        .collect();
    let Some(sym) = try_symmetry(&lat, &ends, &Mat2::identity(), &t, true) else {
        return false;
    };
    if sym.apply(joints) != joints {
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
    let lt = grad * (t / scale);
    for (i, tile) in cell.tiles.iter().enumerate() {
        let target = tile.centroid + t;
        let Some((j, k)) = cell
            .tiles
            .iter()
            .enumerate()
            .find_map(|(j, o)| lat.coords(&(target - o.centroid)).map(|k| (j, k)))
        else {
            return false;
        };
        let vi = Vec2::new(v[l.tile(i)], v[l.tile(i) + 1]);
        let vj = Vec2::new(v[l.tile(j)], v[l.tile(j) + 1]);
        let lhs = vj + du * f64::from(k[0]) + dw * f64::from(k[1]);
        if (lhs - vi - lt).norm() > MOTION_TOL
            || (v[l.tile(j) + 2] - v[l.tile(i) + 2]).abs() > MOTION_TOL
        {
            return false;
        }
    }
    true
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

/// A design that survived deduplication.
#[derive(Debug, Clone)]
pub struct Kept {
    /// Joint choice per unique edge: the smallest joint string of its symmetry orbit.
    pub joints: Vec<JointChoice>,
    /// Its mobility, from `mobility::analyze` (dof = 1).
    pub mobility: Mobility,
    /// Its separation verdict.
    pub separation: Separation,
    /// Size of its symmetry orbit (distinct images under the sheet's symmetries).
    pub orbit_size: usize,
    /// Other orbits merged into it because their motion matched.
    pub same_motion_merged: usize,
    /// Its motion invariant.
    pub invariant: MotionInvariant,
}

/// Counts and survivors of deduplication.
#[derive(Debug, Clone)]
pub struct DedupResult {
    /// Distinct symmetry orbits given.
    pub symmetry_classes: usize,
    /// Orbit representatives that `mobility::analyze` did not confirm at dof = 1 (expected 0).
    pub unconfirmed: usize,
    /// Orbits left after removing repeats of smaller cells.
    pub after_repeats: usize,
    /// Survivors, in joint-string order.
    pub kept: Vec<Kept>,
}

/// Number of pin joints of a joint list.
fn pin_count(joints: &[JointChoice]) -> usize {
    joints.iter().map(|j| j.ends().len()).sum()
}

/// Steps 2 and 3 of the module docs on the canonical keys of the symmetry orbits found
/// (step 1 is the keying itself). Each representative is analysed again with
/// `mobility::analyze` (`settings` as in the expansion), which also gives its reported gap and
/// motion. `mech`: any mechanism of the cell.
pub fn dedup_orbits(
    cell: &UnitCell,
    mech: &Mechanism,
    group: &SymmetryGroup,
    canonical_keys: &BTreeSet<u64>,
    settings: MobilitySettings,
) -> DedupResult {
    let translations = repeat_translations(cell, &group.symmetries);
    let mut out = DedupResult {
        symmetry_classes: canonical_keys.len(),
        unconfirmed: 0,
        after_repeats: 0,
        kept: Vec::new(),
    };
    let mut index = MotionIndex::new();
    for &key in canonical_keys {
        let joints = group.joints_of(key);
        let Ok(m) = Mechanism::new(cell, &joints) else {
            out.unconfirmed += 1;
            continue;
        };
        let mob = match analyze(&m, &m.rest, settings) {
            Ok(mob) if mob.dof == 1 && mob.motion.is_some() => mob,
            _ => {
                out.unconfirmed += 1;
                continue;
            }
        };
        let Some(v) = mob.motion.as_ref().map(|mo| mo.vector.clone()) else {
            continue;
        };
        if translations
            .iter()
            .any(|&t| is_repeat(cell, mech, &joints, &v, t))
        {
            continue;
        }
        out.after_repeats += 1;
        let inv = motion_invariant(cell, mech, &v);
        let kept = Kept {
            separation: separation(cell, mech, &joints, &v),
            orbit_size: group.canonical_key(&joints).1,
            joints,
            mobility: mob,
            same_motion_merged: 0,
            invariant: inv.clone(),
        };
        if let Some(k) = index.find(&inv, MOTION_TOL) {
            // Of designs that move alike, keep the most connected one: the stiffest
            // realisation of the motion and the one a maker builds (rotating squares with all
            // eight hinges rather than a six-hinge subset); ties keep the smaller spec.
            let merged = out.kept[k].same_motion_merged + 1;
            if pin_count(&kept.joints) > pin_count(&out.kept[k].joints) {
                out.kept[k] = Kept {
                    same_motion_merged: merged,
                    ..kept
                };
            } else {
                out.kept[k].same_motion_merged = merged;
            }
            continue;
        }
        index.insert(inv);
        out.kept.push(kept);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::CellDims;
    use crate::tiling::{Family, Tiling};

    fn cell(n: u32, a: u8, b: u8) -> UnitCell {
        let f = Family::from_number(n).unwrap();
        UnitCell::new(&Tiling::default_for(f), CellDims::new(a, b).unwrap()).unwrap()
    }

    #[test]
    fn square_grid_symmetry_group() {
        // Square grid, 2×2 cell: 4 translations × 8 point symmetries (D4).
        let c = cell(76, 2, 2);
        let syms = sheet_symmetries(&c);
        assert_eq!(syms.len(), 32);
        assert!(is_identity(&syms[0]));
        assert_eq!(syms.iter().filter(|s| s.proper).count(), 16);
    }

    #[test]
    fn keys_round_trip_and_order_like_strings() {
        let c = cell(76, 2, 2);
        let g = SymmetryGroup::new(&c);
        let a = vec![JointChoice::A; 8];
        let mut b = a.clone();
        b[7] = JointChoice::B;
        let none = vec![JointChoice::None; 8];
        assert_eq!(g.joints_of(g.key(&b)), b);
        assert!(g.key(&none) < g.key(&a) && g.key(&a) < g.key(&b));
        assert!(joint_string(&none) < joint_string(&a) && joint_string(&a) < joint_string(&b));
        // The all-jointed mask is fixed by every symmetry.
        assert_eq!(g.mask_orbit(0xFF), (0xFF, 1));
        let named = crate::topology::named_design("rotating-squares").unwrap();
        let (k, size) = g.canonical_key(&named.joints);
        assert!(k <= g.key(&named.joints));
        // Orbit–stabiliser: the orbit size divides the group order.
        assert!((1..=32).contains(&size) && 32 % size == 0);
    }

    #[test]
    fn symmetries_form_a_group() {
        for (n, a, b) in [(76, 2, 2), (1, 2, 1), (28, 1, 1), (93, 2, 1), (41, 1, 2)] {
            let c = cell(n, a, b);
            let syms = sheet_symmetries(&c);
            let m = c.edges.len();
            let probe: Vec<JointChoice> = (0..m)
                .map(|k| [JointChoice::A, JointChoice::B, JointChoice::None][k % 3])
                .collect();
            // Closure: applying any two gives the image of some one.
            let images: Vec<Vec<JointChoice>> = syms.iter().map(|s| s.apply(&probe)).collect();
            for s in &syms {
                for t in &syms {
                    let st = t.apply(&s.apply(&probe));
                    assert!(images.contains(&st), "IH{n} {a}x{b}");
                }
            }
        }
    }
}

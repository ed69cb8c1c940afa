//! Step 1 of deduplication: the symmetry group of the sheet — every isometry of the plane that
//! maps the cell's edge network onto itself modulo the supercell lattice and maps that lattice
//! onto itself — computed geometrically: each candidate maps edge 0 onto some edge (two
//! directions, proper or improper), and is kept when every edge lands on an edge. This covers
//! translations inside the supercell (cyclic shifts of the copies), rotations, reflections and
//! glides of the straight-edged default tiling (including symmetries the default shape has
//! beyond its isohedral type's). A joint at endpoint A of edge e moves to the image endpoint of
//! the image edge. Designs in one orbit are one, represented by the orbit's smallest joint
//! string ([`SymmetryGroup::canonical_key`]); the same group acting on joint masks lets the
//! expansion visit one mask per orbit.

use super::lattice::{edge_ends, Lattice};
use crate::cell::UnitCell;
use crate::math::{cross, Mat2, Vec2};
use crate::topology::JointChoice;
use serde::Serialize;

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

    /// True when the symmetry maps `joints` onto itself (`apply(joints) == joints`, without
    /// building the image).
    pub fn fixes(&self, joints: &[JointChoice]) -> bool {
        joints.len() == self.edge_map.len()
            && joints.iter().enumerate().all(|(e, &j)| {
                let image = if self.swap[e] { swapped(j) } else { j };
                joints[self.edge_map[e]] == image
            })
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

/// Every symmetry of the sheet that preserves the supercell lattice, modulo that lattice,
/// identity first. Computed from the cell's geometry (see the module docs).
pub fn sheet_symmetries(cell: &UnitCell) -> Vec<Symmetry> {
    let lat = Lattice::new(cell);
    let ends = edge_ends(cell);
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
pub(super) fn try_symmetry(
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

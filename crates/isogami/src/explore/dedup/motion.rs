//! Step 3 of deduplication: two designs whose motions agree are one. The comparison uses an
//! invariant that does not depend on which tile is fixed, on the tile or edge order, on the
//! sign or scale of the motion vector, or on an isometry of the sheet: the sorted multiset,
//! over all unique edges, of (|ω_b − ω_a|, smaller and larger |relative velocity| at the two
//! endpoints), plus |tr D| and det D of the symmetric part D of the lattice velocity gradient
//! [u̇ ẇ][u w]⁻¹, normalised to unit length. Invariants match when every entry agrees to
//! [`MOTION_TOL`]; a [`MotionIndex`] finds matches without comparing against every design.

use crate::cell::UnitCell;
use crate::explore::separate::edge_rates;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Mat2, Vec2};
use serde::{Deserialize, Serialize};

/// Entry-wise tolerance of the normalised motion invariant, and of the periodicity test of
/// the repeat check (on the unit motion vector).
pub const MOTION_TOL: f64 = 1e-6;

/// A tile-fixing-independent, order-independent fingerprint of a first-order motion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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

/// Width of the buckets of [`MotionIndex`] on two sums of an invariant's entries (plain, and
/// with alternating signs). Entries that agree to `tol` give sums that agree to `len · tol`
/// ≤ 1e-4 for `tol` ≤ 1e-6 and up to 100 entries, less than a bucket, so the neighbouring
/// buckets of both sums hold every possible match.
const BUCKET: f64 = 1e-3;

/// Where an invariant is filed: its length and the buckets of its two sums.
type BucketKey = (usize, i64, i64);

/// Motion invariants indexed for matching: buckets on (length, sum of entries, alternating
/// sum of entries), so a lookup compares against a few candidates instead of all (the plain
/// sum alone left thousands of cap-20 invariants in one bucket).
#[derive(Debug, Clone, Default)]
pub struct MotionIndex {
    items: Vec<MotionInvariant>,
    buckets: std::collections::HashMap<BucketKey, Vec<usize>>,
}

impl MotionIndex {
    /// An empty index.
    pub fn new() -> MotionIndex {
        MotionIndex::default()
    }

    fn bucket(inv: &MotionInvariant) -> BucketKey {
        let sum: f64 = inv.values.iter().sum();
        let alternating: f64 = inv
            .values
            .iter()
            .enumerate()
            .map(|(i, x)| if i % 2 == 0 { *x } else { -x })
            .sum();
        let cut = |x: f64| (x / BUCKET).floor() as i64;
        (inv.values.len(), cut(sum), cut(alternating))
    }

    /// The smallest id of a stored invariant that matches `inv` to `tol` (≤ 1e-6).
    pub fn find(&self, inv: &MotionInvariant, tol: f64) -> Option<usize> {
        let (len, b, c) = Self::bucket(inv);
        (b - 1..=b + 1)
            .flat_map(|i| (c - 1..=c + 1).map(move |j| (len, i, j)))
            .filter_map(|k| self.buckets.get(&k))
            .flatten()
            .copied()
            .filter(|&i| self.items[i].matches(inv, tol))
            .min()
    }

    /// Number of stored invariants.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// True when nothing is stored.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// The stored invariants, in id order.
    pub fn into_items(self) -> Vec<MotionInvariant> {
        self.items
    }

    /// Stores `inv` and returns its id (ids count up from 0).
    pub fn insert(&mut self, inv: MotionInvariant) -> usize {
        let id = self.items.len();
        self.buckets.entry(Self::bucket(&inv)).or_default().push(id);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// `find` returns what a scan of every stored invariant returns: the smallest id that
    /// matches, or none. Invariants drawn with a fixed seed, small entries so that the sums
    /// cross bucket edges often; queries are stored invariants moved by up to ±tol per entry
    /// (the edges included), and unrelated ones.
    #[test]
    fn find_is_the_smallest_matching_id_of_a_full_scan() {
        let mut rng = crate::test_rng::TestRng::new(11);
        let mut unit = || rng.unit();
        let tol = MOTION_TOL;
        let mut index = MotionIndex::new();
        let mut stored = Vec::new();
        for k in 0..3000 {
            let len = 5 + k % 4;
            let values: Vec<f64> = (0..len).map(|_| (unit() * 2000.0).round() * 2e-6).collect();
            let inv = MotionInvariant { values };
            index.insert(inv.clone());
            stored.push(inv);
        }
        let scan = |q: &MotionInvariant| stored.iter().position(|s| s.matches(q, tol));
        let mut found = 0;
        for k in 0..6000 {
            let q = if k % 3 == 2 {
                MotionInvariant {
                    values: (0..5 + k % 4).map(|_| unit() * 4e-3).collect(),
                }
            } else {
                let base = &stored[k % stored.len()];
                let values = base
                    .values
                    .iter()
                    .map(|x| match k % 3 {
                        0 => x + tol * (2.0 * unit() - 1.0),
                        _ => x + if unit() < 0.5 { -tol } else { tol } * 0.999_999,
                    })
                    .collect();
                MotionInvariant { values }
            };
            let want = scan(&q);
            assert_eq!(index.find(&q, tol), want, "query {k}");
            found += usize::from(want.is_some());
        }
        assert!(found >= 3990, "{found} queries matched");
    }
}

//! Cell twins: one design found on two cells of its family. The per-cell deduplication keeps
//! one design per motion within a cell, but the same sheet is found again on another cell
//! whose lattice also fits it (an a×b cell and its rotated b×a twin, a 4×1 cell and a 2×2
//! one that tile the plane with the same pattern). Such designs have the same family, the
//! same shape and the same path; a catalogue stores one of them and lists the others'
//! cells.
//!
//! Two designs are twins when they have the same family, bit-identical shape parameters
//! (samples of one family's grid), different cells, first-order motions that match at their
//! shape ([`motion_invariant`](super::motion_invariant) to [`MOTION_TOL`]) and path figures
//! (largest and final area ratio, largest and smallest principal expansion) equal to a
//! relative [`PATH_TOL`]. The design kept for a group is the first in preference order: one
//! with a one-DOF finite sheet before one without, then the smallest spec; the others point
//! at it. The rule depends only on the set of candidates, not on their order. Plain data in
//! and out; the motion analyses run in parallel on the current rayon pool.

use super::motion::MOTION_TOL;
use crate::explore::motion_classes::topology_motion;
use crate::mobility::MobilitySettings;
use crate::topology::Design;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Relative tolerance on path figures for two designs to count as one path. Twins found on
/// the default exploration agree to about 1e-15; distinct designs of one shape differ by far
/// more than this.
pub const PATH_TOL: f64 = 1e-8;

/// One design offered to [`cell_twins`].
#[derive(Debug, Clone, PartialEq)]
pub struct TwinCandidate {
    /// The design (family, shape, cell, joints).
    pub design: Design,
    /// Its spec as stored (decides ties).
    pub spec: String,
    /// Path figures: largest area ratio, final area ratio, largest and smallest principal
    /// expansion. A design with a non-finite figure has no twin.
    pub path: [f64; 4],
    /// Whether it has a one-DOF finite sheet (kept before one that does not).
    pub one_dof_sheet: bool,
}

/// For each candidate, the index of the design its twin group keeps, or None when it is kept
/// itself or has no twin (see the module docs).
pub fn cell_twins(candidates: &[TwinCandidate], settings: MobilitySettings) -> Vec<Option<usize>> {
    let mut groups: BTreeMap<(u8, Vec<u64>), Vec<usize>> = BTreeMap::new();
    for (i, c) in candidates.iter().enumerate() {
        let shape = c.design.params.iter().map(|p| p.to_bits()).collect();
        groups
            .entry((c.design.family.number(), shape))
            .or_default()
            .push(i);
    }
    let mut kept_by = vec![None; candidates.len()];
    for mut members in groups.into_values() {
        let first_dims = candidates[members[0]].design.dims;
        if members
            .iter()
            .all(|&i| candidates[i].design.dims == first_dims)
        {
            continue;
        }
        members.sort_by(|&a, &b| {
            let (a, b) = (&candidates[a], &candidates[b]);
            b.one_dof_sheet
                .cmp(&a.one_dof_sheet)
                .then_with(|| a.spec.cmp(&b.spec))
        });
        let keys: Vec<_> = members
            .par_iter()
            .map(|&i| topology_motion(&candidates[i].design, settings))
            .collect();
        let mut kept: Vec<usize> = Vec::new();
        for (m, &i) in members.iter().enumerate() {
            let Some(key) = &keys[m] else { continue };
            let c = &candidates[i];
            let twin = kept.iter().copied().find(|&k| {
                let o = &candidates[members[k]];
                o.design.dims != c.design.dims
                    && same_path(&o.path, &c.path)
                    && keys[k]
                        .as_ref()
                        .is_some_and(|ok| ok.matches(key, MOTION_TOL))
            });
            match twin {
                Some(k) => kept_by[i] = Some(members[k]),
                None => kept.push(m),
            }
        }
    }
    kept_by
}

/// Whether two designs' path figures agree to [`PATH_TOL`] (relative to each figure's size,
/// at least 1).
fn same_path(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a.iter().zip(b).all(|(x, y)| {
        x.is_finite() && y.is_finite() && (x - y).abs() <= PATH_TOL * x.abs().max(y.abs()).max(1.0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn path_figures_agree_only_within_the_tolerance_and_never_when_not_finite() {
        let a = [2.0, 1.5, 1.4, 1.1];
        let mut b = a;
        b[0] += 1e-12;
        assert!(same_path(&a, &b));
        b[0] = 2.0 + 1e-6;
        assert!(!same_path(&a, &b));
        let mut c = a;
        c[3] = f64::NAN;
        assert!(!same_path(&c, &c));
    }
}

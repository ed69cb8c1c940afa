//! Deduplication of one cell's symmetry orbits: each orbit representative is confirmed at
//! dof = 1, dropped when it repeats a smaller cell ([`super::repeats`]), and merged with an
//! earlier design whose motion matches ([`super::motion`]), keeping the design with the most
//! pin joints (ties: the smaller spec).

use super::motion::{motion_invariant, MotionIndex, MotionInvariant, MOTION_TOL};
use super::repeats::{is_repeat, repeat_translations};
use super::symmetry::SymmetryGroup;
use crate::cell::UnitCell;
use crate::explore::separate::{separation, Separation};
use crate::kinematics::Mechanism;
use crate::mobility::{analyze, Mobility, MobilitySettings};
use crate::topology::JointChoice;
use std::collections::BTreeSet;

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

/// Steps 2 and 3 of [`super`] on the canonical keys of the symmetry orbits found
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

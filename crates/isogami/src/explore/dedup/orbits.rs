//! Deduplication of one cell's symmetry orbits: each orbit representative is confirmed at
//! dof = 1, dropped when it repeats a smaller cell ([`super::repeats`]), and merged with an
//! earlier design whose motion matches ([`super::motion`]), keeping the design with the most
//! pin joints (ties: the smaller spec).

use super::motion::{motion_invariant, MotionIndex, MotionInvariant, MOTION_TOL};
use super::repeats::{is_repeat, repeat_translations};
use super::symmetry::SymmetryGroup;
use crate::cell::UnitCell;
use crate::explore::separate::{closing_rates, edge_rates, separation, Separation};
use crate::kinematics::Mechanism;
use crate::math::Vec2;
use crate::mobility::{analyze, MobilitySettings};
use crate::topology::JointChoice;
use rayon::prelude::*;
use std::collections::BTreeSet;
use std::time::{Duration, Instant};

/// A design that survived deduplication: only what the report needs, so that a cell with a
/// million distinct motions holds about 100 bytes per design plus its invariant (the full
/// mobility analysis, eigenvalues and modes, would be several kilobytes each).
#[derive(Debug, Clone)]
pub struct Kept {
    /// Joint choice per unique edge: the smallest joint string of its symmetry orbit.
    pub joints: Vec<JointChoice>,
    /// Its mobility's eigenvalue gap in decades, from `mobility::analyze` (dof = 1).
    pub gap_decades: Option<f64>,
    /// The cell area's rate of change along its motion.
    pub area_rate: f64,
    /// Its separation verdict.
    pub separation: Separation,
    /// Its largest first-order closing rates along both signs of its motion
    /// ([`closing_rates`]; `None` when not finite), for the catalogue's screen.
    pub closing: Option<[f64; 2]>,
    /// Size of its symmetry orbit (distinct images under the sheet's symmetries).
    pub orbit_size: usize,
    /// Other orbits merged into it because their motion matched.
    pub same_motion_merged: usize,
    /// Its motion invariant.
    pub invariant: MotionInvariant,
    /// Its key (`SymmetryGroup::key` of `joints`): keys order like joint strings.
    pub key: u64,
    /// Key of the first design of its motion class in key order (itself unless a more
    /// connected later design took the slot).
    pub first_key: u64,
    /// The first design's invariant, which the merge looks the class up by, when the slot was
    /// taken by a later design (`None`: it is `invariant`). Merging the deduplications of
    /// several mask parts needs it (`catalog::combine_parts`).
    pub first_invariant: Option<MotionInvariant>,
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
    /// Time spent analysing the representatives, summed over threads.
    pub work: Duration,
}

/// Number of pin joints of a joint list.
fn pin_count(joints: &[JointChoice]) -> usize {
    joints.iter().map(|j| j.ends().len()).sum()
}

/// A kept design while the merge runs; its invariant lives in the merge's [`MotionIndex`].
#[derive(Debug)]
struct Survivor {
    joints: Vec<JointChoice>,
    gap_decades: Option<f64>,
    area_rate: f64,
    separation: Separation,
    closing: Option<[f64; 2]>,
    orbit_size: usize,
    same_motion_merged: usize,
    /// Set when a later, more connected design took this slot: its own invariant (it matched
    /// the stored one to the tolerance, which stays in the index for lookups).
    replaced_invariant: Option<MotionInvariant>,
    /// Its canonical key.
    key: u64,
    /// The key of the class's first design.
    first_key: u64,
}

/// Orbit representatives analysed per parallel batch: bounds the memory held by analysed but
/// not yet merged designs.
const BATCH: usize = 4096;

/// One orbit representative after its (parallel) analysis.
enum Analysed {
    /// Not confirmed at dof = 1.
    Unconfirmed,
    /// A repeat of a smaller cell's design.
    Repeat,
    /// A candidate for the motion merge, with its invariant.
    Candidate(Box<Survivor>, MotionInvariant),
}

fn analyse(
    cell: &UnitCell,
    mech: &Mechanism,
    group: &SymmetryGroup,
    translations: &[Vec2],
    key: u64,
    settings: MobilitySettings,
) -> Analysed {
    let joints = group.joints_of(key);
    let Ok(m) = Mechanism::new(cell, &joints) else {
        return Analysed::Unconfirmed;
    };
    let mob = match analyze(&m, &m.rest, settings) {
        Ok(mob) if mob.dof == 1 && mob.motion.is_some() => mob,
        _ => return Analysed::Unconfirmed,
    };
    let Some(v) = mob.motion.as_ref().map(|mo| mo.vector.clone()) else {
        return Analysed::Unconfirmed;
    };
    if translations
        .iter()
        .any(|&t| is_repeat(cell, mech, &joints, &v, t))
    {
        return Analysed::Repeat;
    }
    Analysed::Candidate(
        Box::new(Survivor {
            separation: separation(cell, mech, &joints, &v),
            closing: closing_rates(&edge_rates(cell, &m, &v)),
            orbit_size: group.canonical_key(&joints).1,
            gap_decades: mob.gap_decades,
            area_rate: mob.motion.as_ref().map_or(0.0, |mo| mo.area_rate),
            joints,
            same_motion_merged: 0,
            replaced_invariant: None,
            key,
            first_key: key,
        }),
        motion_invariant(cell, mech, &v),
    )
}

/// Steps 2 and 3 of [`super`] on the canonical keys of the symmetry orbits found
/// (step 1 is the keying itself). Each representative is analysed again with
/// `mobility::analyze` (`settings` as in the expansion), which also gives its reported gap and
/// motion. `mech`: any mechanism of the cell.
///
/// The analyses run in parallel on the current rayon pool, in batches; the motion merge then
/// takes them in key order, so the result does not depend on the number of threads.
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
        work: Duration::ZERO,
    };
    let mut index = MotionIndex::new();
    let mut survivors: Vec<Survivor> = Vec::new();
    let keys: Vec<u64> = canonical_keys.iter().copied().collect();
    for batch in keys.chunks(BATCH) {
        let analysed: Vec<(Analysed, Duration)> = batch
            .par_iter()
            .map(|&key| {
                let t = Instant::now();
                let a = analyse(cell, mech, group, &translations, key, settings);
                (a, t.elapsed())
            })
            .collect();
        for (a, time) in analysed {
            out.work += time;
            let (kept, invariant) = match a {
                Analysed::Unconfirmed => {
                    out.unconfirmed += 1;
                    continue;
                }
                Analysed::Repeat => continue,
                Analysed::Candidate(k, invariant) => (*k, invariant),
            };
            out.after_repeats += 1;
            if let Some(k) = index.find(&invariant, MOTION_TOL) {
                // Of designs that move alike, keep the most connected one: the stiffest
                // realisation of the motion and the one a maker builds (rotating squares with
                // all eight hinges rather than a six-hinge subset); ties keep the smaller spec.
                let merged = survivors[k].same_motion_merged + 1;
                if pin_count(&kept.joints) > pin_count(&survivors[k].joints) {
                    survivors[k] = Survivor {
                        same_motion_merged: merged,
                        replaced_invariant: Some(invariant),
                        first_key: survivors[k].first_key,
                        ..kept
                    };
                } else {
                    survivors[k].same_motion_merged = merged;
                }
                continue;
            }
            index.insert(invariant);
            survivors.push(kept);
        }
    }
    out.kept = survivors
        .into_iter()
        .zip(index.into_items())
        .map(|(s, stored)| {
            let (invariant, first_invariant) = match s.replaced_invariant {
                Some(own) => (own, Some(stored)),
                None => (stored, None),
            };
            Kept {
                joints: s.joints,
                gap_decades: s.gap_decades,
                area_rate: s.area_rate,
                separation: s.separation,
                closing: s.closing,
                orbit_size: s.orbit_size,
                same_motion_merged: s.same_motion_merged,
                invariant,
                key: s.key,
                first_key: s.first_key,
                first_invariant,
            }
        })
        .collect();
    out
}

//! Deduplication of one cell's symmetry orbits: each orbit representative is confirmed at
//! dof = 1, dropped when it repeats a smaller cell ([`super::repeats`]), and merged with an
//! earlier design whose motion matches ([`super::motion`]), keeping the design with the most
//! pin joints (ties: the smaller spec).

use super::motion::{motion_invariant, MotionIndex, MotionInvariant, MOTION_TOL};
use super::repeats::{repeat_translations, RepeatTest};
use super::symmetry::SymmetryGroup;
use crate::cell::UnitCell;
use crate::explore::expand::Expander;
use crate::explore::separate::{closing_rates, edge_rates, separation, Separation};
use crate::kinematics::Mechanism;
use crate::math::DVec;
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
    /// Its motion invariant (from the motion the merge used: see [`dedup_orbits`]).
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
    Candidate(Survivor, MotionInvariant),
}

/// The representative's motion: the expansion's certificate when it decides (see
/// [`Expander::certified_motion`]), else `mobility::analyze`; `None` when it does not have one
/// degree of freedom.
fn motion(
    cell: &UnitCell,
    expander: &Expander,
    joints: &[JointChoice],
    settings: MobilitySettings,
) -> Option<DVec> {
    if let Some(v) = expander.certified_motion(joints) {
        return Some(v);
    }
    let m = Mechanism::new(cell, joints).ok()?;
    match analyze(&m, &m.rest, settings) {
        Ok(mob) if mob.dof == 1 => mob.motion.map(|mo| mo.vector),
        _ => None,
    }
}

fn analyse(
    scope: &Scope<'_>,
    repeats: &[RepeatTest],
    key: u64,
    settings: MobilitySettings,
) -> Analysed {
    let joints = scope.group.joints_of(key);
    let Some(v) = motion(scope.cell, scope.expander, &joints, settings) else {
        return Analysed::Unconfirmed;
    };
    if repeats.iter().any(|r| r.holds(scope.mech, &joints, &v)) {
        return Analysed::Repeat;
    }
    let invariant = motion_invariant(scope.cell, scope.mech, &v);
    Analysed::Candidate(
        Survivor {
            joints,
            same_motion_merged: 0,
            replaced_invariant: None,
            key,
            first_key: key,
        },
        invariant,
    )
}

/// What a kept design's report needs, from `mobility::analyze` (the gap, the area rate and the
/// motion the separation and closing rates are measured on, exactly as a design analysed on
/// its own), with the invariants the merge used; `None` when the analysis does not confirm
/// one degree of freedom (not expected: the merge took it on a certified or analysed
/// dof = 1).
fn report(
    scope: &Scope<'_>,
    s: Survivor,
    stored: MotionInvariant,
    settings: MobilitySettings,
) -> Option<Kept> {
    let cell = scope.cell;
    let m = Mechanism::new(cell, &s.joints).ok()?;
    let mob = analyze(&m, &m.rest, settings).ok()?;
    let motion = mob.motion.filter(|_| mob.dof == 1)?;
    let v = &motion.vector;
    let (invariant, first_invariant) = match s.replaced_invariant {
        Some(own) => (own, Some(stored)),
        None => (stored, None),
    };
    Some(Kept {
        separation: separation(cell, scope.mech, &s.joints, v),
        closing: closing_rates(&edge_rates(cell, &m, v)),
        orbit_size: scope.group.canonical_key(&s.joints).1,
        gap_decades: mob.gap_decades,
        area_rate: motion.area_rate,
        joints: s.joints,
        same_motion_merged: s.same_motion_merged,
        invariant,
        key: s.key,
        first_key: s.first_key,
        first_invariant,
    })
}

/// The cell and its helpers, shared by every analysis of one deduplication.
struct Scope<'a> {
    cell: &'a UnitCell,
    mech: &'a Mechanism,
    group: &'a SymmetryGroup,
    expander: &'a Expander<'a>,
}

/// Steps 2 and 3 of [`super`] on the canonical keys of the symmetry orbits found
/// (step 1 is the keying itself). Each representative's dof = 1 and motion come from the
/// expansion's certificate on its joints (`expander`, the cell's; microseconds), or from
/// `mobility::analyze` (`settings` as in the expansion) when the certificate does not decide;
/// the repeat test and the motion merge use that motion. Only the designs that survive the
/// merge are analysed with `mobility::analyze` for their reports (gap, area rate, separation,
/// closing rates), so a kept design's report is what analysing it alone gives; its invariant
/// is the one the merge used.
/// `mech`: any mechanism of the cell.
///
/// The analyses run in parallel on the current rayon pool, in batches; the motion merge then
/// takes them in key order, so the result does not depend on the number of threads.
pub fn dedup_orbits(
    cell: &UnitCell,
    mech: &Mechanism,
    group: &SymmetryGroup,
    expander: &Expander,
    canonical_keys: &BTreeSet<u64>,
    settings: MobilitySettings,
) -> DedupResult {
    let scope = Scope {
        cell,
        mech,
        group,
        expander,
    };
    let repeats: Vec<RepeatTest> = repeat_translations(cell, &group.symmetries)
        .into_iter()
        .map(|t| RepeatTest::new(cell, t))
        .collect();
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
                let a = analyse(&scope, &repeats, key, settings);
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
                Analysed::Candidate(k, invariant) => (k, invariant),
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
    // The survivors' reports, in parallel, in key order.
    let reported: Vec<(Option<Kept>, Duration)> = survivors
        .into_par_iter()
        .zip(index.into_items())
        .map(|(s, stored)| {
            let t = Instant::now();
            let k = report(&scope, s, stored, settings);
            (k, t.elapsed())
        })
        .collect();
    for (k, time) in reported {
        out.work += time;
        match k {
            Some(k) => out.kept.push(k),
            None => out.unconfirmed += 1,
        }
    }
    out
}

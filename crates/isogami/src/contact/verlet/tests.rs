//! The Verlet lists give exactly the pairs of a fresh listing, at every state of real
//! trajectories and of a sheet sheared far out of its cell, while reusing lists.

use super::*;
use crate::contact::reach::MIN_SKIN;
use crate::contact::{ContactModel, ContactSettings, CLEARANCE_REACH};
use crate::deploy::{deploy, DeploySettings, Method};
use crate::kinematics::{Mechanism, StateLayout};
use crate::math::DVec;
use crate::topology::{Design, SAMPLE_OPENING_DESIGNS};
use std::collections::BTreeSet;

type Key = (usize, usize, [i32; 2]);

fn key(p: CandidatePair) -> Key {
    (p.a, p.b, p.offset)
}

/// Gap between the bounding circles of a pair at `placed`.
fn circle_gap(placed: &Placement, extents: &[Real], (a, b, o): Key) -> Real {
    let d = placed.tiles[b].centre - placed.tiles[a].centre + placed.shift(o);
    d.norm() - extents[a] - extents[b]
}

/// Asserts that the cache gives the pairs of a fresh listing at `margin`, each once (pairs
/// whose circles are within rounding of the margin may go either way). Returns how many
/// pairs had an offset beyond the 3×3 block.
fn agrees(cache: &mut PairCache, placed: &Placement, extents: &[Real], margin: Real) -> usize {
    let mut fresh = BTreeSet::new();
    for_each_near_pair(placed, extents, margin, |p| {
        fresh.insert(key(p));
    })
    .unwrap();
    let mut cached = BTreeSet::new();
    cache
        .for_each_near_pair(placed, extents, margin, |p| {
            assert!(cached.insert(key(p)), "{p:?} passed on twice");
        })
        .unwrap();
    for k in fresh.symmetric_difference(&cached) {
        let gap = circle_gap(placed, extents, *k);
        assert!(
            (gap - margin).abs() < 1e-9,
            "margin {margin}: {k:?} (circle gap {gap}) only in the {} listing",
            if fresh.contains(k) { "fresh" } else { "cached" }
        );
    }
    fresh
        .iter()
        .filter(|(_, _, o)| o[0].abs().max(o[1].abs()) > 1)
        .count()
}

/// The margins the solver asks for: the barrier's d̂, the clearance reach, the smallest
/// conservative-advancement skin.
fn margins() -> [Real; 3] {
    [ContactSettings::default().dhat, CLEARANCE_REACH, MIN_SKIN]
}

#[test]
fn lists_agree_with_fresh_listings_along_trajectories() {
    let reproducers = [
        "IH38::1x1:x--------",
        "IH51:0.5,0.5,0.6:1x1:a-------",
        "IH54:0.230769230769,0.230769230769:1x1:b-------",
    ];
    let runs = SAMPLE_OPENING_DESIGNS
        .iter()
        .map(|s| (*s, Method::RigidModes))
        .chain(reproducers.iter().map(|s| (*s, Method::RigidModes)))
        .chain([
            (SAMPLE_OPENING_DESIGNS[1], Method::Springs),
            (reproducers[2], Method::Ncm),
        ]);
    let (mut queries, mut listings) = (0u64, 0u64);
    for (spec, method) in runs {
        let design = Design::resolve(spec).unwrap();
        let mech = Mechanism::new(&design.cell().unwrap(), &design.joints).unwrap();
        let settings = DeploySettings {
            method,
            ..DeploySettings::default()
        };
        let model = ContactModel::new(&mech, settings.contact).unwrap();
        let traj = deploy(&mech, &settings, &mut |_| true).unwrap();
        let mut cache = PairCache::new();
        // Every accepted state and three states between each two, as a solver visits them.
        for step in traj.steps.windows(2) {
            let (q0, q1) = (&step[0].q, &step[1].q);
            for s in [0.0, 0.25, 0.5, 0.75] {
                let q: DVec = q0 + (q1 - q0) * s;
                let placed = Placement::centres_only(mech.layout, &q);
                for margin in margins() {
                    agrees(&mut cache, &placed, &model.extents, margin);
                    queries += 1;
                }
            }
        }
        listings += cache.listings();
    }
    // The lists were reused, not redone at every query.
    assert!(
        queries > 5000 && 4 * listings < queries,
        "{listings} of {queries}"
    );
}

#[test]
fn lists_follow_a_sheet_sheared_far_out_of_its_cell() {
    // Two tiles; w is sheared by five cells along u while u stretches and a tile drifts:
    // neighbours come from ever farther cell offsets, whose copies move fastest.
    let layout = StateLayout { tiles: 2 };
    let extents = [0.45, 0.3];
    let state = |t: Real| {
        let mut q = DVec::zeros(layout.len());
        q[layout.tile(1)] = 0.5 + 0.2 * t;
        q[layout.tile(1) + 1] = 0.1 - 0.1 * t;
        (q[layout.u()], q[layout.u() + 1]) = (1.0 + 0.3 * t, 0.0);
        (q[layout.w()], q[layout.w() + 1]) = (5.0 * t, 1.0 - 0.2 * t);
        q
    };
    let mut cache = PairCache::new();
    let (mut far, mut queries) = (0, 0u64);
    let increments = 4000;
    for i in 0..=increments {
        let placed =
            Placement::centres_only(layout, &state(Real::from(i) / Real::from(increments)));
        for margin in margins() {
            far += agrees(&mut cache, &placed, &extents, margin);
            queries += 1;
        }
    }
    assert!(far > 0, "no pair beyond the 3×3 block was exercised");
    assert!(
        4 * cache.listings() < queries,
        "{} of {queries}",
        cache.listings()
    );
    // A jump far beyond the skin is listed afresh, not answered from the old list.
    let before = cache.listings();
    let mut q = state(1.0);
    q[layout.tile(1)] += 3.0 * SKIN;
    agrees(
        &mut cache,
        &Placement::centres_only(layout, &q),
        &extents,
        0.1,
    );
    assert_eq!(cache.listings(), before + 1);
}

/// Runs `agrees` at `margin` along `state(t)`, t = 0, 0.001, …, 1, with one cache.
fn follow(layout: StateLayout, extents: &[Real], margin: Real, state: impl Fn(Real) -> DVec) {
    let mut cache = PairCache::new();
    for i in 0..=1000 {
        let placed = Placement::centres_only(layout, &state(Real::from(i) / 1000.0));
        agrees(&mut cache, &placed, extents, margin);
    }
    assert!(cache.listings() > 1 && cache.listings() < 100);
}

#[test]
fn the_drift_bound_is_tight_for_approaching_tiles_and_a_shrinking_cell() {
    // Each motion brings a pair that is just left out of the list (circle gap a hair above
    // margin + SKIN) towards contact exactly as fast as the bound allows, so a list kept a
    // little longer than the bound says would miss it.
    for margin in [ContactSettings::default().dhat, CLEARANCE_REACH] {
        let listed = margin + SKIN;
        // Two tiles in a huge cell move straight at each other: each reference point moves
        // by c, the gap shrinks by 2c.
        let layout = StateLayout { tiles: 2 };
        let r = 0.3;
        follow(layout, &[r, r], margin, |t| {
            let c = SKIN * t;
            let mut q = DVec::zeros(layout.len());
            q[layout.tile(0)] = c;
            q[layout.tile(1)] = 2.0 * r + listed + 1e-9 - c;
            (q[layout.u()], q[layout.w() + 1]) = (100.0, 100.0);
            q
        });
        // One tile, a cell shrinking along u: the copy k cells away approaches at ‖k‖·|Δu|,
        // and ‖k‖ is as large as the distance allows (k = (2, 0) just left out, σ = 2).
        let layout = StateLayout { tiles: 1 };
        let r = (4.0 - listed) / 2.0 - 1e-9;
        follow(layout, &[r], margin, |t| {
            let mut q = DVec::zeros(layout.len());
            (q[layout.u()], q[layout.w() + 1]) = (2.0 - SKIN * t, 2.0);
            q
        });
    }
}

#[test]
fn degenerate_lattices_and_other_models() {
    let layout = StateLayout { tiles: 1 };
    let mut q = DVec::zeros(layout.len());
    (q[layout.u()], q[layout.w() + 1]) = (1.0, 1.0);
    let mut cache = PairCache::new();
    let placed = Placement::centres_only(layout, &q);
    agrees(&mut cache, &placed, &[0.4], 0.2);
    // Other extents (another model): the old lists are not used.
    agrees(&mut cache, &placed, &[0.9], 0.2);
    assert_eq!(cache.listings(), 2);
    // u ∥ w: the same refusal as a fresh listing.
    q[layout.w()] = 2.0;
    q[layout.w() + 1] = 0.0;
    let flat = Placement::centres_only(layout, &q);
    assert_eq!(
        cache.for_each_near_pair(&flat, &[0.9], 0.2, |_| {}),
        Err(LatticeProblem::Degenerate)
    );
}

//! Expansion against named designs and against `mobility::analyze`.

use super::*;
use crate::cell::CellDims;
use crate::tiling::{Family, Tiling};

#[test]
fn rotating_squares_mask_keeps_the_named_design() {
    let f = Family::from_number(76).unwrap();
    let cell = UnitCell::new(&Tiling::default_for(f), CellDims::new(2, 2).unwrap()).unwrap();
    let ex = Expander::new(&cell, MobilitySettings::default()).unwrap();
    assert_eq!(ex.columns(), 13);
    let (found, stats) = ex.expand_collect(0xFF);
    assert_eq!(stats.configurations, 256);
    let named = crate::topology::named_design("rotating-squares").unwrap();
    assert!(found.contains(&named.joints));
    assert_eq!(stats.mobility_one as usize, found.len());
}

/// The one-choice certificate the deduplication uses certifies exactly the leaves the
/// expansion certifies, with the same motion bit for bit, and nothing else.
#[test]
fn certified_motion_is_the_certified_leaf() {
    for (n, a, b, mask) in [(76, 2, 2, 0xFFu32), (28, 1, 1, 0x3FF), (44, 1, 1, 0xF)] {
        let f = Family::from_number(n).unwrap();
        let cell = UnitCell::new(&Tiling::default_for(f), CellDims::new(a, b).unwrap()).unwrap();
        let ex = Expander::new(&cell, MobilitySettings::default()).unwrap();
        let mut certified = Vec::new();
        ex.expand(mask, &mut |leaf| {
            if !leaf.analysed {
                certified.push((leaf.joints.to_vec(), leaf.motion.clone()));
            }
        });
        assert!(!certified.is_empty(), "IH{n}");
        let edges: Vec<usize> = (0..cell.edges.len())
            .filter(|k| mask >> k & 1 == 1)
            .collect();
        let mut found = 0;
        for bits in 0u32..1 << edges.len() {
            let mut joints = vec![JointChoice::None; cell.edges.len()];
            for (i, &e) in edges.iter().enumerate() {
                joints[e] = if bits >> i & 1 == 0 {
                    JointChoice::A
                } else {
                    JointChoice::B
                };
            }
            let known = certified.iter().find(|(j, _)| *j == joints);
            match (ex.certified_motion(&joints), known) {
                (Some(v), Some((_, w))) => {
                    assert!(v
                        .iter()
                        .zip(w.iter())
                        .all(|(x, y)| x.to_bits() == y.to_bits()));
                    found += 1;
                }
                (None, None) => {}
                (v, w) => panic!("IH{n} {joints:?}: {} vs {}", v.is_some(), w.is_some()),
            }
        }
        assert_eq!(found, certified.len(), "IH{n}");
        let mut welded = certified[0].0.clone();
        welded[edges[0]] = JointChoice::Both;
        assert!(ex.certified_motion(&welded).is_none());
        assert!(ex.certified_motion(&welded[1..]).is_none());
    }
}

/// Certified leaves carry the motion `analyze` would give, sign included.
#[test]
fn certified_motion_equals_analysed_motion() {
    for (n, a, b, mask) in [(76, 2, 2, 0xFFu32), (28, 1, 1, 0x3FF), (44, 1, 1, 0xF)] {
        let f = Family::from_number(n).unwrap();
        let cell = UnitCell::new(&Tiling::default_for(f), CellDims::new(a, b).unwrap()).unwrap();
        let ex = Expander::new(&cell, MobilitySettings::default()).unwrap();
        let mut checked = 0;
        ex.expand(mask, &mut |leaf| {
            let mech = Mechanism::new(&cell, leaf.joints).unwrap();
            let mob = analyze(&mech, &mech.rest, MobilitySettings::default()).unwrap();
            assert_eq!(mob.dof, 1);
            let v = &mob.motion.as_ref().unwrap().vector;
            let rate = mob.motion.as_ref().unwrap().area_rate;
            let err = if rate.abs() > 1e-9 {
                (v - leaf.motion).norm()
            } else {
                // No area change: the sign follows the largest component, which ties
                // within roundoff for symmetric motions, in `analyze` as here.
                (v - leaf.motion).norm().min((v + leaf.motion).norm())
            };
            assert!(err < 1e-8, "IH{n} {:?}", leaf.joints);
            checked += usize::from(!leaf.analysed);
        });
        assert!(checked > 0, "IH{n}");
    }
}

/// The rigidity and dof = 1 certificates that the O(N) bound decides are the ones solving R⁻¹
/// decides (`factor::tests::check_bounded` solves every one afresh), on every family's 1×1
/// cell of at most 10 edges: its full mask and six masks drawn with a fixed seed.
#[test]
fn bounded_certificates_are_the_solved_ones() {
    let before = factor::tests::BOUNDED.with(|b| b.get());
    let mut rng = crate::test_rng::TestRng::new(17);
    let mut draw = |m: usize| (rng.next_u64() >> 33) as u32 & ((1u32 << m) - 1);
    let mut cells = 0;
    for f in Family::all() {
        let Ok(cell) = UnitCell::new(&Tiling::default_for(f), CellDims::new(1, 1).unwrap()) else {
            continue;
        };
        let m = cell.edges.len();
        if m > 10 {
            continue;
        }
        let ex = Expander::new(&cell, MobilitySettings::default()).unwrap();
        let full = (1u32 << m) - 1;
        for mask in std::iter::once(full).chain((0..6).map(|_| draw(m))) {
            let (found, stats) = ex.expand_collect(mask);
            assert_eq!(stats.mobility_one as usize, found.len());
        }
        cells += 1;
    }
    assert!(cells > 20, "{cells} cells");
    let bounded = factor::tests::BOUNDED.with(|b| b.get()) - before;
    assert!(bounded > 100, "the bound decided {bounded} certificates");
}

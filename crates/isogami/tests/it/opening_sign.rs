//! Issue 21, part B: the motion `analyze` returns opens the sheet, |det[u w]| growing, also in
//! families whose tiling vectors are clockwise (det[u w] < 0), where signing by the growth of
//! the signed determinant made it close the sheet.

use isogami::api::resolve_design;
use isogami::kinematics::Mechanism;
use isogami::math::{cross, DVec};
use isogami::mobility::{analyze, area_rate, MobilitySettings};

/// Designs of families with t1 × t2 < 0 (IH23, IH30, IH28, IH2, IH6), one DOF each but the
/// last, which has several (one joint only).
const CLOCKWISE: [&str; 6] = [
    "IH23:0.155769230769,0.35,0.225335752741,0.35:1x1:aa-a-",
    "IH30:0.230769230769:1x1:-aaaaaa-a-ba",
    "IH28:0.452827026611,0.5:1x1:-aaaaaaaa-",
    "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:aa-aa-",
    "IH6:0.12239750492,0.5,0.225335752741,0.625,0.5:1x1:--a--aab--aa",
    "IH23:0.155769230769,0.35,0.225335752741,0.35:1x1:a----",
];

fn mechanism(spec: &str) -> Mechanism {
    let d = resolve_design(spec).unwrap();
    Mechanism::new(&d.cell().unwrap(), &d.joints).unwrap()
}

/// Signed cell area det[u w] at state q (non-dimensional).
fn det(m: &Mechanism, q: &DVec) -> f64 {
    let (u, w) = m.lattice(q);
    cross(&u, &w)
}

#[test]
fn analyze_opens_clockwise_lattices() {
    let h = 1e-6;
    for spec in CLOCKWISE {
        let m = mechanism(spec);
        let q = &m.rest;
        let a0 = det(&m, q);
        assert!(a0 < 0.0, "{spec}: the lattice is clockwise ({a0})");
        let mob = analyze(&m, q, MobilitySettings::default()).unwrap();
        assert!(mob.dof >= 1, "{spec}");
        let motion = mob.motion.unwrap();
        // A small step along the motion grows the cell's area magnitude: it opens. (Signed by
        // d det/ds, as before the fix, it shrank.)
        let ahead = det(&m, &(q + &motion.vector * h));
        let behind = det(&m, &(q - &motion.vector * h));
        assert!(ahead.abs() > a0.abs(), "{spec}: {ahead} vs {a0}");
        assert!(behind.abs() < a0.abs(), "{spec}: {behind} vs {a0}");
        // area_rate is the rate of |det|, positive, and matches the finite difference.
        let fd = (ahead.abs() - behind.abs()) / (2.0 * h);
        assert!(motion.area_rate > 0.0, "{spec}");
        assert!(
            (motion.area_rate - fd).abs() <= 1e-6 * fd.abs().max(1.0),
            "{spec}: {} vs {fd}",
            motion.area_rate
        );
        assert_eq!(area_rate(&m, q, &motion.vector), motion.area_rate);
        assert_eq!(area_rate(&m, q, &-&motion.vector), -motion.area_rate);
    }
}

#[test]
fn several_dofs_open_along_the_fastest_growth_of_the_area_magnitude() {
    let spec = CLOCKWISE[5];
    let m = mechanism(spec);
    let mob = analyze(&m, &m.rest, MobilitySettings::default()).unwrap();
    assert!(mob.dof > 1, "{spec}: {}", mob.dof);
    let best = mob.motion.unwrap().area_rate;
    // No basis motion, either sign, grows |det| faster than the chosen combination.
    for mode in &mob.modes {
        let r = area_rate(&m, &m.rest, &mode.vector);
        assert!(r.abs() <= best * (1.0 + 1e-12), "{spec}: {r} vs {best}");
    }
    assert!(best > 0.0);
}

#[test]
fn counter_clockwise_lattices_are_unchanged() {
    // rotating squares: det > 0, d|det|/ds = d det/ds.
    let m = mechanism("rotating-squares");
    assert!(det(&m, &m.rest) > 0.0);
    let motion = analyze(&m, &m.rest, MobilitySettings::default())
        .unwrap()
        .motion
        .unwrap();
    let (iu, iw) = (m.layout.u(), m.layout.w());
    let (u, w) = m.lattice(&m.rest);
    let v = &motion.vector;
    let raw = cross(&isogami::math::vec2(v[iu], v[iu + 1]), &w)
        + cross(&u, &isogami::math::vec2(v[iw], v[iw + 1]));
    assert_eq!(motion.area_rate, raw);
    assert!(raw > 0.0);
}

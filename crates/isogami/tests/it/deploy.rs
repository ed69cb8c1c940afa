//! Deployment: the analytic rotating-squares curve, kerf-limited end, invariants on every
//! frame, locked and rigid designs, and the baselines against rigid modes.

use crate::common;

use common::rotating_squares;
use isogami::contact::{ContactModel, ContactSettings};
use isogami::deploy::DeployError;
use isogami::deploy::{
    compare_methods, deploy, frame_records, DeploySettings, EndReason, Method, Trajectory,
};
use isogami::kinematics::Mechanism;
use isogami::measure::FrameMeasures;
use isogami::topology::{Design, JointChoice};

use isogami::topology::SAMPLE_OPENING_DESIGNS as OPENING_DESIGNS;

fn mech_of(spec: &str) -> Mechanism {
    let d = Design::resolve(spec).unwrap();
    Mechanism::new(&d.cell().unwrap(), &d.joints).unwrap()
}

/// Deploys and checks every accepted state independently of the solver: joints closed to
/// 1e-8 L, the exact overlap test, no NaN.
fn checked(mech: &Mechanism, settings: &DeploySettings) -> Trajectory {
    let traj = deploy(mech, settings, &mut |_| true).unwrap();
    let contact = ContactModel::new(mech, settings.contact).unwrap();
    let all: Vec<usize> = (0..traj.steps.len()).collect();
    frame_records(mech, &contact, &traj, &all, 1e-8)
        .unwrap_or_else(|e| panic!("{}: {e}", settings.method));
    traj
}

fn run(mech: &Mechanism, kerf: f64) -> Trajectory {
    let s = DeploySettings {
        contact: ContactSettings::with_kerf(kerf),
        ..DeploySettings::default()
    };
    checked(mech, &s)
}

/// φ = half the rotation of tile 1 relative to tile 0 (chessboard neighbours).
fn phi(mech: &Mechanism, q: &isogami::math::DVec) -> f64 {
    (mech.pose(q, 1).1 - mech.pose(q, 0).1).abs() / 2.0
}

#[test]
fn rotating_squares_follows_the_analytic_curve() {
    let (_, _, mech) = rotating_squares();
    let traj = run(&mech, 0.01);
    assert_eq!(traj.end_reason, EndReason::ContactLimit);
    assert!(traj.steps.len() > 30);
    let mut best = (0.0, 0.0);
    for (k, step) in traj.steps.iter().enumerate() {
        let m = FrameMeasures::from_states(&mech, &mech.rest, &step.q, traj.t(k)).unwrap();
        let p = phi(&mech, &step.q);
        let analytic = p.cos() + p.sin() - 1.0;
        assert!(
            (m.max_expansion - analytic).abs() < 1e-6,
            "step {k}: {} vs {analytic}",
            m.max_expansion
        );
        assert!(
            (m.min_expansion - analytic).abs() < 1e-6,
            "step {k}: {} vs {analytic}",
            m.min_expansion
        );
        if let Some(nu) = m.poisson_ratio() {
            assert!((nu + 1.0).abs() < 1e-6, "Poisson ratio {nu}");
        }
        if m.max_expansion > best.0 {
            best = (m.max_expansion, p);
        }
    }
    assert!(
        (best.0 - (2f64.sqrt() - 1.0)).abs() < 1e-3,
        "max stretch {}",
        best.0
    );
    assert!(
        (best.1 - std::f64::consts::FRAC_PI_4).abs() < 0.05,
        "at phi {}",
        best.1
    );
    // Ends by contact close to φ = 90°.
    let end = phi(&mech, &traj.steps.last().unwrap().q);
    assert!(
        (end - std::f64::consts::FRAC_PI_2).abs() < 0.02,
        "end phi {end}"
    );
}

#[test]
fn rotating_squares_end_depends_on_the_kerf() {
    let (_, _, mech) = rotating_squares();
    // Past φ = 90° the squares close again; the inset collision polygons still have the kerf
    // between them, so contact comes a kerf-dependent angle later.
    let over: Vec<f64> = [0.005, 0.01, 0.02]
        .iter()
        .map(|&k| {
            let t = run(&mech, k);
            assert_eq!(t.end_reason, EndReason::ContactLimit);
            phi(&mech, &t.steps.last().unwrap().q) - std::f64::consts::FRAC_PI_2
        })
        .collect();
    assert!(
        over[0] > 0.0 && over[0] < over[1] && over[1] < over[2],
        "{over:?}"
    );
    // Roughly proportional: the barrier stops the squares about d̂ = kerf / 2 apart.
    for (o, k) in over.iter().zip([0.005, 0.01, 0.02]) {
        let ratio = o / k;
        assert!((0.1..0.5).contains(&ratio), "overshoot/kerf = {ratio}");
    }
}

#[test]
fn every_frame_keeps_joints_closed_and_tiles_apart() {
    for spec in OPENING_DESIGNS {
        let mech = mech_of(spec);
        let settings = DeploySettings::default();
        let traj = deploy(&mech, &settings, &mut |_| true).unwrap();
        assert_eq!(traj.end_reason, EndReason::ContactLimit, "{spec}");
        assert!(traj.steps.len() > 5, "{spec}");
        let contact = ContactModel::new(&mech, settings.contact).unwrap();
        let all: Vec<usize> = (0..traj.steps.len()).collect();
        // frame_records re-checks each state independently: joints to 1e-8 L, the exact
        // overlap test, finiteness.
        let frames = frame_records(&mech, &contact, &traj, &all, 1e-8)
            .unwrap_or_else(|e| panic!("{spec}: {e}"));
        for f in &frames {
            assert!(f.q.iter().all(|x| x.is_finite()));
            assert!(f.min_clearance > 0.0, "{spec}");
            assert!(f.measures.area_ratio.is_finite());
        }
        // t is monotone from 0 to 1.
        assert_eq!(traj.t(0), 0.0);
        assert!((traj.t(traj.steps.len() - 1) - 1.0).abs() < 1e-15);
        assert!(frames.windows(2).all(|w| w[0].t < w[1].t));
    }
}

#[test]
fn blocked_design_is_locked() {
    let mech = mech_of("IH1:0.12239750492,0.5,0.143395479017,0.625:2x1:a-a-bb");
    let mob = isogami::mobility::analyze(&mech, &mech.rest, Default::default()).unwrap();
    assert_eq!(mob.dof, 1, "first-order mobile");
    let traj = deploy(&mech, &DeploySettings::default(), &mut |_| true).unwrap();
    assert_eq!(traj.end_reason, EndReason::Locked);
    assert_eq!(traj.steps.len(), 1);
}

#[test]
fn rigid_design_is_refused() {
    let (d, cell, _) = rotating_squares();
    let welded = Mechanism::new(&cell, &vec![JointChoice::Both; d.joints.len()]).unwrap();
    match deploy(&welded, &DeploySettings::default(), &mut |_| true) {
        Err(e @ DeployError::Rigid) => assert!(e.to_string().contains("rigid")),
        other => panic!("expected a rigid error, got {other:?}"),
    }
}

#[test]
fn bad_settings_are_refused() {
    let (_, _, mech) = rotating_squares();
    for kerf in [0.0, -0.01, 0.5, f64::NAN] {
        let s = DeploySettings {
            contact: ContactSettings::with_kerf(kerf),
            ..DeploySettings::default()
        };
        assert!(deploy(&mech, &s, &mut |_| true).is_err(), "kerf {kerf}");
    }
}

/// The baselines on designs whose motion turns away from the initial eigenvector: springs
/// stall where the cell stops growing, NCM where the projection on the initial eigenvector
/// stops growing; only rigid modes reach the contact limit (paper Fig. 4: 0.11, 0.78, 1.0).
#[test]
fn baselines_stop_early_on_turning_designs() {
    for spec in [OPENING_DESIGNS[0], OPENING_DESIGNS[1]] {
        let mech = mech_of(spec);
        let rigid = deploy(&mech, &DeploySettings::default(), &mut |_| true).unwrap();
        let min_dot = rigid
            .steps
            .iter()
            .skip(1)
            .map(|s| s.direction.dot(&rigid.initial_direction))
            .fold(1.0, f64::min);
        assert!(
            min_dot < -0.2,
            "{spec}: the motion must turn away from v0 (min dot {min_dot})"
        );
        let results = compare_methods(&mech, &DeploySettings::default()).unwrap();
        let t = |m: Method| results.iter().find(|r| r.method == m).unwrap().final_t;
        assert_eq!(t(Method::RigidModes), 1.0, "{spec}");
        assert!(t(Method::Ncm) < 0.95, "{spec}: ncm {}", t(Method::Ncm));
        assert!(
            t(Method::Springs) < 0.6,
            "{spec}: springs {}",
            t(Method::Springs)
        );
        assert!(t(Method::Springs) < t(Method::Ncm), "{spec}");
        let springs = results
            .iter()
            .find(|r| r.method == Method::Springs)
            .unwrap();
        assert_eq!(springs.end_reason, EndReason::Stalled);
    }
}

#[test]
fn a_contact_model_built_for_another_kerf_is_refused() {
    use isogami::contact::{ContactModel, ContactSettings};
    use isogami::deploy::deploy_with;
    let (_, _, mech) = common::rotating_squares();
    let contact = ContactModel::new(&mech, ContactSettings::with_kerf(0.02)).unwrap();
    let settings = DeploySettings::default();
    let err = deploy_with(&mech, &contact, &settings, &mut |_| true).unwrap_err();
    assert!(err.to_string().contains("other contact settings"), "{err}");
    let same = ContactModel::new(&mech, settings.contact).unwrap();
    let a = deploy_with(&mech, &same, &settings, &mut |_| true).unwrap();
    let b = deploy(&mech, &settings, &mut |_| true).unwrap();
    assert_eq!(a.steps.len(), b.steps.len());
    assert_eq!(a.steps.last().unwrap().q, b.steps.last().unwrap().q);
}

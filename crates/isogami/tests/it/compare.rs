//! The Fig. 4 comparison on its default design set: the properties that make it mean what it
//! says (rigid modes reaches the contact limit and the largest opening; on each design a
//! baseline that stops early loses a stated share of the opening; every number is finite and
//! every t in [0, 1]), agreement with separate `deploy` runs, and why the baselines stop where
//! they do.

use isogami::contact::ContactModel;
use isogami::deploy::{
    build_report, compare_design, deploy, frame_records, DeploySettings, DeploymentReport,
    DesignComparison, EndReason, Method, MethodResult, Trajectory, COMPARISON_DESIGNS, METHODS,
};
use isogami::kinematics::Mechanism;
use isogami::topology::Design;
use std::sync::OnceLock;

/// One design of the default set: the comparison, and a separate deployment per method.
struct Run {
    spec: &'static str,
    mech: Mechanism,
    comparison: DesignComparison,
    trajectories: Vec<Trajectory>,
}

/// The default set is run once and shared by the tests of this file.
fn runs() -> &'static [Run] {
    static RUNS: OnceLock<Vec<Run>> = OnceLock::new();
    RUNS.get_or_init(|| {
        COMPARISON_DESIGNS
            .iter()
            .map(|&spec| {
                let design = Design::resolve(spec).unwrap();
                let mech = Mechanism::new(&design.cell().unwrap(), &design.joints).unwrap();
                let settings = DeploySettings::default();
                let comparison = compare_design(&design, &settings).unwrap();
                let trajectories = METHODS
                    .iter()
                    .map(|&method| {
                        let s = DeploySettings { method, ..settings };
                        deploy(&mech, &s, &mut |_| true).unwrap()
                    })
                    .collect();
                Run {
                    spec,
                    mech,
                    comparison,
                    trajectories,
                }
            })
            .collect()
    })
}

fn result(run: &Run, method: Method) -> &MethodResult {
    run.comparison
        .results
        .iter()
        .find(|r| r.method == method)
        .unwrap()
}

/// Share of the rigid-modes path's opening (largest area ratio − 1) that `r` did not reach.
fn lost(run: &Run, r: &MethodResult) -> f64 {
    let peak = result(run, Method::RigidModes).max_area_ratio;
    1.0 - (r.max_area_ratio - 1.0) / (peak - 1.0)
}

/// What each default design is there to show: the least share of the opening each method
/// loses (None: it reaches the rigid-modes path's largest area, within 1 %).
const EXPECTED: &[(&str, Option<f64>, Option<f64>)] = &[
    // (design prefix, NCM loses at least, springs lose at least)
    ("IH23:", None, Some(0.25)),
    ("IH12:", None, Some(0.10)),
    ("IH6:", Some(0.02), None),
    ("IH22:", Some(0.10), Some(0.04)),
    ("rotating-squares", None, None),
];

#[test]
fn every_number_is_finite_and_every_t_in_unit_interval() {
    for run in runs() {
        let methods: Vec<Method> = run.comparison.results.iter().map(|r| r.method).collect();
        assert_eq!(methods, METHODS, "{}", run.spec);
        for r in &run.comparison.results {
            let numbers = [
                r.final_t,
                r.path_distance,
                r.max_area_ratio,
                r.max_area_t,
                r.final_area_ratio,
                r.max_expansion,
                r.min_expansion,
                r.max_tile_rotation,
                r.millis,
            ];
            assert!(numbers.iter().all(|x| x.is_finite()), "{}: {r:?}", run.spec);
            assert!((0.0..=1.0).contains(&r.final_t), "{}: {r:?}", run.spec);
            assert!((0.0..=1.0).contains(&r.max_area_t), "{}: {r:?}", run.spec);
            assert!(r.min_expansion <= r.max_expansion, "{}: {r:?}", run.spec);
            assert!(
                r.final_area_ratio <= r.max_area_ratio,
                "{}: {r:?}",
                run.spec
            );
            assert!(
                r.max_area_ratio > 1.0 && r.steps >= 2,
                "{}: {r:?}",
                run.spec
            );
        }
    }
}

#[test]
fn rigid_modes_reaches_the_contact_limit_and_the_largest_opening() {
    for run in runs() {
        assert_eq!(run.comparison.dof, 1, "{}", run.spec);
        let rigid = result(run, Method::RigidModes);
        assert_eq!(rigid.final_t, 1.0, "{}", run.spec);
        assert_eq!(rigid.path_distance, 0.0, "{}", run.spec);
        assert_eq!(rigid.end_reason, EndReason::ContactLimit, "{}", run.spec);
        assert!(rigid.reached_peak_area, "{}", run.spec);
        for r in &run.comparison.results {
            // No baseline opens further than rigid modes (1 ‰ of the opening for steps).
            assert!(lost(run, r) > -1e-3, "{}: {r:?}", run.spec);
            assert!(
                r.max_expansion <= rigid.max_expansion * (1.0 + 1e-3),
                "{}: {r:?}",
                run.spec
            );
        }
    }
}

#[test]
fn each_default_design_shows_what_it_is_there_for() {
    assert_eq!(runs().len(), EXPECTED.len());
    for (run, &(prefix, ncm, springs)) in runs().iter().zip(EXPECTED) {
        assert!(run.spec.starts_with(prefix), "{} vs {prefix}", run.spec);
        for (method, least) in [(Method::Ncm, ncm), (Method::Springs, springs)] {
            let r = result(run, method);
            let lost = lost(run, r);
            match least {
                Some(least) => {
                    assert!(lost >= least, "{}: {method} lost {lost:.3}", run.spec);
                    assert!(!r.reached_peak_area, "{}: {method}", run.spec);
                    // It stopped on the rigid-modes path, so its t means something.
                    assert!(r.final_t < 1.0 - least, "{}: {r:?}", run.spec);
                    assert!(r.path_distance < 1e-2, "{}: {r:?}", run.spec);
                }
                None => {
                    assert!(lost <= 0.01, "{}: {method} lost {lost:.3}", run.spec);
                    assert!(r.reached_peak_area, "{}: {method}", run.spec);
                }
            }
        }
    }
}

#[test]
fn a_larger_t_is_not_more_opening() {
    // IH23: NCM reaches the largest area but not the largest expansion, which keeps growing
    // past the area peak.
    let ih23 = &runs()[0];
    let (ncm, rigid) = (result(ih23, Method::Ncm), result(ih23, Method::RigidModes));
    assert!(ncm.max_expansion < 0.95 * rigid.max_expansion, "{ncm:?}");
    assert!(rigid.max_area_t < 0.7, "{rigid:?}");
    // Rotating squares: the path closes again after t ≈ 0.5; NCM ends further along it
    // than the springs but with less area.
    let squares = &runs()[4];
    let (ncm, springs) = (
        result(squares, Method::Ncm),
        result(squares, Method::Springs),
    );
    let rigid = result(squares, Method::RigidModes);
    assert!((rigid.max_area_t - 0.5).abs() < 0.02, "{rigid:?}");
    assert!(rigid.final_area_ratio < 1.0, "{rigid:?}");
    assert!(ncm.final_t > springs.final_t + 0.05);
    assert!(ncm.final_area_ratio < springs.final_area_ratio);
}

/// The report `isogami deploy --all-steps` would print for this trajectory.
fn all_steps_report(run: &Run, method: Method, traj: &Trajectory) -> DeploymentReport {
    let settings = DeploySettings {
        method,
        ..DeploySettings::default()
    };
    let contact = ContactModel::new(&run.mech, settings.contact).unwrap();
    let all: Vec<usize> = (0..traj.steps.len()).collect();
    let frames = frame_records(&run.mech, &contact, traj, &all, settings.joint_tolerance).unwrap();
    build_report(run.spec, &run.mech, &settings, traj, &frames).unwrap()
}

#[test]
fn measures_agree_with_separate_deploy_runs() {
    for run in runs() {
        for (&method, traj) in METHODS.iter().zip(&run.trajectories) {
            let r = result(run, method);
            let report = all_steps_report(run, method, traj);
            let same = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(1.0);
            let what = format!("{} {method}", run.spec);
            assert_eq!(r.end_reason, report.end_reason, "{what}");
            assert_eq!(r.steps, report.steps, "{what}");
            assert_eq!(r.attempts, report.attempts, "{what}");
            assert!(same(r.max_area_ratio, report.max_area_ratio), "{what}");
            assert!(same(r.max_expansion, report.max_expansion), "{what}");
            assert!(same(r.min_expansion, report.min_expansion), "{what}");
            assert!(
                same(r.max_tile_rotation, report.max_tile_rotation),
                "{what}"
            );
            let last = report.frames.last().unwrap();
            assert!(same(r.final_area_ratio, last.measures.area_ratio), "{what}");
        }
    }
}

/// t along `traj` of the first state after which `f` decreases (the last state if none).
fn first_local_max(traj: &Trajectory, f: impl Fn(usize) -> f64) -> f64 {
    let n = traj.steps.len();
    let k = (1..n.saturating_sub(1))
        .find(|&k| f(k) >= f(k - 1) && f(k) > f(k + 1))
        .unwrap_or(n - 1);
    traj.t(k)
}

#[test]
fn springs_stop_where_the_pulled_lengths_stop_growing() {
    // The springs pull u and w outwards, so they stall where |u|² + |w|² first stops growing
    // along the mechanism's path, wherever the area peaks.
    for run in runs() {
        let rigid = &run.trajectories[0];
        let pulled = |k: usize| {
            let (u, w) = run.mech.lattice(&rigid.steps[k].q);
            u.norm_squared() + w.norm_squared()
        };
        let t_star = first_local_max(rigid, pulled);
        let springs = result(run, Method::Springs);
        assert!(
            (springs.final_t - t_star).abs() < 0.03,
            "{}: springs stop at {:.3}, |u|²+|w|² peaks at {t_star:.3}",
            run.spec,
            springs.final_t
        );
    }
}

#[test]
fn ncm_stops_where_the_path_turns_away_from_the_first_eigenvector() {
    // NCM measures progress as (q − q⁰)·v⁰, so it stops where that projection first stops
    // growing along the mechanism's path (paper §3.2, Discussion).
    for run in runs() {
        let rigid = &run.trajectories[0];
        let v0 = &rigid.initial_direction;
        let projection = |k: usize| (&rigid.steps[k].q - &run.mech.rest).dot(v0);
        let t_star = first_local_max(rigid, projection);
        let ncm = result(run, Method::Ncm);
        assert!(
            (ncm.final_t - t_star).abs() < 0.03,
            "{}: NCM stops at {:.3}, the projection peaks at {t_star:.3}",
            run.spec,
            ncm.final_t
        );
    }
}

/// The progress callback of a comparison sees every method's states and can stop it.
#[test]
fn comparison_progress_reports_each_method_and_cancels() {
    use isogami::api::{compare_with, resolve_design};
    let design = resolve_design("rotating-squares").unwrap();
    let settings = DeploySettings::default();
    let mut calls = Vec::new();
    let full = compare_with(&design, &settings, &mut |n| {
        calls.push(n);
        true
    })
    .unwrap();
    // Each method's count starts again (and so does a probe of the other opening sign).
    let restarts = calls.windows(2).filter(|w| w[1] < w[0]).count();
    assert!(restarts >= METHODS.len() - 1, "{calls:?}");
    let expected: usize = full.results.iter().map(|r| r.steps - 1).sum();
    assert!(
        calls.len() >= expected,
        "{} calls, {expected} accepted steps",
        calls.len()
    );
    let e = compare_with(&design, &settings, &mut |n| n < 3).unwrap_err();
    assert!(e.is_cancelled(), "{e}");
}

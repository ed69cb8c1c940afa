//! Issue 21, part A: summaries over the whole trajectory and exactly the frames asked for.
//!
//! A deployment's summary (expansions, area ratio, tile rotation, clearance, joint residual,
//! behaviour class, Poisson-like range) must not depend on how many frames were asked for, and
//! asking for N frames must give N frames, increasing in t, from the closed state to the final
//! state, each an exact, checked state.

use isogami::api::{deploy, resolve_design, DeployRequest, Deployment, FrameSelection};
use isogami::deploy::{
    frame_records_for, plan_frames, step_measures, DeployError, DeploySettings, DeploymentReport,
    FramePick, InsertProblem,
};
use isogami::math::Real;

/// Rotating squares (91 states with the default settings), an IH88 design whose 40 frames
/// missed its peak area ratio, and an orthotropic IH23 design (clockwise lattice).
const DESIGNS: [&str; 3] = [
    "rotating-squares",
    "IH88::1x1:aaabbaaba",
    "IH23:0.155769230769,0.35,0.225335752741,0.35:1x1:aa-a-",
];

const COUNTS: [usize; 5] = [2, 7, 40, 60, 120];

fn run(spec: &str, frames: FrameSelection) -> Deployment {
    let design = resolve_design(spec).unwrap();
    let request = DeployRequest {
        frames,
        ..DeployRequest::default()
    };
    deploy(&design, &request, &mut |_| true).unwrap_or_else(|e| panic!("{spec}: {e}"))
}

/// Every summary number of a report as bits, plus the class and the Poisson-like range.
fn summary(r: &DeploymentReport) -> (Vec<u64>, String, Option<(u64, u64)>) {
    let numbers = [
        r.max_expansion,
        r.min_expansion,
        r.max_area_ratio,
        r.max_tile_rotation,
        r.min_clearance,
        r.max_joint_residual,
        r.arc_length,
    ];
    (
        numbers.iter().map(|x| x.to_bits()).collect(),
        format!(
            "{:?} {} {} {:?}",
            r.behaviour, r.steps, r.attempts, r.end_reason
        ),
        r.poisson_range().map(|(a, b)| (a.to_bits(), b.to_bits())),
    )
}

#[test]
fn summaries_are_bit_identical_for_every_frame_count() {
    for spec in DESIGNS {
        let all = run(spec, FrameSelection::AllSteps);
        let want = summary(&all.report);
        assert!(want.2.is_some(), "{spec}: opens, so it has a Poisson range");
        for n in COUNTS {
            let got = run(spec, FrameSelection::Evenly(n));
            assert_eq!(
                summary(&got.report),
                want,
                "{spec}: {n} frames vs all steps"
            );
        }
    }
}

#[test]
fn exactly_the_frames_asked_for_come_back() {
    for spec in DESIGNS {
        let all = run(spec, FrameSelection::AllSteps);
        let states = all.trajectory.steps.len();
        let mut counts = COUNTS.to_vec();
        // Fewer states than frames asked for: frames are inserted.
        counts.push(2 * states + 3);
        for n in counts {
            let d = run(spec, FrameSelection::Evenly(n));
            let frames = &d.report.frames;
            let what = format!("{spec}: {n} frames of {states} states");
            assert_eq!(frames.len(), n, "{what}");
            assert_eq!(d.frames.len(), n, "{what}");
            assert!(
                frames.windows(2).all(|w| w[0].t < w[1].t),
                "{what}: t not strictly increasing"
            );
            // First the closed state, last the final state, both as accepted.
            assert_eq!(
                (frames[0].step, frames[0].t, frames[0].inserted),
                (0, 0.0, false)
            );
            assert_eq!(d.frames[0].q, d.mechanism.rest, "{what}");
            let last = frames.last().unwrap();
            assert_eq!((last.step, last.t, last.inserted), (states - 1, 1.0, false));
            assert_eq!(
                d.frames[n - 1].q,
                d.trajectory.steps[states - 1].q,
                "{what}"
            );
            let inserted = frames.iter().filter(|f| f.inserted).count();
            assert_eq!(inserted, n.saturating_sub(states), "{what}");
            // Accepted frames are distinct accepted states, as they are.
            let steps: Vec<usize> = frames
                .iter()
                .filter(|f| !f.inserted)
                .map(|f| f.step)
                .collect();
            assert!(
                steps.windows(2).all(|w| w[0] < w[1]),
                "{what}: a step repeats"
            );
            for (f, rec) in frames.iter().zip(&d.frames) {
                if !f.inserted {
                    assert_eq!(rec.q, d.trajectory.steps[f.step].q, "{what}");
                    continue;
                }
                // An inserted state lies in its gap of t and is an exact, overlap-free state
                // (checked here again, independently of the frame check).
                let k = f.step;
                assert!(
                    d.trajectory.t(k) < f.t && f.t < d.trajectory.t(k + 1),
                    "{what}"
                );
                let residual = d.mechanism.residual(&rec.q).amax();
                assert!(
                    residual <= DeploySettings::default().joint_tolerance,
                    "{what}: {residual}"
                );
                assert!(
                    d.contact.overlapping_pair(&d.mechanism, &rec.q).is_none(),
                    "{what}"
                );
                // Near the chord it was projected from, not somewhere else on the sheet.
                let (a, b) = (&d.trajectory.steps[k].q, &d.trajectory.steps[k + 1].q);
                let lambda =
                    (f.t - d.trajectory.t(k)) / (d.trajectory.t(k + 1) - d.trajectory.t(k));
                let chord = a + (b - a) * lambda;
                assert!((&rec.q - chord).norm() <= 0.1 * (b - a).norm(), "{what}");
            }
        }
    }
}

#[test]
fn frames_used_to_be_fewer_for_rotating_squares() {
    // The old selection dropped repeats of the nearest step: 120 asked, 91 came back.
    let d = run("rotating-squares", FrameSelection::Evenly(120));
    assert!(
        d.trajectory.steps.len() < 120,
        "{}",
        d.trajectory.steps.len()
    );
    assert_eq!(d.report.frames.len(), 120);
    // Also with more states than frames, where nearest-t picks collide near the end.
    for n in [60, 80, d.trajectory.steps.len()] {
        let d = run("rotating-squares", FrameSelection::Evenly(n));
        assert_eq!(d.report.frames.len(), n);
        assert!(d.report.frames.iter().all(|f| !f.inserted));
    }
}

#[test]
fn ih88_reports_the_peak_its_frames_miss() {
    let d = run("IH88::1x1:aaabbaaba", FrameSelection::Evenly(40));
    let over_steps = step_measures(&d.mechanism, &d.trajectory)
        .unwrap()
        .iter()
        .map(|m| m.area_ratio)
        .fold(Real::NEG_INFINITY, Real::max);
    let over_frames = d
        .report
        .frames
        .iter()
        .map(|f| f.measures.area_ratio)
        .fold(Real::NEG_INFINITY, Real::max);
    // The frames miss the peak (what the report used to say), the report does not.
    assert!(over_frames < over_steps, "{over_frames} vs {over_steps}");
    assert_eq!(d.report.max_area_ratio, over_steps);
    assert!(
        d.report.max_area_ratio > 3.9999,
        "{}",
        d.report.max_area_ratio
    );
}

#[test]
fn rotating_squares_principal_angle_is_zero_on_every_frame() {
    for frames in [FrameSelection::AllSteps, FrameSelection::Evenly(200)] {
        let d = run("rotating-squares", frames);
        for f in &d.report.frames {
            assert_eq!(f.measures.principal_angle, 0.0, "t = {}", f.t);
        }
    }
}

#[test]
fn a_frame_count_that_cannot_be_honoured_is_refused() {
    let d = run("rotating-squares", FrameSelection::AllSteps);
    let states = d.trajectory.steps.len();
    let picks = plan_frames(&d.trajectory, 120);
    assert_eq!(picks.len(), 120);
    assert!(picks.iter().any(|p| matches!(p, FramePick::Between { .. })));
    // An unreachable joint tolerance: the inserted states cannot be projected to it.
    let settings = DeploySettings {
        joint_tolerance: 1e-300,
        ..DeploySettings::default()
    };
    let err =
        frame_records_for(&d.mechanism, &d.contact, &d.trajectory, &picks, &settings).unwrap_err();
    assert!(
        matches!(
            err,
            DeployError::FrameCount { asked: 120, states: s, problem: InsertProblem::NotConverged { .. }, .. }
                if s == states
        ),
        "{err:?}"
    );
    let message = err.to_string();
    assert!(!message.contains('\n'), "{message}");
    assert!(message.starts_with("cannot return 120 frames"), "{message}");
    assert!(
        message.ends_with(&format!("ask for at most {states} frames (or all steps)")),
        "{message}"
    );
}

#[test]
fn stored_reports_keep_their_poisson_range() {
    let d = run(
        "IH23:0.155769230769,0.35,0.225335752741,0.35:1x1:aa-a-",
        FrameSelection::Evenly(7),
    );
    let json = serde_json::to_value(&d.report).unwrap();
    let range = d.report.poisson_range().unwrap();
    assert_eq!(json["poisson_range"], serde_json::json!([range.0, range.1]));
    let back: DeploymentReport = serde_json::from_value(json.clone()).unwrap();
    assert_eq!(back.poisson_range(), Some(range));
    // A report written before the range was stored reads it from its frames, as then.
    let mut old = json;
    old.as_object_mut().unwrap().remove("poisson_range");
    let old: DeploymentReport = serde_json::from_value(old).unwrap();
    let from_frames = isogami::deploy::poisson_range(
        d.report
            .frames
            .iter()
            .map(|f| (f.measures.min_expansion, f.measures.max_expansion)),
        d.report.max_expansion,
    );
    assert_eq!(old.poisson_range(), from_frames);
    // Over 7 frames the range is narrower than over every state.
    let (lo, hi) = from_frames.unwrap();
    assert!(
        lo >= range.0 && hi <= range.1 && (lo, hi) != range,
        "{lo} {hi} {range:?}"
    );
}

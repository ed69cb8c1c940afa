//! Inverse design on small, known inputs: the rotating squares' known optimum, constraints,
//! stopping, and validity of everything returned.

use isogami::api::{deploy, resolve_design, DeployRequest};
use isogami::inverse::{
    inverse_design, Candidate, Evaluator, Invalidity, InverseError, InverseProgress,
    InverseRequest, Outcome, Stage, Target, LEADERS,
};
use isogami::topology::Design;
use isogami::Error;
use std::collections::{HashMap, HashSet};
use std::sync::atomic::AtomicBool;

fn candidate(text: &str, with_report: bool) -> Candidate {
    let design = resolve_design(text).unwrap();
    let report = with_report.then(|| {
        deploy(&design, &DeployRequest::default(), &mut |_| true)
            .unwrap()
            .report
    });
    let topology = Design {
        params: design.family.default_params(),
        ..design.clone()
    }
    .to_string();
    Candidate {
        design,
        topology,
        report,
    }
}

/// Designs of a few families (the library's sample opening designs).
fn samples() -> Vec<Candidate> {
    isogami::topology::SAMPLE_OPENING_DESIGNS
        .iter()
        .skip(1)
        .take(4)
        .map(|s| candidate(s, true))
        .collect()
}

#[test]
fn rotating_squares_reach_area_ratio_two_at_45_degrees() {
    let mut pool = samples();
    pool.push(candidate("rotating-squares", false));
    let request = InverseRequest::new(Target::parse("area; families=IH76").unwrap());
    let result = inverse_design(&pool, &request, &mut |_| true).unwrap();
    assert_eq!(
        result.admitted, 1,
        "the family constraint keeps rotating squares only"
    );
    let best = &result.results[0].after;
    // (cos φ + sin φ)² = 1 + sin 2φ, largest at φ = 45°: 2.
    assert!((best.measures.max_area_ratio - 2.0).abs() < 2e-3);
    let at_max = best
        .report
        .frames
        .iter()
        .max_by(|a, b| a.measures.area_ratio.total_cmp(&b.measures.area_ratio))
        .unwrap();
    let phi = at_max.measures.max_tile_rotation.to_degrees();
    assert!((phi - 45.0).abs() < 3.0, "largest area at {phi}°");
}

#[test]
fn every_returned_design_is_valid_and_no_worse_than_screened() {
    let pool = samples();
    let target = Target::parse("uniform + 0.5*zero-poisson").unwrap();
    let mut request = InverseRequest::new(target.clone());
    request.top = 2;
    request.budget = 16;
    let mut stages = Vec::new();
    let result = inverse_design(&pool, &request, &mut |p| {
        stages.push(p.stage);
        true
    })
    .unwrap();
    assert!(!result.results.is_empty() && result.results.len() <= 2);
    assert!(stages.contains(&isogami::inverse::Stage::Verify));
    let ev = Evaluator {
        target: &target,
        settings: request.settings,
    };
    for r in &result.results {
        assert!(r.after.objective <= r.before.objective);
        assert_eq!(r.improved, r.after.objective < r.before.objective);
        let again = ev
            .evaluate(&r.after.design, r.after.kerf, &AtomicBool::new(false))
            .unwrap();
        assert_eq!(again.objective(), Some(r.after.objective));
        assert_eq!(r.after.report.dof, 1);
    }
    let topologies: std::collections::HashSet<_> =
        result.results.iter().map(|r| &r.topology).collect();
    assert_eq!(
        topologies.len(),
        result.results.len(),
        "different topologies"
    );
    let json = serde_json::to_string(&result).unwrap();
    assert!(json.contains("\"before\"") && json.contains("\"after\""));
}

#[test]
fn the_progress_callback_stops_the_run() {
    let pool = samples();
    let request = InverseRequest::new(Target::parse("area").unwrap());
    let mut calls = 0;
    let e = inverse_design(&pool, &request, &mut |_| {
        calls += 1;
        calls < 3
    })
    .unwrap_err();
    assert!(e.is_cancelled(), "{e}");
    assert_eq!(e, Error::Inverse(InverseError::Cancelled));
}

#[test]
fn leaders_only_improve_and_end_as_the_result() {
    let pool = samples();
    let mut request = InverseRequest::new(Target::parse("uniform + 0.5*zero-poisson").unwrap());
    request.top = 2;
    request.budget = 16;
    let mut reports: Vec<InverseProgress> = Vec::new();
    let result = inverse_design(&pool, &request, &mut |p| {
        reports.push(p.clone());
        true
    })
    .unwrap();
    let mut seen: HashMap<String, (f64, String)> = HashMap::new();
    let mut changes = 0;
    for p in &reports {
        assert!(p.leaders.len() <= LEADERS.max(request.top));
        let topologies: HashSet<&str> = p.leaders.iter().map(|l| l.topology.as_str()).collect();
        assert_eq!(topologies.len(), p.leaders.len(), "one leader per topology");
        assert!(p
            .leaders
            .windows(2)
            .all(|w| w[0].objective <= w[1].objective));
        // The run's best is the first leader's.
        assert_eq!(p.best, p.leaders.first().map(|l| l.objective));
        for l in &p.leaders {
            match seen.get(&l.topology) {
                Some((v, spec)) if *spec == l.spec => assert_eq!(*v, l.objective),
                Some((v, spec)) => {
                    assert!(
                        l.objective < *v,
                        "{} got worse: {v} -> {}",
                        spec,
                        l.objective
                    );
                    changes += 1;
                }
                None => {}
            }
            seen.insert(l.topology.clone(), (l.objective, l.spec.clone()));
        }
    }
    let last = &reports.last().unwrap().leaders;
    assert!(last.len() >= result.results.len());
    for (l, r) in last.iter().zip(&result.results) {
        assert_eq!(
            (&l.topology, &l.spec, l.objective, l.kerf),
            (&r.topology, &r.after.spec, r.after.objective, r.after.kerf)
        );
    }
    // Refinement improved a design here; the board showed it as it happened: a leader found
    // after screening.
    assert!(result.results.iter().any(|r| r.improved));
    assert!(changes > 0);
    assert!(last
        .iter()
        .any(|l| matches!(l.stage, Stage::Triage | Stage::Refine)));
}

#[test]
fn requests_and_candidates_are_checked() {
    let pool = samples();
    let mut request = InverseRequest::new(Target::parse("area").unwrap());
    request.top = 0;
    assert!(inverse_design(&pool, &request, &mut |_| true)
        .unwrap_err()
        .to_string()
        .contains("top 0"));
    // A NaN kerf is refused, also when the target's minimum kerf would otherwise hide it
    // in the maximum of the two.
    for target in ["area", "area; kerf>=0.02"] {
        let mut request = InverseRequest::new(Target::parse(target).unwrap());
        request.kerf = f64::NAN;
        let e = inverse_design(&pool, &request, &mut |_| true).unwrap_err();
        assert!(e.to_string().contains("kerf NaN"), "{e}");
    }
    let request = InverseRequest::new(Target::parse("area").unwrap());
    assert!(inverse_design(&[], &request, &mut |_| true)
        .unwrap_err()
        .to_string()
        .contains("no candidate designs given"));
    // No candidate passes: the error names the constraint, how many it removes and what
    // the candidates offer instead (issue 23 item 23: "no candidate designs pass the
    // constraints" named nothing).
    let families: Vec<String> = pool.iter().map(|c| c.design.family.to_string()).collect();
    let request = InverseRequest::new(Target::parse("area; families=IH7").unwrap());
    let e = inverse_design(&pool, &request, &mut |_| true)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(&format!(
            "none of the {} candidate designs passes the constraints: families=IH7 removes {}",
            pool.len(),
            pool.len()
        )),
        "{e}"
    );
    assert!(families.iter().all(|f| e.contains(f.as_str())), "{e}");
    let tiles: Vec<usize> = pool
        .iter()
        .map(|c| {
            let d = &c.design;
            d.family.info().aspect_count * usize::from(d.dims.a()) * usize::from(d.dims.b())
        })
        .collect();
    let (fewest, most) = (tiles.iter().min().unwrap(), tiles.iter().max().unwrap());
    let request = InverseRequest::new(Target::parse("isotropic; tiles>=40").unwrap());
    let e = inverse_design(&pool, &request, &mut |_| true)
        .unwrap_err()
        .to_string();
    let offer = if fewest == most {
        format!("their cells have {most} tiles")
    } else {
        format!("their cells have {fewest} to {most} tiles")
    };
    assert!(
        e.contains(&format!("tiles>=40 removes {} ({offer})", pool.len())),
        "{e}"
    );
    assert!(
        !e.contains("families"),
        "only the constraint that removes some: {e}"
    );
    // A hinge bridge as long as an edge fits no design: nothing valid, and the reason is
    // named with the count of designs it refused.
    let request = InverseRequest::new(Target::parse("area; hinge>=1").unwrap());
    match inverse_design(&pool, &request, &mut |_| true) {
        Err(Error::Inverse(e @ InverseError::NothingValid { screened, .. })) => {
            let text = e.to_string();
            assert!(
                text.contains(&format!(
                    "{screened} leave no room for a hinge>=1 (e.g. hinge clearance:"
                )),
                "{text}"
            );
        }
        other => panic!("{other:?}"),
    }
    let request = InverseRequest::new(Target::parse("area; rotation>=179").unwrap());
    let e = inverse_design(&pool, &request, &mut |_| true)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("turn their tiles by less than rotation>=179 (at most "),
        "{e}"
    );
}

#[test]
fn the_verdict_says_whether_a_value_was_reached_and_how_far_off() {
    let pool = vec![candidate("rotating-squares", true)];
    let run = |text: &str| {
        let mut request = InverseRequest::new(Target::parse(text).unwrap());
        request.budget = 0;
        inverse_design(&pool, &request, &mut |_| true).unwrap()
    };
    // Rotating squares open to twice their area: area(2) is met, area(1.6) is not (0.4 off:
    // its shape has no parameter to move), and the verdict says so with the distance.
    let met = run("area(2)");
    assert_eq!(met.met, Some(true));
    let v = &met.results[0].verdict;
    assert!(v.goals[0].value < 2e-3 && v.goals[0].tolerance == Some(0.01));
    assert!(
        v.summary().starts_with("target met: area(2) is "),
        "{}",
        v.summary()
    );
    let missed = run("area(1.6)");
    assert_eq!(missed.met, Some(false));
    let v = &missed.results[0].verdict;
    let reached = missed.results[0].after.measures.max_area_ratio;
    assert!((v.goals[0].value - (reached - 1.6)).abs() < 1e-12);
    assert!(
        v.summary().starts_with("target NOT met: area(1.6) is 0.39"),
        "{}",
        v.summary()
    );
    // A loose enough tolerance meets it.
    assert_eq!(run("area(1.6)~0.5").met, Some(true));
    // The unreachable lock: not met, with its distance.
    let lock = run("lock(6.07,6.07)");
    assert_eq!(lock.met, Some(false));
    assert!(lock.results[0].verdict.goals[0].value > 5.0);
    // Goals asking for the most have no verdict.
    assert_eq!(run("area").met, None);
}

#[test]
fn constraints_make_designs_invalid_with_a_reason() {
    let rs = resolve_design("rotating-squares").unwrap();
    let stop = AtomicBool::new(false);
    let check = |text: &str, kerf: f64| {
        let target = Target::parse(text).unwrap();
        let ev = Evaluator {
            target: &target,
            settings: Default::default(),
        };
        ev.evaluate(&rs, kerf, &stop).unwrap().outcome
    };
    assert!(matches!(check("area", 0.01), Outcome::Valid { .. }));
    assert!(matches!(
        check("area; kerf>=0.02", 0.01),
        Outcome::Invalid(Invalidity::Kerf { .. })
    ));
    assert!(matches!(
        check("area; tiles<=2", 0.01),
        Outcome::Invalid(Invalidity::Excluded { what: "tile count" })
    ));
    assert!(matches!(
        check("area; rotation>=100", 0.01),
        Outcome::Invalid(Invalidity::Rotation { .. })
    ));
    // A bridge of 0.05 L fits on the squares' edges; one as long as the edge cannot (the cut
    // must clear the joint's corner first).
    assert!(matches!(
        check("area; hinge>=0.05", 0.01),
        Outcome::Valid { .. }
    ));
    match check("area; hinge>=1", 0.01) {
        Outcome::Invalid(Invalidity::Hinge { problem }) => assert!(!problem.is_empty()),
        Outcome::Invalid(i) => panic!("{i}"),
        Outcome::Valid { .. } => panic!("a bridge of a whole edge fits"),
    }
    // A shape the exploration would not sample (a sliver) is invalid.
    let sliver: Design = "IH28:3,0.05:1x1:a--a-b-bbb".parse().unwrap();
    let target = Target::parse("area").unwrap();
    let ev = Evaluator {
        target: &target,
        settings: Default::default(),
    };
    assert!(matches!(
        ev.evaluate(&sliver, 0.01, &stop).unwrap().outcome,
        Outcome::Invalid(Invalidity::Shape { .. } | Invalidity::Build { .. })
    ));
}

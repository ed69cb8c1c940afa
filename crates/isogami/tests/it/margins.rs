//! Margins (issue 40): the stored shape tolerance agrees with deployments at shapes moved in
//! other, random directions; special designs lose their opening off their exact shape; the
//! most open state and the end of the path are those of the deployment's accepted states.

use super::common::Rng;
use isogami::api::{deploy, DeployRequest, FrameSelection};
use isogami::catalog::{
    largest_area_ratio, margins, margins_report, run_unit, shape_move, CatalogEntry,
    CatalogSettings, Margins, FABRICATION_TOLERANCE, KEPT_FRACTION, TOLERANCE_LEVELS,
};
use isogami::cell::CellDims;
use isogami::math::{Real, Vec2};
use isogami::tiling::{Family, Tiling};
use isogami::topology::Design;

fn settings() -> CatalogSettings {
    CatalogSettings {
        samples: 3,
        ..CatalogSettings::default()
    }
}

/// The entries of a rule-chosen set of units: every eighth family with shape parameters
/// (from IH1), each on its 1×1 cell.
fn entries() -> Vec<CatalogEntry> {
    let s = settings();
    Family::all()
        .filter(|f| f.param_count() > 0)
        .step_by(8)
        .flat_map(|f| {
            run_unit(f, CellDims::new(1, 1).unwrap(), &s)
                .unwrap()
                .entries
        })
        .collect()
}

/// The prototile's vertices about their centroid, and its mean edge length.
fn centred(family: Family, params: &[Real]) -> (Vec<Vec2>, Real) {
    let t = Tiling::new(family, params).unwrap();
    let v = t.prototile();
    let c = v.iter().fold(Vec2::zeros(), |a, p| a + p) / v.len() as Real;
    let n = v.len();
    let mean = (0..n).map(|i| (v[(i + 1) % n] - v[i]).norm()).sum::<Real>() / n as Real;
    (v.iter().map(|p| p - c).collect(), mean)
}

/// Largest vertex displacement (relative to the mean edge) between two shapes.
fn displacement(family: Family, a: &[Real], b: &[Real]) -> Real {
    let (va, mean) = centred(family, a);
    let (vb, _) = centred(family, b);
    va.iter()
        .zip(&vb)
        .map(|(p, q)| (q - p).norm())
        .fold(0.0, Real::max)
        / mean
}

/// `design` moved along a random direction of its parameters until its vertices move by
/// `delta` (relative to the mean edge): the step found by bisection on the measured
/// displacement, not from the library's rate.
fn moved_randomly(design: &Design, rng: &mut Rng, delta: Real) -> Design {
    let dir: Vec<Real> = design.params.iter().map(|_| rng.sym()).collect();
    let at = |s: Real| -> Vec<Real> {
        design
            .params
            .iter()
            .zip(&dir)
            .map(|(p, d)| p + s * d)
            .collect()
    };
    let (mut lo, mut hi) = (0.0, 1e-9);
    while displacement(design.family, &design.params, &at(hi)) < delta {
        lo = hi;
        hi *= 2.0;
        assert!(
            hi < 1.0,
            "{design}: no move of the parameters reaches {delta}"
        );
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if displacement(design.family, &design.params, &at(mid)) < delta {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    design.at_params(&at(hi))
}

#[test]
fn stored_tolerances_agree_with_moves_in_random_directions() {
    let s = settings();
    let deploy_settings = s.deploy_request().settings;
    let all = entries();
    assert!(all.len() >= 10, "{} entries", all.len());
    let mut rng = Rng::new(40);
    let (mut special, mut generic) = (0, 0);
    for e in &all {
        let m: Margins = e.margins.expect("every new entry has its margins");
        assert_eq!(
            m,
            margins(&e.design, &s).unwrap(),
            "{}: recomputed",
            e.design
        );
        let largest = e.report.max_area_ratio;
        let tolerance = m.shape_tolerance.expect("families with parameters");
        assert!(
            tolerance == 0.0 || TOLERANCE_LEVELS.contains(&tolerance),
            "{}: {tolerance}",
            e.design
        );
        if tolerance == 0.0 {
            // Special: a move of the smallest level in another direction loses the opening.
            special += 1;
            let moved = moved_randomly(&e.design, &mut rng, TOLERANCE_LEVELS[0]);
            let kept = largest_area_ratio(&moved, &deploy_settings) / largest;
            assert!(
                kept < KEPT_FRACTION,
                "{} special but {moved} keeps {kept}",
                e.design
            );
        } else {
            // Generic to `tolerance`: half of it in two other directions keeps nearly all of
            // the opening (0.9: other directions may cost more than the stored one).
            generic += 1;
            for _ in 0..2 {
                let moved = moved_randomly(&e.design, &mut rng, 0.5 * tolerance);
                let kept = largest_area_ratio(&moved, &deploy_settings) / largest;
                assert!(
                    kept >= 0.9,
                    "{} keeps its opening to {tolerance} but {moved} keeps {kept}",
                    e.design
                );
            }
        }
        let fab = m.fabrication_kept.unwrap();
        assert_eq!(
            fab >= KEPT_FRACTION,
            tolerance >= FABRICATION_TOLERANCE,
            "{}: kept {fab} at the fabrication tolerance, tolerance {tolerance}",
            e.design
        );
    }
    assert!(
        special > 0 && generic > 0,
        "{special} special, {generic} generic"
    );
}

#[test]
fn the_issues_special_design_is_special_and_locks_a_hair_off() {
    let design: Design = "IH42:0.230769230769,0.5:4x1:-aaabbbbbaaaabbb"
        .parse()
        .unwrap();
    let s = settings();
    let m = margins(&design, &s).unwrap();
    assert_eq!(m.shape_tolerance, Some(0.0), "{m:?}");
    assert!(m.is_special());
    assert!(m.fabrication_kept.unwrap() < KEPT_FRACTION, "{m:?}");
    // The issue's shape, 1e-9 off in the second parameter.
    let off: Design = "IH42:0.230769230769,0.500000001:4x1:-aaabbbbbaaaabbb"
        .parse()
        .unwrap();
    let largest = largest_area_ratio(&design, &s.deploy_request().settings);
    let kept = largest_area_ratio(&off, &s.deploy_request().settings) / largest;
    assert!(kept < KEPT_FRACTION, "kept {kept}");
}

#[test]
fn shape_moves_displace_the_vertices_by_what_they_claim() {
    let mut rng = Rng::new(7);
    for family in Family::all().filter(|f| f.param_count() > 0) {
        let design = Design::new(
            family,
            &family.default_params(),
            CellDims::new(1, 1).unwrap(),
            Vec::new(),
        );
        let Some(mv) = shape_move(&design).unwrap() else {
            continue;
        };
        let delta = TOLERANCE_LEVELS[rng.below(TOLERANCE_LEVELS.len())];
        for sign in [1.0, -1.0] {
            let params = mv.params(&design, delta, sign);
            let Ok(_) = Tiling::new(family, &params) else {
                continue;
            };
            let got = displacement(family, &design.params, &params);
            assert!(
                (got - delta).abs() <= 0.02 * delta,
                "{family}: moved {got} for {delta}"
            );
        }
    }
}

#[test]
fn the_most_open_state_and_the_end_are_the_deployments_states() {
    let s = settings();
    for e in entries().iter().step_by(3) {
        let m = e.margins.unwrap();
        let run = deploy(
            &e.design,
            &DeployRequest {
                settings: s.deploy_request().settings,
                frames: FrameSelection::AllSteps,
            },
            &mut |_| true,
        )
        .unwrap();
        let frames = &run.report.frames;
        let best = frames
            .iter()
            .map(|f| f.measures.area_ratio)
            .fold(Real::NEG_INFINITY, Real::max);
        let at_open = frames
            .iter()
            .min_by(|a, b| (a.t - m.open_t).abs().total_cmp(&(b.t - m.open_t).abs()))
            .unwrap();
        assert_eq!(at_open.measures.area_ratio, best, "{}", e.design);
        assert_eq!(best, e.report.max_area_ratio, "{}", e.design);
        let last = frames.last().unwrap();
        assert_eq!(last.t, 1.0);
        assert_eq!(last.measures.area_ratio, m.end_area_ratio, "{}", e.design);
        assert!(m.end_area_ratio <= best);
    }
}

/// The independent check of a whole database's stored tolerances (docs/validation/margins.md):
/// `ISOGAMI_MARGINS_CHECK=FILE` names a file of lines `SPEC TOLERANCE MAX_AREA_RATIO`
/// (tolerance `-` for a fixed shape), e.g. from
/// `sqlite3 -separator ' ' DB "select spec, ifnull(shape_tolerance, '-'), max_area_ratio from designs where origin = 'explored'"`.
/// Every design is moved by the fabrication tolerance in two random directions and by 1e-6 L in
/// one and deployed; the verdicts are compared with the stored ones and counted.
#[test]
#[ignore = "a validation run over a database: see docs/validation/margins.md"]
fn a_databases_tolerances_agree_with_moves_in_random_directions() {
    let Ok(path) = std::env::var("ISOGAMI_MARGINS_CHECK") else {
        panic!("set ISOGAMI_MARGINS_CHECK to the file of specs and stored tolerances");
    };
    let text = std::fs::read_to_string(path).unwrap();
    let s = settings().deploy_request().settings;
    let mut rng = Rng::new(2026);
    let (mut rows, mut agree_fab, mut special, mut special_lose, mut generic, mut generic_keep) =
        (0, 0, 0, 0, 0, 0);
    let mut disagreements = Vec::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let mut it = line.split_whitespace();
        let (spec, tol, largest) = (it.next().unwrap(), it.next().unwrap(), it.next().unwrap());
        if tol == "-" {
            continue;
        }
        let design: Design = spec.parse().unwrap();
        let tol: Real = tol.parse().unwrap();
        let largest: Real = largest.parse().unwrap();
        rows += 1;
        let kept = |d: &Design| largest_area_ratio(d, &s) / largest;
        let fab = (0..2)
            .map(|_| kept(&moved_randomly(&design, &mut rng, FABRICATION_TOLERANCE)))
            .fold(Real::INFINITY, Real::min);
        if (fab >= KEPT_FRACTION) == (tol >= FABRICATION_TOLERANCE) {
            agree_fab += 1;
        } else {
            disagreements.push(format!(
                "{spec}: stored {tol}, kept {fab:.4} at the fabrication tolerance"
            ));
        }
        let hair = kept(&moved_randomly(&design, &mut rng, TOLERANCE_LEVELS[0]));
        if tol == 0.0 {
            special += 1;
            special_lose += usize::from(hair < KEPT_FRACTION);
        } else {
            generic += 1;
            generic_keep += usize::from(hair >= KEPT_FRACTION);
        }
        if (tol == 0.0) != (hair < KEPT_FRACTION) {
            disagreements.push(format!("{spec}: stored {tol}, kept {hair:.4} 1e-6 L off"));
        }
    }
    println!(
        "{rows} designs with shape parameters: the fabrication verdict agrees for {agree_fab} \
         ({:.2} %); {special_lose} of {special} special designs lose their opening 1e-6 L off in \
         a random direction, {generic_keep} of {generic} others keep it",
        100.0 * agree_fab as Real / rows as Real
    );
    for d in &disagreements {
        println!("  {d}");
    }
    assert!(agree_fab as Real >= 0.98 * rows as Real);
}

/// The report `analyze` and `deploy` print from carries the finite patch's figures as the
/// catalogue stored them (every third entry of the rule's units).
#[test]
fn the_margins_report_carries_the_catalogues_finite_figures() {
    let s = settings();
    let mut seen = (0, 0);
    for e in entries().iter().step_by(3) {
        let report = margins_report(&e.design, &s).unwrap();
        assert_eq!(report.finite, e.finite, "{}", e.design);
        match e.finite.and_then(|f| f.covered) {
            Some(_) => seen.0 += 1,
            None => seen.1 += 1,
        }
        assert_eq!(Some(report.margins), e.margins, "{}", e.design);
    }
    assert!(seen.0 > 0, "no entry with a one-DOF sheet among {seen:?}");
}

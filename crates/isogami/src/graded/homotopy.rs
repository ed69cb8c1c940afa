//! A graded sheet that opens, whatever the target: the target approached from the design's
//! own sheet until the sheet stops opening.
//!
//! The optimisation ([`super::optimise`]) asks the pins to close in a few states and keeps
//! tiles apart by penalties; between those states, or where the penalties lose to the fit, a
//! sheet can still overlap or jam, and then it does not open. Its path check
//! ([`super::check_path`]) says so. Then, first, every state where two tiles overlap joins
//! the optimisation's states and the contacts weigh more, and the sheet is optimised again
//! from where it is, a few rounds. If it still does not open, the fit is blended: every
//! outline point is asked to lie a fraction λ of the way from where it lies on the design's
//! own (ungraded) sheet to the target (λ = 0: the ungraded sheet meets it; λ = 1: the target;
//! field cells likewise from their own area ratio), and λ is raised from 0 in steps, each try
//! graded from the last sheet that opened, with its states (a step that fails is halved). The
//! result is the sheet asked for when it opens, else the nearest sheet found that opens, with
//! how far it stays from the target (measured against the target itself, not the blend). More iterations cannot make the answer a sheet that
//! does not open: every sheet returned has passed its path check, unless the design's own
//! sheet fails it too.

use super::field::cell_ratios;
use super::problem::FitBlend;
use super::solve::measure;
use super::{
    check_path, optimise, setup, GradedProgress, GradedReport, GradedRequest, GradedSheet,
    PathCheck, Problem, SolveSettings,
};
use crate::math::Real;
use crate::stop::KeepGoing;

/// States of the path check.
pub const PATH_STEPS: usize = 20;

/// A graded sheet with its path check, and how much of the way to its target it went.
#[derive(Debug, Clone)]
pub struct Graded {
    /// The sheet.
    pub sheet: GradedSheet,
    /// The problem of the target asked (the measures are against it).
    pub problem: Problem,
    /// The optimisation's report, measured against the target asked (its iterations and
    /// seconds summed over every optimisation run, its cost the sheet's own).
    pub report: GradedReport,
    /// The path from the opened state to the closed tiling.
    pub path: PathCheck,
    /// How far towards the target the sheet was graded: 1 the target itself, 0 the design's
    /// own sheet (the ungraded one).
    pub target_fraction: Real,
}

/// Grades `request`'s sheet towards its target; when that sheet does not open along one
/// motion, grades it towards blends of the target with the design's own sheet and returns
/// the one nearest the target that opens (see the module's documentation).
pub fn grade_until_open(
    request: &GradedRequest,
    progress: &mut dyn FnMut(&GradedProgress) -> bool,
    keep_going: KeepGoing<'_>,
) -> Result<Graded, crate::Error> {
    // The optimisations' time over every try (the report's `seconds`: fit and closing
    // projection, not the path checks).
    let spent = std::cell::Cell::new(0.0);
    let iterations = std::cell::Cell::new(0);
    let (start, problem) = setup(request)?;
    let own_ratios = cell_ratios(&start, &problem.field);
    // One try: `from` (a sheet, its states part of the way and their openings in its
    // problem) graded towards the blend at `lambda`, then up to `rounds` refinements.
    let attempt = |from: &Graded,
                   lambda: Real,
                   rounds: usize,
                   settings: &SolveSettings,
                   progress: &mut dyn FnMut(&GradedProgress) -> bool|
     -> Result<Graded, crate::Error> {
        let mut sheet = from.sheet.clone();
        let mut blended = blend(&from.problem, &start, &own_ratios, lambda);
        let mut report = optimise(&mut sheet, &mut blended, settings, progress, keep_going)?;
        spent.set(spent.get() + report.seconds);
        iterations.set(iterations.get() + report.iterations);
        let mut path = check_path(&sheet, &blended, PATH_STEPS, keep_going)?;
        for _ in 0..rounds {
            let overlapping = path.states.iter().any(|s| s.overlap.is_some());
            if path.reached || !overlapping {
                break;
            }
            add_overlapping_states(&mut sheet, &mut blended, &path);
            // Contacts weigh more each round: they lose to the pins, made stiff by the fit's
            // last stages, by a hair otherwise.
            blended.weights.contact *= CONTACT_STIFFENING;
            let mut quiet = |_: &GradedProgress| true;
            report = optimise(&mut sheet, &mut blended, settings, &mut quiet, keep_going)?;
            spent.set(spent.get() + report.seconds);
            iterations.set(iterations.get() + report.iterations);
            path = check_path(&sheet, &blended, PATH_STEPS, keep_going)?;
        }
        // The target asked, with the states this sheet now has.
        let mut asked = from.problem.clone();
        asked.openings = blended.openings;
        // The fit's figures against the target asked, not the blend.
        let against = measure(&sheet, &asked);
        report = GradedReport {
            iterations: report.iterations,
            cost: report.cost,
            seconds: report.seconds,
            ..against
        };
        Ok(Graded {
            sheet,
            problem: asked,
            report,
            path,
            target_fraction: lambda,
        })
    };
    let timed = |mut g: Graded| {
        g.report.seconds = spent.get();
        g.report.iterations = iterations.get();
        g
    };
    // λ = 0: the ungraded sheet itself, which meets the blend without optimising (an
    // optimisation towards it would still move shapes for its other rows). Its path is
    // checked only when it is needed.
    let mut own_sheet = Graded {
        report: measure(&start, &problem),
        path: PathCheck::default(),
        sheet: start.clone(),
        problem: problem.clone(),
        target_fraction: 0.0,
    };
    let full = attempt(&own_sheet, 1.0, REFINEMENTS, &request.solve, progress)?;
    if full.path.reached || !request.fall_back {
        return Ok(timed(full));
    }
    own_sheet.path = check_path(&start, &problem, PATH_STEPS, keep_going)?;
    if !own_sheet.path.reached {
        // The design's own sheet does not open here either: nothing to fall back on.
        return Ok(timed(full));
    }
    // Continuation in λ: every try starts from the nearest sheet found so far that opens,
    // with its states, a step further; a step that fails is halved.
    let mut quiet = |_: &GradedProgress| true;
    // Each try starts from a sheet that opens, a step away: half the iterations.
    let settings = SolveSettings {
        max_iterations: request.solve.max_iterations.div_ceil(2),
        ..request.solve
    };
    let mut lo = own_sheet;
    let mut step = FIRST_STEP;
    for _ in 0..FALLBACK_TRIES {
        let lambda = lo.target_fraction + step;
        let tried = attempt(&lo, lambda, FALLBACK_REFINEMENTS, &settings, &mut quiet)?;
        if tried.path.reached {
            lo = tried;
        } else {
            step *= 0.5;
        }
    }
    Ok(timed(lo))
}

/// Tries of the fall-back's continuation from the design's own sheet towards the target.
pub const FALLBACK_TRIES: usize = 3;

/// The fall-back's first step in λ.
pub const FIRST_STEP: Real = 0.25;

/// Refinement rounds of each try of the fall-back.
pub const FALLBACK_REFINEMENTS: usize = 1;

/// Rounds in which the states where the path check finds two tiles overlapping join the
/// optimisation's states, and the sheet is optimised again from where it is.
pub const REFINEMENTS: usize = 4;

/// Factor on the contacts' weight in every refinement round.
pub const CONTACT_STIFFENING: Real = 10.0;

/// Adds to `sheet`'s states part of the way (and `problem`'s openings) every state of `path`
/// strictly between closed and opened where two tiles overlap, posed as the path check found
/// it. Contacts are kept only at the optimisation's states,
/// so a corner can pass through a neighbour between two of them: the state where it does
/// becomes one.
fn add_overlapping_states(sheet: &mut GradedSheet, problem: &mut Problem, path: &PathCheck) {
    let opened = *problem.openings.last().expect("a problem has a state");
    for state in &path.states {
        if state.overlap.is_none() || !(state.opening > 0.0 && state.opening < 1.0) {
            continue;
        }
        let opening = opened * state.opening;
        let last = problem.openings.len() - 1;
        if problem.openings[..last]
            .iter()
            .any(|&o| (o / opened - state.opening).abs() < 1e-9)
        {
            continue;
        }
        let at = problem.openings[..last]
            .iter()
            .position(|&o| o / opened > state.opening)
            .unwrap_or(last);
        problem.openings.insert(at, opening);
        sheet.path.insert(at, state.poses.clone());
    }
}

/// `problem` with its target blended a fraction `lambda` of the way from the start: every
/// outline point from its distance to the centre on `start` ([`FitBlend`]), every field cell
/// from its own area ratio there (`own_ratios`).
fn blend(problem: &Problem, start: &GradedSheet, own_ratios: &[Real], lambda: Real) -> Problem {
    let mut out = problem.clone();
    if lambda >= 1.0 {
        return out;
    }
    for (cell, r0) in out.field.iter_mut().zip(own_ratios) {
        cell.target = (1.0 - lambda) * r0 + lambda * cell.target;
    }
    let r0 = |points: &[(usize, usize)]| -> Vec<Real> {
        points
            .iter()
            .map(|&(i, n)| start.opened_corner(i, n).norm())
            .collect()
    };
    out.fit_from = Some(FitBlend {
        lambda,
        tips: r0(&problem.tips),
        inside: r0(&problem.inside),
    });
    out
}

#[cfg(test)]
mod tests {
    use super::super::deploy::self_intersecting;
    use super::super::{grade, parse_target};
    use super::*;
    use crate::stop::NEVER;

    /// The IH26 reproducer: graded to a disc at 3×3 cells, its sheet overlapped (tiles 0 and 1
    /// in the opened state, others part of the way) and the tool only said so. Now the
    /// states where it overlaps join the optimisation and the sheet opens along one motion,
    /// still near the disc, with no fall-back needed.
    #[test]
    fn the_overlapping_ih26_sheet_now_opens_along_one_motion() {
        let request = GradedRequest {
            design: "IH26:0.230769230769,0.225335752741:2x1:a-aaa-bbbb".into(),
            rows: 3,
            cols: 3,
            ..GradedRequest::default()
        };
        let graded = grade_until_open(&request, &mut |_| true, NEVER).unwrap();
        assert!(graded.path.reached, "{:#?}", graded.path);
        assert_eq!(graded.target_fraction, 1.0);
        assert!(
            graded.report.max_outline_error < 0.03,
            "{:?}",
            graded.report
        );
    }

    /// A target the sheet cannot open into (rotating squares, 2×2 cells, an L): the sheet
    /// graded towards it does not open; the answer is a sheet part of the way that does, its
    /// error measured against the L itself (larger than against the blend it was graded to).
    #[test]
    fn an_unreachable_target_gives_the_nearest_sheet_that_opens() {
        let request = GradedRequest {
            design: "rotating-squares".into(),
            rows: 2,
            cols: 2,
            ..GradedRequest::default()
        }
        .with_target(parse_target("polygon:0,0;2,0;2,1;1,1;1,2;0,2").unwrap());
        let exact = grade_until_open(
            &GradedRequest {
                fall_back: false,
                ..request.clone()
            },
            &mut |_| true,
            NEVER,
        )
        .unwrap();
        assert!(!exact.path.reached, "the L opens: no fall-back to test");
        let graded = grade_until_open(&request, &mut |_| true, NEVER).unwrap();
        assert!(graded.path.reached, "{:#?}", graded.path);
        assert!(
            graded.target_fraction > 0.0 && graded.target_fraction < 1.0,
            "{}",
            graded.target_fraction
        );
        // Its figures are against the L, not the blend it was graded towards.
        let (_, problem) = setup(&request).unwrap();
        let against = measure(&graded.sheet, &problem);
        assert_eq!(graded.report.max_outline_error, against.max_outline_error);
    }

    /// The blend's ends: at 0 the start meets it (every tip's fit row is zero, no other
    /// boundary corner's is active), though it misses the target; at 1 it is the target's.
    #[test]
    fn the_blend_runs_from_the_start_to_the_target() {
        let request = GradedRequest {
            rows: 3,
            cols: 3,
            ..GradedRequest::default()
        }
        .with_target(parse_target("ellipse:2,1").unwrap());
        let (start, mut problem) = setup(&request).unwrap();
        problem.full = true;
        let z = Problem::pack(&start);
        let fit_cost = |p: &Problem| {
            let mut without = p.clone();
            without.tips.clear();
            without.inside.clear();
            p.rows(&z).cost() - without.rows(&z).cost()
        };
        let zero = blend(&problem, &start, &[], 0.0);
        assert!(fit_cost(&zero).abs() < 1e-20, "{}", fit_cost(&zero));
        assert!(fit_cost(&problem) > 1.0, "{}", fit_cost(&problem));
        let half = blend(&problem, &start, &[], 0.5);
        assert!(fit_cost(&half) > 0.0 && fit_cost(&half) < fit_cost(&problem));
        assert_eq!(blend(&problem, &start, &[], 1.0).fit_from, None);
    }

    /// The concave reproducer (IH1, a 221° reflex corner), 3×3 cells graded to an ellipse:
    /// closed tile 33 crossed itself. Every triangle of a concave tile now keeps its area,
    /// and no closed tile crosses itself.
    #[test]
    fn concave_tiles_stay_simple_polygons() {
        let request = GradedRequest {
            design: super::super::CONCAVE_DESIGN.into(),
            rows: 3,
            cols: 3,
            ..GradedRequest::default()
        }
        .with_target(parse_target("ellipse:2,1").unwrap());
        let (sheet, problem, _) = grade(&request, &mut |_| true, NEVER).unwrap();
        assert!(!problem.triangles.is_empty());
        assert_eq!(self_intersecting(&sheet), Vec::<usize>::new());
    }
}

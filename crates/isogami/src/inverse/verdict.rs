//! Whether a design meets its target, and by how much it misses.
//!
//! A goal that names a value (`area(r)`, `expansion(θ°, e)`, `poisson(ν)`, `lock`, `lock-f`,
//! `path`) has a goal value that is a distance from it: the goal is met when that distance is
//! at most the term's tolerance ([`Term::effective_tolerance`]). A goal that asks for the most
//! (`area`, `expansion(θ°)`, `uniform`) has nothing to meet: its verdict is `None`, and the
//! design is simply the best found. The target is met when every goal that names a value is;
//! it has no verdict when none does.

use super::target::{Target, Term};
use crate::math::Real;
use serde::Serialize;

/// One goal's verdict.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GoalVerdict {
    /// The goal in canonical text.
    pub goal: String,
    /// Its goal value (unweighted): the distance from the value it names, or for goals that
    /// ask for the most, the negated amount reached.
    pub value: Real,
    /// The distance at which it is met; `None` when it asks for the most.
    pub tolerance: Option<Real>,
    /// Met within the tolerance; `None` when it asks for the most.
    pub met: Option<bool>,
}

/// Every goal's verdict and the target's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    /// Every goal naming a value is met (`None`: no goal names one).
    pub met: Option<bool>,
    /// Per goal, in the target's order.
    pub goals: Vec<GoalVerdict>,
    /// The verdict in one line for people ([`Verdict::summary`]).
    pub summary: String,
}

impl GoalVerdict {
    fn of(term: &Term, value: Real) -> GoalVerdict {
        let tolerance = term.effective_tolerance();
        GoalVerdict {
            goal: term.goal.to_string(),
            value,
            tolerance,
            met: tolerance.map(|tol| value <= tol),
        }
    }

    /// How many tolerances away it is (0 for goals that ask for the most).
    fn excess(&self) -> Real {
        self.tolerance.map_or(0.0, |tol| self.value / tol)
    }
}

impl Verdict {
    /// The verdict of goal values `terms` (a score's, in the target's order).
    pub fn of(target: &Target, terms: &[Real]) -> Verdict {
        let goals: Vec<GoalVerdict> = target
            .terms
            .iter()
            .zip(terms)
            .map(|(t, &v)| GoalVerdict::of(t, v))
            .collect();
        let judged: Vec<bool> = goals.iter().filter_map(|g| g.met).collect();
        let met = (!judged.is_empty()).then(|| judged.iter().all(|&m| m));
        let summary = summary(met, &goals);
        Verdict {
            met,
            goals,
            summary,
        }
    }

    /// One line for people: whether the target is met, and for a miss, how far the design
    /// is from each goal it misses (furthest first, in tolerances).
    pub fn summary(&self) -> &str {
        &self.summary
    }
}

/// See [`Verdict::summary`].
fn summary(met: Option<bool>, goals: &[GoalVerdict]) -> String {
    let distance = |g: &GoalVerdict| {
        format!(
            "{} is {} away (tolerance {})",
            g.goal,
            short(g.value),
            short(g.tolerance.unwrap_or(0.0))
        )
    };
    let most: Vec<&str> = goals
        .iter()
        .filter(|g| g.met.is_none())
        .map(|g| g.goal.as_str())
        .collect();
    let asks_most = |what: &str| match most.len() {
        0 => String::new(),
        1 => format!("; {} asks for the most{what}", most[0]),
        _ => format!("; {} ask for the most{what}", most.join(", ")),
    };
    match met {
        None => format!(
            "no value to meet{}: the design shown is the best found",
            asks_most("")
        ),
        Some(true) => {
            let within: Vec<String> = goals
                .iter()
                .filter(|g| g.met == Some(true))
                .map(distance)
                .collect();
            format!(
                "target met: {}{}",
                within.join("; "),
                asks_most(" (no verdict)")
            )
        }
        Some(false) => {
            let mut missed: Vec<&GoalVerdict> =
                goals.iter().filter(|g| g.met == Some(false)).collect();
            missed.sort_by(|a, b| b.excess().total_cmp(&a.excess()));
            let missed: Vec<String> = missed.into_iter().map(distance).collect();
            format!("target NOT met: {}", missed.join("; "))
        }
    }
}

/// Four significant digits, no trailing noise; below 0.001 in exponent form.
fn short(v: Real) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if v.abs() < 1e-3 {
        return format!("{v:.3e}");
    }
    let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn verdict(text: &str, terms: &[Real]) -> Verdict {
        Verdict::of(&Target::parse(text).unwrap(), terms)
    }

    #[test]
    fn value_goals_are_met_within_their_tolerance() {
        let v = verdict("area(1.6) + lock(0.1,0.2)~0.05", &[0.004, 0.049]);
        assert_eq!(v.met, Some(true));
        assert_eq!(v.goals[0].tolerance, Some(0.01));
        assert_eq!(
            v.summary(),
            "target met: area(1.6) is 0.004 away (tolerance 0.01); lock(0.1,0.2) is 0.049 away \
             (tolerance 0.05)"
        );
        // Just outside one tolerance: not met, and the miss is named with its distance.
        let v = verdict("area(1.6) + lock(0.1,0.2)~0.05", &[0.004, 0.0501]);
        assert_eq!(v.met, Some(false));
        assert_eq!(v.goals[0].met, Some(true));
        assert_eq!(
            v.summary(),
            "target NOT met: lock(0.1,0.2) is 0.0501 away (tolerance 0.05)"
        );
    }

    #[test]
    fn misses_are_listed_furthest_first_in_tolerances() {
        // 0.3 from a 0.05 Poisson tolerance (6×) is further than 0.05 from 0.01 (5×).
        let v = verdict("area(2) + isotropic", &[0.05, 0.3]);
        let s = v.summary();
        assert!(
            s.starts_with("target NOT met: poisson(-1) is 0.3 away (tolerance 0.05); area(2)"),
            "{s}"
        );
    }

    #[test]
    fn goals_asking_for_the_most_have_no_verdict() {
        let v = verdict("area + uniform", &[-1.0, -0.4]);
        assert_eq!(v.met, None);
        assert!(v.goals.iter().all(|g| g.met.is_none()));
        assert_eq!(
            v.summary(),
            "no value to meet; area, uniform ask for the most: the design shown is the best found"
        );
        // Beside a value goal they do not change the verdict, and are said to have none.
        let v = verdict("area + lock(6.07,6.07)", &[-1.0, 5.9]);
        assert_eq!(v.met, Some(false));
        let v = verdict("area + lock(0.1,0.1)", &[-1.0, 0.001]);
        assert_eq!(v.met, Some(true));
        assert!(
            v.summary()
                .ends_with("; area asks for the most (no verdict)"),
            "{}",
            v.summary()
        );
    }

    #[test]
    fn short_numbers() {
        assert_eq!(short(5.912345), "5.912");
        assert_eq!(short(0.0012341), "0.001234");
        assert_eq!(short(1.0471e-9), "1.047e-9");
        assert_eq!(short(0.01), "0.01");
        assert_eq!(short(1234.7), "1235");
        assert_eq!(short(0.0), "0");
    }
}

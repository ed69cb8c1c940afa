//! The compact text form of a target, for command lines and URLs, and its canonical writer.
//!
//! ```text
//! target     := goals (';' constraint)*
//! goals      := term ('+' term)*
//! term       := [weight '*'] goal ['~' tolerance]
//! goal       := area | area(r) | uniform | isotropic | zero-poisson
//!             | expansion(θ°) | expansion(θ°, e) | poisson(ν) | ratio(r)
//!             | lock(ε_min, ε_max [, θ°]) | lock-f(a, b, c, d)
//!             | path(t:ε_min:ε_max, ...)
//! constraint := families=IH1,IH28 | cells=1x1,2x1 | tiles<=N | tiles>=N | tiles=N
//!             | rotation>=DEG | kerf>=K | hinge>=H
//! ```
//!
//! Example: `2*area + isotropic; families=IH1,IH28; tiles<=6; hinge>=0.05`; "opens to 1.6
//! times its area, to within 2 %": `area(1.6)~0.02`. A tolerance is only taken by goals that
//! name a value (see [`super::target::Goal`]). Spaces are ignored; names are
//! case-insensitive. `Display` writes the canonical form (every weight,
//! numbers in Rust's shortest round-trip form), which parses back to an equal target.

//!
//! One file per part of the grammar: [`goal`] (terms and goals), [`constraint`], and
//! [`write`] (the canonical writer).

mod constraint;
mod goal;
mod write;

use super::error::InverseError;
use super::target::{Constraints, Target};
use crate::math::Real;
use crate::topology::quote_input;

fn number(what: &'static str, text: &str) -> Result<Real, InverseError> {
    let t = text.trim();
    t.parse::<Real>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| InverseError::NotANumber {
            what,
            text: quote_input(t),
        })
}

/// Splits `text` on `sep` outside parentheses. A `+` that is an exponent sign (`1e+3`) does
/// not split.
fn split_top(text: &str, sep: char) -> Vec<&str> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0usize);
    let bytes = text.as_bytes();
    for (i, c) in text.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            c if c == sep && depth == 0 => {
                let exponent = sep == '+'
                    && i >= 2
                    && matches!(bytes[i - 1], b'e' | b'E')
                    && bytes[i - 2].is_ascii_digit();
                if !exponent {
                    out.push(&text[start..i]);
                    start = i + 1;
                }
            }
            _ => {}
        }
    }
    out.push(&text[start..]);
    out
}

/// `name(args)` → (name, Some(args)); `name` → (name, None).
impl Target {
    /// Reads the compact text form (see the module documentation) and validates it.
    pub fn parse(text: &str) -> Result<Target, InverseError> {
        let mut parts = text.split(';');
        let goals = parts.next().unwrap_or("").trim();
        if goals.is_empty() {
            return Err(InverseError::NoGoal);
        }
        let terms = split_top(goals, '+')
            .into_iter()
            .map(goal::term)
            .collect::<Result<Vec<_>, _>>()?;
        let mut constraints = Constraints::default();
        for c in parts.filter(|p| !p.trim().is_empty()) {
            constraint::constraint(c, &mut constraints)?;
        }
        let target = Target { terms, constraints };
        target.validate()?;
        Ok(target)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::CellDims;
    use crate::inverse::target::{Goal, PathPoint};

    #[test]
    fn every_goal_and_constraint_reads() {
        let t = Target::parse(
            "2*area + expansion(30) + uniform + isotropic + zero-poisson + 0.5*ratio(0.25) \
             + lock(0.1,0.3) + lock-f(1.2,0,0.1,1.1) + area; families=IH28,ih1; cells=1x1,2x1; \
             tiles>=2; tiles<=8; rotation>=10; kerf>=0.02; hinge>=0.05",
        )
        .unwrap_err();
        // Nine goals: one too many.
        assert_eq!(t, InverseError::TooManyGoals { count: 9, max: 8 });
        let t = Target::parse(
            "2*area + expansion(30) + uniform + isotropic + 0.5*ratio(0.25) \
             + lock(0.1,0.3,15) + lock-f(1.2,0,0.1,1.1) + path(0:0:0, 0.5:0.05:0.1, 1:0.1:0.2); \
             families=IH28,ih1; cells=1x1,2x1; tiles>=2; tiles<=8; rotation>=10; kerf>=0.02; \
             hinge>=0.05",
        )
        .unwrap();
        assert_eq!(t.terms.len(), 8);
        assert_eq!(t.terms[0].weight, 2.0);
        assert_eq!(t.terms[0].goal, Goal::Area { ratio: None });
        assert_eq!(
            t.terms[1].goal,
            Goal::Expansion {
                angle_deg: 30.0,
                value: None
            }
        );
        assert_eq!(t.terms[3].goal, Goal::Poisson { nu: -1.0 });
        assert_eq!(t.terms[4].goal, Goal::Poisson { nu: -0.25 });
        assert_eq!(t.terms[4].weight, 0.5);
        assert_eq!(
            t.terms[5].goal,
            Goal::Lock {
                min: 0.1,
                max: 0.3,
                angle_deg: Some(15.0)
            }
        );
        assert_eq!(
            t.terms[6].goal,
            Goal::LockF {
                f: [[1.2, 0.0], [0.1, 1.1]]
            }
        );
        match &t.terms[7].goal {
            Goal::Path { points } => {
                assert_eq!(points.len(), 3);
                assert_eq!(
                    points[1],
                    PathPoint {
                        t: 0.5,
                        min: 0.05,
                        max: 0.1
                    }
                );
            }
            g => panic!("{g:?}"),
        }
        let c = &t.constraints;
        assert_eq!(c.families.len(), 2);
        assert_eq!(c.families[0].number(), 28);
        assert_eq!(
            c.cells,
            vec![CellDims::MINIMAL, CellDims::new(2, 1).unwrap()]
        );
        assert_eq!((c.min_tiles, c.max_tiles), (Some(2), Some(8)));
        assert_eq!(c.min_rotation_deg, Some(10.0));
        assert_eq!(c.min_kerf, Some(0.02));
        assert_eq!(c.min_hinge, Some(0.05));
        // Canonical text and JSON both give the same target back.
        let text = t.to_string();
        assert_eq!(Target::parse(&text).unwrap(), t, "{text}");
        let json = serde_json::to_string(&t).unwrap();
        assert_eq!(Target::from_json(&json).unwrap(), t, "{json}");
        assert_eq!(Target::resolve(&json).unwrap(), t);
    }

    #[test]
    fn values_and_tolerances_read_and_write_back() {
        let t = Target::parse("area(1.6)~0.02 + 2*expansion(30, 0.25) + isotropic~0.1").unwrap();
        assert_eq!(t.terms[0].goal, Goal::Area { ratio: Some(1.6) });
        assert_eq!(t.terms[0].tolerance, Some(0.02));
        assert_eq!(t.terms[0].effective_tolerance(), Some(0.02));
        assert_eq!(
            t.terms[1].goal,
            Goal::Expansion {
                angle_deg: 30.0,
                value: Some(0.25)
            }
        );
        assert_eq!((t.terms[1].weight, t.terms[1].tolerance), (2.0, None));
        assert_eq!(t.terms[1].effective_tolerance(), Some(0.01));
        assert_eq!(t.terms[2].effective_tolerance(), Some(0.1));
        let text = t.to_string();
        assert_eq!(
            text,
            "1*area(1.6)~0.02 + 2*expansion(30,0.25) + 1*poisson(-1)~0.1"
        );
        assert_eq!(Target::parse(&text).unwrap(), t);
        let json = serde_json::to_string(&t).unwrap();
        assert!(json.contains(r#"{"kind":"area","ratio":1.6}"#), "{json}");
        assert_eq!(Target::from_json(&json).unwrap(), t);
        // Goals that ask for the most keep their JSON and have no tolerance.
        let most = Target::parse("area + expansion(10) + uniform").unwrap();
        assert!(most.terms.iter().all(|t| t.effective_tolerance().is_none()));
        let json = serde_json::to_string(&most).unwrap();
        assert!(json.contains(r#"{"kind":"area"}"#), "{json}");
        assert!(!json.contains("tolerance"), "{json}");
    }

    #[test]
    fn exponents_are_not_term_separators() {
        let t = Target::parse("1e+1*area+2E+0*uniform").unwrap();
        assert_eq!(t.terms.len(), 2);
        assert_eq!(t.terms[0].weight, 10.0);
        assert_eq!(t.terms[1].weight, 2.0);
    }

    #[test]
    fn bad_targets_say_what_is_wrong_on_one_line() {
        let cases: &[(&str, &str)] = &[
            ("", "no goal"),
            ("  ; tiles<=3", "no goal"),
            ("areas", "unknown goal 'areas'"),
            ("expansion", "expansion takes an angle in degrees"),
            ("expansion(a)", "expansion 'a' is not a number"),
            ("expansion(1,2,3)", "expansion takes an angle in degrees"),
            ("area(1,2)", "area takes one area ratio"),
            ("area(0)", "area ratio 0 must lie in (0, 100]"),
            ("expansion(0,-1)", "expansion value -1 must lie in (-1, 10]"),
            ("area~0.1", "area asks for the most and takes no tolerance"),
            ("uniform ~ 0.1", "uniform asks for the most"),
            ("expansion(30)~0.1", "expansion(30) asks for the most"),
            ("area(1.6)~0", "tolerance 0 must lie in (0, 10]"),
            ("area(1.6)~x", "tolerance 'x' is not a number"),
            (
                "lock(0.3,0.1)",
                "lock min expansion 0.3 must be at most 0.1",
            ),
            ("lock(-2,0.1)", "lock min expansion -2 must lie in (-1, 10]"),
            ("lock-f(1,0,0,-1)", "det F -1 must be a finite number above"),
            ("poisson(-3)", "Poisson-like ratio -3 must lie in [-1, 100]"),
            ("poisson(NaN)", "is not a number"),
            ("path(0.5:0:0.1,0.2:0:0.1)", "strictly increasing t"),
            ("path(0.5:0)", "path takes points t:min:max"),
            ("0*area", "weight 0 must lie in (0, 1000000]"),
            ("x*area", "weight 'x' is not a number"),
            ("area; colour=red", "unknown constraint 'colour'"),
            ("area; tiles<=2; tiles<=3", "'tiles' given twice"),
            ("area; tiles>=5; tiles<=3", "min tiles 5 must be at most 3"),
            ("area; families=IH19", "IH19"),
            ("area; cells=9x9", "9x9"),
            ("area; kerf<=0.1", "kerf takes '>='"),
            ("area; kerf>=0.5", "min kerf 0.5 must lie in [0.0001, 0.2]"),
            ("area; hinge>=0", "min hinge 0 must lie in (0, 1]"),
            ("area; rotation", "expected KEY=VALUE"),
            ("{\"terms\": []}", "no goal"),
            (
                "{\"terms\": [{\"goal\": {\"kind\": \"area\"}, \"w\": 1}]}",
                "unknown field `w`",
            ),
            (
                "{\"terms\": [{\"goal\": {\"kind\": \"fly\"}}]}",
                "unknown variant `fly`",
            ),
            // Goals without fields refuse unknown keys too (issue 23 item 24).
            (
                "{\"terms\": [{\"goal\": {\"kind\": \"uniform\", \"weight\": 5}}]}",
                "unknown field `weight`",
            ),
            (
                "{\"terms\": [{\"goal\": {\"kind\": \"area\", \"nu\": 1}}]}",
                "unknown field `nu`",
            ),
            ("{", "target JSON"),
        ];
        for (text, want) in cases {
            let e = Target::resolve(text).unwrap_err().to_string();
            assert!(e.contains(want), "{text:?}: {e}");
            assert!(!e.contains('\n'), "{text:?}: {e}");
        }
    }

    #[test]
    fn weights_default_to_one_in_json() {
        let t = Target::from_json(
            r#"{"terms":[{"goal":{"kind":"lock","min":0.1,"max":0.2}}],
               "constraints":{"max_tiles":4,"families":["IH28"]}}"#,
        )
        .unwrap();
        assert_eq!(t.terms[0].weight, 1.0);
        assert_eq!(t.constraints.max_tiles, Some(4));
        assert_eq!(t.to_string(), "1*lock(0.1,0.2); families=IH28; tiles<=4");
    }
}

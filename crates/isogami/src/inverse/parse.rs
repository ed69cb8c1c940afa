//! The compact text form of a target, for command lines and URLs, and its canonical writer.
//!
//! ```text
//! target     := goals (';' constraint)*
//! goals      := term ('+' term)*
//! term       := [weight '*'] goal
//! goal       := area | uniform | isotropic | zero-poisson
//!             | expansion(θ°) | poisson(ν) | ratio(r)
//!             | lock(ε_min, ε_max [, θ°]) | lock-f(a, b, c, d)
//!             | path(t:ε_min:ε_max, ...)
//! constraint := families=IH1,IH28 | cells=1x1,2x1 | tiles<=N | tiles>=N | tiles=N
//!             | rotation>=DEG | kerf>=K | hinge>=H
//! ```
//!
//! Example: `2*area + isotropic; families=IH1,IH28; tiles<=6; hinge>=0.05`. Spaces are
//! ignored; names are case-insensitive. `Display` writes the canonical form (every weight,
//! numbers in Rust's shortest round-trip form), which parses back to an equal target.

use super::error::InverseError;
use super::target::{Constraints, Goal, PathPoint, Target, Term};
use crate::math::Real;
use crate::topology::quote_input;
use std::fmt;

const GOALS: &str =
    "area, expansion(deg), uniform, isotropic, zero-poisson, poisson(nu), ratio(r), \
                     lock(min,max[,deg]), lock-f(a,b,c,d), path(t:min:max,...)";
const CONSTRAINTS: &str = "families, cells, tiles, rotation, kerf, hinge";

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
fn call(text: &str) -> Result<(String, Option<&str>), InverseError> {
    let t = text.trim();
    match t.find('(') {
        None => Ok((t.to_ascii_lowercase(), None)),
        Some(open) => {
            let name = t[..open].trim().to_ascii_lowercase();
            let inner =
                t[open + 1..]
                    .strip_suffix(')')
                    .ok_or_else(|| InverseError::UnknownGoal {
                        name: quote_input(t),
                        known: GOALS,
                    })?;
            Ok((name, Some(inner)))
        }
    }
}

fn numbers(
    goal: &'static str,
    expected: &'static str,
    args: Option<&str>,
    counts: &[usize],
) -> Result<Vec<Real>, InverseError> {
    let wrong = || InverseError::GoalArguments {
        goal,
        expected,
        found: quote_input(args.unwrap_or("")),
    };
    let args = args.ok_or_else(wrong)?;
    let parts: Vec<&str> = args.split(',').collect();
    if !counts.contains(&parts.len()) || args.trim().is_empty() {
        return Err(wrong());
    }
    parts.iter().map(|p| number(goal, p)).collect()
}

fn no_args(goal: &'static str, args: Option<&str>) -> Result<(), InverseError> {
    match args {
        None => Ok(()),
        Some(a) => Err(InverseError::GoalArguments {
            goal,
            expected: "no arguments",
            found: quote_input(a),
        }),
    }
}

fn goal(text: &str) -> Result<Goal, InverseError> {
    let (name, args) = call(text)?;
    Ok(match name.as_str() {
        "area" => {
            no_args("area", args)?;
            Goal::Area {}
        }
        "uniform" => {
            no_args("uniform", args)?;
            Goal::Uniform {}
        }
        "isotropic" => {
            no_args("isotropic", args)?;
            Goal::Poisson { nu: -1.0 }
        }
        "zero-poisson" => {
            no_args("zero-poisson", args)?;
            Goal::Poisson { nu: 0.0 }
        }
        "expansion" => Goal::Expansion {
            angle_deg: numbers("expansion", "one angle in degrees", args, &[1])?[0],
        },
        "poisson" => Goal::Poisson {
            nu: numbers("poisson", "one ratio nu", args, &[1])?[0],
        },
        "ratio" => Goal::Poisson {
            nu: -numbers("ratio", "one ratio min/max", args, &[1])?[0],
        },
        "lock" => {
            let v = numbers("lock", "min, max[, angle in degrees]", args, &[2, 3])?;
            Goal::Lock {
                min: v[0],
                max: v[1],
                angle_deg: v.get(2).copied(),
            }
        }
        "lock-f" => {
            let v = numbers("lock-f", "four entries a, b, c, d of F", args, &[4])?;
            Goal::LockF {
                f: [[v[0], v[1]], [v[2], v[3]]],
            }
        }
        "path" => Goal::Path {
            points: path_points(args)?,
        },
        _ => {
            return Err(InverseError::UnknownGoal {
                name: quote_input(&name),
                known: GOALS,
            })
        }
    })
}

fn path_points(args: Option<&str>) -> Result<Vec<PathPoint>, InverseError> {
    let wrong = |found: &str| InverseError::GoalArguments {
        goal: "path",
        expected: "points t:min:max separated by commas",
        found: quote_input(found),
    };
    let args = args.ok_or_else(|| wrong(""))?;
    args.split(',')
        .map(|p| {
            let v: Vec<&str> = p.split(':').collect();
            if v.len() != 3 {
                return Err(wrong(p));
            }
            Ok(PathPoint {
                t: number("path t", v[0])?,
                min: number("path min", v[1])?,
                max: number("path max", v[2])?,
            })
        })
        .collect()
}

fn term(text: &str) -> Result<Term, InverseError> {
    match text.split_once('*') {
        Some((w, g)) => Ok(Term {
            weight: number("weight", w)?,
            goal: goal(g)?,
        }),
        None => Ok(Term {
            weight: 1.0,
            goal: goal(text)?,
        }),
    }
}

fn constraint(text: &str, c: &mut Constraints) -> Result<(), InverseError> {
    let t = text.trim();
    let bad = |problem: &str| InverseError::BadConstraint {
        text: quote_input(t),
        problem: problem.to_string(),
    };
    let (key, op, value) = ["<=", ">=", "="]
        .iter()
        .find_map(|op| t.split_once(op).map(|(k, v)| (k, *op, v)))
        .ok_or_else(|| bad("expected KEY=VALUE, KEY>=VALUE or KEY<=VALUE"))?;
    let key = key.trim().to_ascii_lowercase();
    let value = value.trim();
    let at_least = |name: &'static str, slot: &mut Option<Real>| -> Result<(), InverseError> {
        if op != ">=" {
            return Err(bad(&format!("{name} takes '>=' (a lower bound)")));
        }
        if slot.is_some() {
            return Err(InverseError::RepeatedConstraint { key: name });
        }
        *slot = Some(number(name, value)?);
        Ok(())
    };
    match key.as_str() {
        "families" | "family" => {
            if op != "=" || !c.families.is_empty() {
                return Err(bad("families=IH1,IH28 (once)"));
            }
            c.families = value
                .split(',')
                .map(|f| {
                    f.trim()
                        .parse()
                        .map_err(|e: crate::tiling::TilingError| bad(&e.to_string()))
                })
                .collect::<Result<_, _>>()?;
        }
        "cells" | "cell" => {
            if op != "=" || !c.cells.is_empty() {
                return Err(bad("cells=1x1,2x1 (once)"));
            }
            c.cells = value
                .split(',')
                .map(|d| {
                    d.trim()
                        .parse()
                        .map_err(|e: crate::cell::CellError| bad(&e.to_string()))
                })
                .collect::<Result<_, _>>()?;
        }
        "tiles" => {
            let n: u32 = value
                .parse()
                .map_err(|_| bad("the tile count must be a whole number"))?;
            let (lo, hi) = match op {
                ">=" => (Some(n), None),
                "<=" => (None, Some(n)),
                _ => (Some(n), Some(n)),
            };
            for (slot, v) in [(&mut c.min_tiles, lo), (&mut c.max_tiles, hi)] {
                if let Some(v) = v {
                    if slot.is_some() {
                        return Err(InverseError::RepeatedConstraint { key: "tiles" });
                    }
                    *slot = Some(v);
                }
            }
        }
        "rotation" => at_least("rotation", &mut c.min_rotation_deg)?,
        "kerf" => at_least("kerf", &mut c.min_kerf)?,
        "hinge" => at_least("hinge", &mut c.min_hinge)?,
        _ => {
            return Err(InverseError::UnknownConstraint {
                key: quote_input(&key),
                known: CONSTRAINTS,
            })
        }
    }
    Ok(())
}

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
            .map(term)
            .collect::<Result<Vec<_>, _>>()?;
        let mut constraints = Constraints::default();
        for c in parts.filter(|p| !p.trim().is_empty()) {
            constraint(c, &mut constraints)?;
        }
        let target = Target { terms, constraints };
        target.validate()?;
        Ok(target)
    }
}

impl fmt::Display for Goal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Goal::Area {} => f.write_str("area"),
            Goal::Uniform {} => f.write_str("uniform"),
            Goal::Expansion { angle_deg } => write!(f, "expansion({angle_deg})"),
            Goal::Poisson { nu } => write!(f, "poisson({nu})"),
            Goal::LockF { f: m } => {
                write!(f, "lock-f({},{},{},{})", m[0][0], m[0][1], m[1][0], m[1][1])
            }
            Goal::Lock {
                min,
                max,
                angle_deg,
            } => match angle_deg {
                Some(a) => write!(f, "lock({min},{max},{a})"),
                None => write!(f, "lock({min},{max})"),
            },
            Goal::Path { points } => {
                let p: Vec<String> = points
                    .iter()
                    .map(|p| format!("{}:{}:{}", p.t, p.min, p.max))
                    .collect();
                write!(f, "path({})", p.join(","))
            }
        }
    }
}

impl fmt::Display for Constraints {
    /// The constraints as `; key op value` items (empty when there are none).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let join = |v: Vec<String>| v.join(",");
        if !self.families.is_empty() {
            let names = self.families.iter().map(|x| x.to_string()).collect();
            write!(f, "; families={}", join(names))?;
        }
        if !self.cells.is_empty() {
            write!(
                f,
                "; cells={}",
                join(self.cells.iter().map(|x| x.to_string()).collect())
            )?;
        }
        if let Some(n) = self.min_tiles {
            write!(f, "; tiles>={n}")?;
        }
        if let Some(n) = self.max_tiles {
            write!(f, "; tiles<={n}")?;
        }
        if let Some(r) = self.min_rotation_deg {
            write!(f, "; rotation>={r}")?;
        }
        if let Some(k) = self.min_kerf {
            write!(f, "; kerf>={k}")?;
        }
        if let Some(h) = self.min_hinge {
            write!(f, "; hinge>={h}")?;
        }
        Ok(())
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let terms: Vec<String> = self
            .terms
            .iter()
            .map(|t| format!("{}*{}", t.weight, t.goal))
            .collect();
        write!(f, "{}{}", terms.join(" + "), self.constraints)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::CellDims;

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
        assert_eq!(t.terms[0].goal, Goal::Area {});
        assert_eq!(t.terms[1].goal, Goal::Expansion { angle_deg: 30.0 });
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
            ("expansion", "expansion takes one angle"),
            ("expansion(a)", "expansion 'a' is not a number"),
            ("expansion(1,2)", "expansion takes one angle"),
            ("area(3)", "area takes no arguments"),
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

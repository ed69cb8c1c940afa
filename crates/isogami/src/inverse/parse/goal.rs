//! Terms and goals of the text form: `[weight '*'] goal ['~' tolerance]`.

use super::number;
use crate::inverse::error::InverseError;
use crate::inverse::target::{Goal, PathPoint, Term};
use crate::math::Real;
use crate::topology::quote_input;

pub(super) const GOALS: &str = "area, area(r), expansion(deg), expansion(deg,e), uniform, \
     isotropic, zero-poisson, poisson(nu), ratio(r), lock(min,max[,deg]), lock-f(a,b,c,d), \
     path(t:min:max,...)";

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
        "area" => Goal::Area {
            ratio: match args {
                None => None,
                Some(_) => Some(numbers("area", "one area ratio (or none)", args, &[1])?[0]),
            },
        },
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
        "expansion" => {
            let v = numbers(
                "expansion",
                "an angle in degrees and optionally the expansion to reach",
                args,
                &[1, 2],
            )?;
            Goal::Expansion {
                angle_deg: v[0],
                value: v.get(1).copied(),
            }
        }
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

/// `[weight '*'] goal ['~' tolerance]`.
pub(super) fn term(text: &str) -> Result<Term, InverseError> {
    let (text, tolerance) = match text.rsplit_once('~') {
        Some((t, tol)) => (t, Some(number("tolerance", tol)?)),
        None => (text, None),
    };
    let (weight, goal_text) = match text.split_once('*') {
        Some((w, g)) => (number("weight", w)?, g),
        None => (1.0, text),
    };
    Ok(Term {
        goal: goal(goal_text)?,
        weight,
        tolerance,
    })
}

//! What a user asks of a design: weighted goals and constraints.
//!
//! A [`Target`] is read from compact text ([`Target::parse`], see [`super::parse`]) or JSON
//! ([`Target::from_json`]); both give the same value, and [`Target`]'s `Display` writes the
//! canonical text that parses back to it. Every number is checked by [`Target::validate`].
//!
//! Measures are those of `measure` (paper §4.3): F maps the closed tiling vectors to the
//! current ones, U is the right stretch tensor of F = RU (the sheet's overall turn R removed),
//! the principal expansions ε_min ≤ ε_max are the eigenvalues of U − I, ε(θ) = dᵀ(U − I)d
//! for d = (cos θ, sin θ) in the closed sheet's frame, the area ratio is det F, and the
//! Poisson-like ratio of a frame is ν = −ε_min/ε_max. How each goal becomes a number to
//! minimise is documented on [`Goal`] and computed in [`super::objective`].

use super::error::InverseError;
use crate::cell::CellDims;
use crate::contact::{MAX_KERF, MIN_KERF};
use crate::math::Real;
use crate::settings_error::Requirement;
use crate::tiling::Family;
use serde::{Deserialize, Serialize};

/// Most goals in one target.
pub const MAX_GOALS: usize = 8;
/// Most points of an expansion path.
pub const MAX_PATH_POINTS: usize = 100;

/// One sample of a prescribed expansion path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PathPoint {
    /// Deployment parameter t in [0, 1].
    pub t: Real,
    /// Wanted smallest principal expansion at t.
    pub min: Real,
    /// Wanted largest principal expansion at t.
    pub max: Real,
}

/// One behaviour to aim for. Each becomes a value to minimise ([`super::objective`]):
///
/// | goal | text | value (smaller is better) |
/// |---|---|---|
/// | `Area` | `area` | −(A − 1), A the largest area ratio det F over every step of the deployment (the report's `max_area_ratio`) |
/// | `Area` with a ratio | `area(r)` | \|A − r\|: the sheet opens to r times its closed area |
/// | `Expansion` | `expansion(θ°)` | −max over frames of ε(θ) |
/// | `Expansion` with a value | `expansion(θ°, e)` | \|max over frames of ε(θ) − e\| |
/// | `Uniform` | `uniform` | −max over frames of ε_min (the most uniformly opening sheet) |
/// | `Poisson` | `poisson(ν)`, `isotropic` (ν = −1), `zero-poisson` (ν = 0), `ratio(r)` (ν = −r) | max over the open states of \|ν_state − ν\| |
/// | `LockF` | `lock-f(a,b,c,d)` | ‖U_end − U*‖ (Frobenius), U* the stretch of F* = [[a, b], [c, d]] |
/// | `Lock` | `lock(ε_min,ε_max)` or `lock(ε_min,ε_max,θ°)` | ‖U_end − U*‖ with U* = R(θ) diag(1 + ε_max, 1 + ε_min) R(θ)ᵀ; without θ, the distance of the end state's principal expansions from (ε_min, ε_max) |
/// | `Path` | `path(t:ε_min:ε_max, …)` | root mean square over the points of the distance of (ε_min(t), ε_max(t)) from the wanted pair |
///
/// "Open states" are the accepted states of the deployment whose largest principal expansion
/// reaches [`POISSON_OPEN_FRACTION`](crate::deploy::POISSON_OPEN_FRACTION) of the largest one
/// reached (the report's Poisson-like range, which the database's `poisson_min`/`poisson_max`
/// store). "End" is the
/// last state of the deployment, where contact stops it: a design whose deployment ends for
/// another reason does not meet a lock goal. F is compared through U, because the sheet's
/// overall rotation is a convention of the solver (tile 0 is held fixed).
///
/// `area`, `expansion(θ°)` and `uniform` ask for the most of something: they have no value
/// to meet. Every other goal names a value, and its goal value is the distance from it: it
/// is *met* when that distance is at most the term's tolerance
/// ([`Goal::default_tolerance`] unless the term gives one; see [`super::verdict`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind", deny_unknown_fields)]
pub enum Goal {
    /// Largest area ratio, or a given one. (Written with braces so that unknown keys beside
    /// its `kind` are refused: serde ignores them on a unit variant.)
    Area {
        /// The area ratio the sheet should open to (largest over the deployment); absent:
        /// as large as possible.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        ratio: Option<Real>,
    },
    /// Largest expansion along a direction, or a given one.
    Expansion {
        /// Direction in degrees from the closed sheet's x axis.
        angle_deg: Real,
        /// The largest expansion ε(θ) the sheet should reach; absent: as large as possible.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        value: Option<Real>,
    },
    /// Largest smallest principal expansion (braces: see `Area`).
    Uniform {},
    /// A Poisson-like ratio held over the opening.
    Poisson {
        /// Wanted ν = −ε_min/ε_max (−1 isotropic, 0 one axis fixed).
        nu: Real,
    },
    /// A deformation gradient at the contact limit.
    LockF {
        /// F* as rows.
        f: [[Real; 2]; 2],
    },
    /// Principal expansions (and optionally their direction) at the contact limit.
    Lock {
        /// Wanted smallest principal expansion.
        min: Real,
        /// Wanted largest principal expansion.
        max: Real,
        /// Wanted direction of the largest expansion, degrees (any when absent).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        angle_deg: Option<Real>,
    },
    /// Principal expansions as functions of t.
    Path {
        /// Samples, t strictly increasing.
        points: Vec<PathPoint>,
    },
}

/// A goal with its weight in the sum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Term {
    /// The goal.
    pub goal: Goal,
    /// Its weight (finite, > 0; default 1).
    #[serde(default = "one")]
    pub weight: Real,
    /// Largest goal value at which the goal counts as met; absent: the goal's default
    /// ([`Goal::default_tolerance`]). Only goals that name a value take one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<Real>,
}

impl Term {
    /// A term of weight 1 with the goal's default tolerance.
    pub fn of(goal: Goal) -> Term {
        Term {
            goal,
            weight: 1.0,
            tolerance: None,
        }
    }

    /// The tolerance the verdict uses: the term's own, else the goal's default; `None` for
    /// goals that ask for the most of something.
    pub fn effective_tolerance(&self) -> Option<Real> {
        self.tolerance.or_else(|| self.goal.default_tolerance())
    }
}

fn one() -> Real {
    1.0
}

/// Requirements every returned design must meet besides validity. Empty lists and `None`
/// do not constrain.
///
/// - `families`: the design's tiling family is one of these.
/// - `cells`: its supercell a×b is one of these.
/// - `min_tiles`, `max_tiles`: bounds on the number of tiles in the cell.
/// - `min_rotation_deg`: rotation margin — the largest tile rotation reached over the
///   deployment (relative to the sheet) is at least this many degrees, so that the sheet
///   opens by a clear rotation before contact stops it, not by a sliver a fabrication
///   tolerance would eat.
/// - `min_kerf`: the cut width the design is deployed with (units of the mean edge length
///   L) is at least this; a refined kerf never goes below it.
/// - `min_hinge`: hinge clearance — a laser-cut bridge of this width (units of L) fits at
///   every joint: the export's cut layout (`export::laser`, the same as `isogami export
///   --format svg`) of a closed 2×2-cell patch with this hinge and the design's kerf
///   succeeds (every bridge lies on its edge with room for the cut between bridges).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Constraints {
    /// Allowed families.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub families: Vec<Family>,
    /// Allowed supercells.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub cells: Vec<CellDims>,
    /// Fewest tiles in the cell.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_tiles: Option<u32>,
    /// Most tiles in the cell.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_tiles: Option<u32>,
    /// Smallest largest-tile-rotation, degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_rotation_deg: Option<Real>,
    /// Smallest kerf (units of L).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_kerf: Option<Real>,
    /// Smallest hinge bridge that must fit (units of L).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_hinge: Option<Real>,
}

/// Goals with weights, and constraints.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Target {
    /// Weighted goals; the objective is Σ weight · value.
    pub terms: Vec<Term>,
    /// Constraints.
    #[serde(default)]
    pub constraints: Constraints,
}

fn range(what: &'static str, value: Real, requirement: Requirement) -> InverseError {
    InverseError::OutOfRange {
        what,
        value,
        requirement,
    }
}

/// Checks value ∈ [low, high] (finite).
fn within(what: &'static str, value: Real, low: Real, high: Real) -> Result<(), InverseError> {
    if value.is_finite() && (low..=high).contains(&value) {
        Ok(())
    } else {
        Err(range(what, value, Requirement::closed(low, high)))
    }
}

/// Expansions are dimensionless stretches minus one: U stays positive definite above −1.
fn expansion(what: &'static str, value: Real) -> Result<(), InverseError> {
    if value.is_finite() && value > -1.0 && value <= 10.0 {
        Ok(())
    } else {
        Err(range(
            what,
            value,
            Requirement::Within {
                low: -1.0,
                high: 10.0,
                open_low: true,
                open_high: false,
            },
        ))
    }
}

impl Goal {
    /// Checks every number of the goal.
    pub fn validate(&self) -> Result<(), InverseError> {
        match self {
            Goal::Area { ratio: None } | Goal::Uniform {} => Ok(()),
            Goal::Area { ratio: Some(r) } => {
                if r.is_finite() && *r > 0.0 && *r <= 100.0 {
                    Ok(())
                } else {
                    Err(range(
                        "area ratio",
                        *r,
                        Requirement::Within {
                            low: 0.0,
                            high: 100.0,
                            open_low: true,
                            open_high: false,
                        },
                    ))
                }
            }
            Goal::Expansion { angle_deg, value } => {
                within("angle", *angle_deg, -360.0, 360.0)?;
                value.map_or(Ok(()), |e| expansion("expansion value", e))
            }
            Goal::Poisson { nu } => within("Poisson-like ratio", *nu, -1.0, 100.0),
            Goal::LockF { f } => {
                for v in f.iter().flatten() {
                    within("F entry", *v, -10.0, 10.0)?;
                }
                let det = f[0][0] * f[1][1] - f[0][1] * f[1][0];
                if det > 1e-6 {
                    Ok(())
                } else {
                    Err(range("det F", det, Requirement::Above(1e-6)))
                }
            }
            Goal::Lock {
                min,
                max,
                angle_deg,
            } => {
                expansion("lock min expansion", *min)?;
                expansion("lock max expansion", *max)?;
                if min > max {
                    return Err(range("lock min expansion", *min, Requirement::AtMost(*max)));
                }
                if let Some(a) = angle_deg {
                    within("angle", *a, -360.0, 360.0)?;
                }
                Ok(())
            }
            Goal::Path { points } => {
                if points.is_empty() || points.len() > MAX_PATH_POINTS {
                    return Err(range(
                        "path point count",
                        points.len() as Real,
                        Requirement::CountIn {
                            low: 1,
                            high: MAX_PATH_POINTS as u64,
                        },
                    ));
                }
                let mut last = Real::NEG_INFINITY;
                for (index, p) in points.iter().enumerate() {
                    if !(p.t.is_finite() && (0.0..=1.0).contains(&p.t) && p.t > last) {
                        return Err(InverseError::PathOrder { index, t: p.t });
                    }
                    last = p.t;
                    expansion("path min expansion", p.min)?;
                    expansion("path max expansion", p.max)?;
                    if p.min > p.max {
                        return Err(range(
                            "path min expansion",
                            p.min,
                            Requirement::AtMost(p.max),
                        ));
                    }
                }
                Ok(())
            }
        }
    }

    /// True when the goal looks at the end of the deployment (the contact limit).
    pub fn needs_contact_limit(&self) -> bool {
        matches!(self, Goal::LockF { .. } | Goal::Lock { .. })
    }

    /// True when the goal names a value to meet (its goal value is a distance from it);
    /// false for `area`, `expansion(θ°)` and `uniform`, which ask for the most.
    pub fn names_a_value(&self) -> bool {
        !matches!(
            self,
            Goal::Area { ratio: None } | Goal::Expansion { value: None, .. } | Goal::Uniform {}
        )
    }

    /// The distance at which a goal that names a value is met, unless the term says
    /// otherwise: 0.01 for expansions, stretches and area ratios (1 % of the closed size),
    /// 0.05 for a Poisson-like ratio (which varies over the opening of most sheets); `None`
    /// for goals that ask for the most.
    pub fn default_tolerance(&self) -> Option<Real> {
        match self {
            _ if !self.names_a_value() => None,
            Goal::Poisson { .. } => Some(POISSON_TOLERANCE),
            _ => Some(VALUE_TOLERANCE),
        }
    }
}

/// Default tolerance of goals on expansions, stretches and area ratios.
pub const VALUE_TOLERANCE: Real = 0.01;
/// Default tolerance of a Poisson-like ratio goal.
pub const POISSON_TOLERANCE: Real = 0.05;

impl Constraints {
    /// Checks every bound.
    pub fn validate(&self) -> Result<(), InverseError> {
        if let (Some(lo), Some(hi)) = (self.min_tiles, self.max_tiles) {
            if lo > hi {
                return Err(range(
                    "min tiles",
                    Real::from(lo),
                    Requirement::AtMost(Real::from(hi)),
                ));
            }
        }
        if let Some(r) = self.min_rotation_deg {
            within("min rotation (degrees)", r, 0.0, 180.0)?;
        }
        if let Some(k) = self.min_kerf {
            within("min kerf", k, MIN_KERF, MAX_KERF)?;
        }
        if let Some(h) = self.min_hinge {
            if !(h.is_finite() && h > 0.0 && h <= 1.0) {
                return Err(range(
                    "min hinge",
                    h,
                    Requirement::Within {
                        low: 0.0,
                        high: 1.0,
                        open_low: true,
                        open_high: false,
                    },
                ));
            }
        }
        Ok(())
    }

    /// True when a design of `family` on cell `dims` with `tiles` tiles may be returned.
    pub fn admits_cell(&self, family: Family, dims: CellDims, tiles: usize) -> bool {
        let tiles = tiles as u64;
        (self.families.is_empty() || self.families.contains(&family))
            && (self.cells.is_empty() || self.cells.contains(&dims))
            && self.min_tiles.is_none_or(|m| tiles >= u64::from(m))
            && self.max_tiles.is_none_or(|m| tiles <= u64::from(m))
    }
}

impl Target {
    /// A target of one goal with weight 1 and no constraints.
    pub fn goal(goal: Goal) -> Target {
        Target {
            terms: vec![Term::of(goal)],
            constraints: Constraints::default(),
        }
    }

    /// Checks the goals, weights and constraints.
    pub fn validate(&self) -> Result<(), InverseError> {
        if self.terms.is_empty() {
            return Err(InverseError::NoGoal);
        }
        if self.terms.len() > MAX_GOALS {
            return Err(InverseError::TooManyGoals {
                count: self.terms.len(),
                max: MAX_GOALS,
            });
        }
        for t in &self.terms {
            if !(t.weight.is_finite() && t.weight > 0.0 && t.weight <= 1e6) {
                return Err(range(
                    "weight",
                    t.weight,
                    Requirement::Within {
                        low: 0.0,
                        high: 1e6,
                        open_low: true,
                        open_high: false,
                    },
                ));
            }
            t.goal.validate()?;
            if let Some(tol) = t.tolerance {
                if !t.goal.names_a_value() {
                    return Err(InverseError::ToleranceWithoutValue {
                        goal: t.goal.to_string(),
                    });
                }
                if !(tol.is_finite() && tol > 0.0 && tol <= 10.0) {
                    return Err(range(
                        "tolerance",
                        tol,
                        Requirement::Within {
                            low: 0.0,
                            high: 10.0,
                            open_low: true,
                            open_high: false,
                        },
                    ));
                }
            }
        }
        self.constraints.validate()
    }

    /// Reads a target from its JSON form and validates it.
    pub fn from_json(text: &str) -> Result<Target, InverseError> {
        let target: Target = serde_json::from_str(text).map_err(|e| InverseError::Json {
            message: e.to_string().replace('\n', " "),
        })?;
        target.validate()?;
        Ok(target)
    }

    /// Reads a target from JSON (text starting with `{`) or from the compact text form.
    pub fn resolve(text: &str) -> Result<Target, InverseError> {
        if text.trim_start().starts_with('{') {
            Target::from_json(text)
        } else {
            Target::parse(text)
        }
    }

    /// True when some goal looks at the contact limit.
    pub fn needs_contact_limit(&self) -> bool {
        self.terms.iter().any(|t| t.goal.needs_contact_limit())
    }
}

//! Errors of inverse design: a target that cannot be read or is out of range, a request
//! outside its limits, a run stopped by its caller. Every message is one line.

use crate::math::Real;
use crate::settings_error::Requirement;
use thiserror::Error;

/// What is wrong with a target, its text or JSON form, or an inverse-design request.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum InverseError {
    /// No goal was given.
    #[error("target: no goal given (e.g. 'area', 'isotropic', 'lock(0.1,0.3)')")]
    NoGoal,
    /// More goals than allowed.
    #[error("target: {count} goals, at most {max}")]
    TooManyGoals {
        /// Goals given.
        count: usize,
        /// Most allowed.
        max: usize,
    },
    /// A goal name that is not known.
    #[error("target: unknown goal '{name}' (known: {known})")]
    UnknownGoal {
        /// What was written (escaped, at most 40 characters).
        name: String,
        /// The known names.
        known: &'static str,
    },
    /// A goal with the wrong arguments.
    #[error("target: {goal} takes {expected}, got '{found}'")]
    GoalArguments {
        /// The goal.
        goal: &'static str,
        /// What it takes.
        expected: &'static str,
        /// What was written.
        found: String,
    },
    /// Text where a number was expected.
    #[error("target: {what} '{text}' is not a number")]
    NotANumber {
        /// Which value.
        what: &'static str,
        /// What was written.
        text: String,
    },
    /// A number outside its range.
    #[error("target: {what} {value} must {requirement}")]
    OutOfRange {
        /// Which value.
        what: &'static str,
        /// The value given.
        value: Real,
        /// What it must be.
        requirement: Requirement,
    },
    /// An expansion path whose points are not in increasing t.
    #[error(
        "target: path points must have strictly increasing t in [0, 1] (point {index} has t = {t})"
    )]
    PathOrder {
        /// 0-based point index.
        index: usize,
        /// Its t.
        t: Real,
    },
    /// A tolerance on a goal that asks for the most of something (nothing to be within).
    #[error("target: {goal} asks for the most and takes no tolerance; name a value (area(r), expansion(deg,e)) to be met within one")]
    ToleranceWithoutValue {
        /// The goal, in canonical text.
        goal: String,
    },
    /// A constraint key that is not known.
    #[error("target: unknown constraint '{key}' (known: {known})")]
    UnknownConstraint {
        /// What was written.
        key: String,
        /// The known keys.
        known: &'static str,
    },
    /// A constraint that cannot be read.
    #[error("target: constraint '{text}': {problem}")]
    BadConstraint {
        /// What was written.
        text: String,
        /// What is wrong.
        problem: String,
    },
    /// A constraint given twice.
    #[error("target: constraint '{key}' given twice")]
    RepeatedConstraint {
        /// The key.
        key: &'static str,
    },
    /// The target's JSON form could not be read.
    #[error("target JSON: {message}")]
    Json {
        /// serde_json's message (one line).
        message: String,
    },
    /// The catalogue or deployment settings of the request are out of range.
    #[error("inverse design settings: {message}")]
    Settings {
        /// The settings error's message.
        message: String,
    },
    /// No candidate design was given.
    #[error("inverse design: no candidate designs given (is the database empty?)")]
    NoCandidates,
    /// No candidate passes the family, cell and tile constraints.
    #[error(
        "inverse design: none of the {total} candidate designs passes the constraints: {removed}"
    )]
    NoneAdmitted {
        /// Candidates given.
        total: usize,
        /// Each constraint that removes some, with how many and what the candidates offer
        /// (e.g. "tiles>=40 removes 120 (their cells have 1 to 16 tiles)").
        removed: String,
    },
    /// None of the candidates is a valid design that meets the target's requirements.
    #[error("inverse design: none of the {screened} screened designs is valid for this target: {reasons}")]
    NothingValid {
        /// How many were deployed.
        screened: usize,
        /// What made them invalid, most common first, with counts (e.g. "40 turn their
        /// tiles by less than rotation>=30 (at most 22.1°)").
        reasons: String,
    },
    /// The caller's progress callback stopped the run.
    #[error("inverse design stopped by the caller")]
    Cancelled,
}

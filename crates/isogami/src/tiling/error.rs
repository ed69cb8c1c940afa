//! What can be wrong with a family name or a family's shape parameters.

use super::family::Family;
use super::shape::format_params;
use crate::geometry::SimplicityProblem;
use crate::math::Real;
use std::fmt;
use thiserror::Error;

/// A family or shape parameters that give no usable tiling.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum TilingError {
    /// A family name or number that is not one of the 81 isohedral types.
    #[error("unknown tiling family '{input}' (expected IH1..IH93, one of the 81 realizable types; see `isogami families`)")]
    UnknownFamily {
        /// The name as given, escaped and shortened for a one-line message.
        input: String,
    },
    /// The wrong number of shape parameters for a family.
    #[error("family {family} takes {expected} shape parameter(s), got {got}")]
    ParamCount {
        /// The family.
        family: Family,
        /// Parameters the family takes.
        expected: usize,
        /// Parameters given.
        got: usize,
    },
    /// A shape parameter that is NaN or infinite.
    #[error("shape parameter v{index} is {value} (must be a finite number)")]
    ParamNotFinite {
        /// Index of the parameter.
        index: usize,
        /// The offending value.
        value: Real,
    },
    /// Shape parameters that give an unusable tile.
    #[error(
        "{family} with parameters [{}]: {culprit} {} {} {problem}",
        format_params(.params),
        .culprit.verb(),
        .problem.article()
    )]
    InvalidShape {
        /// The family.
        family: Family,
        /// The parameters as given.
        params: Vec<Real>,
        /// Which parameter(s) cause it.
        culprit: Culprit,
        /// What is wrong with the tile.
        problem: ShapeProblem,
    },
}

/// The shape parameters responsible for an invalid tile: (index, value) pairs.
#[derive(Debug, Clone, PartialEq)]
pub enum Culprit {
    /// The family's default parameters themselves.
    Defaults,
    /// Each of these parameters, changed alone from the default, breaks the tile.
    Alone(Vec<(usize, Real)>),
    /// None breaks it alone; these changed parameters do together.
    Together(Vec<(usize, Real)>),
}

impl Culprit {
    /// "gives" for one parameter, "give" for several or the default parameters.
    pub fn verb(&self) -> &'static str {
        match self {
            Culprit::Alone(ix) | Culprit::Together(ix) if ix.len() == 1 => "gives",
            _ => "give",
        }
    }
}

impl ShapeProblem {
    /// "an" before a problem whose text starts with a vowel ("an inverted tile"), else "a".
    pub fn article(&self) -> &'static str {
        let text = self.to_string();
        match text.chars().next() {
            Some('a' | 'e' | 'i' | 'o' | 'u') => "an",
            _ => "a",
        }
    }
}

impl fmt::Display for Culprit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names = |ix: &[(usize, Real)]| {
            ix.iter()
                .map(|(i, v)| format!("v{i}={v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        match self {
            Culprit::Defaults => f.write_str("the default parameters"),
            Culprit::Alone(ix) if ix.len() == 1 => write!(f, "parameter {}", names(ix)),
            Culprit::Alone(ix) => write!(f, "parameters {} (each alone)", names(ix)),
            Culprit::Together(ix) => write!(f, "parameters {} together", names(ix)),
        }
    }
}

/// What is wrong with a tile.
#[derive(Debug, Clone, PartialEq)]
pub enum ShapeProblem {
    /// All vertices coincide (or the tile's size is not finite).
    Degenerate,
    /// The prototile is not a simple polygon.
    NotSimple(SimplicityProblem),
    /// The vertices run the other way round than at the default parameters.
    Inverted,
    /// The tiles cover more or less than a lattice cell.
    Overlap {
        /// Area the tiles of one cell cover.
        covered: Real,
        /// Area of the lattice cell.
        lattice: Real,
    },
}

impl fmt::Display for ShapeProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ShapeProblem::Degenerate => f.write_str("degenerate tile (all vertices coincide)"),
            ShapeProblem::NotSimple(p) => write!(f, "{p}"),
            ShapeProblem::Inverted => {
                f.write_str("inverted tile (its vertices run the other way round)")
            }
            ShapeProblem::Overlap { covered, lattice } => write!(
                f,
                "tiling whose tiles overlap (tiles cover {covered:.6} per lattice cell of area {lattice:.6})"
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_invalid_shape_reads_as_english() {
        let error = |culprit, problem| {
            TilingError::InvalidShape {
                family: Family::from_number(28).unwrap(),
                params: vec![0.1, 0.2],
                culprit,
                problem,
            }
            .to_string()
        };
        let one = error(Culprit::Alone(vec![(1, 0.2)]), ShapeProblem::Inverted);
        assert!(
            one.ends_with(
                "parameter v1=0.2 gives an inverted tile (its vertices run the other way round)"
            ),
            "{one}"
        );
        let two = error(
            Culprit::Together(vec![(0, 0.1), (1, 0.2)]),
            ShapeProblem::Degenerate,
        );
        assert!(two.contains("together give a degenerate tile"), "{two}");
        let defaults = error(Culprit::Defaults, ShapeProblem::Degenerate);
        assert!(
            defaults.contains("the default parameters give a degenerate"),
            "{defaults}"
        );
    }
}

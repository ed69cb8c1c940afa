//! The library's one error type. Every variant says what was wrong and where, in a single
//! line, so front ends can print it as is.

use thiserror::Error;

/// Everything that can go wrong in the pipeline.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A family name or number that is not one of the 81 isohedral types.
    #[error("unknown tiling family '{0}' (expected IH1..IH93, one of the 81 realizable types; see `isogami families`)")]
    UnknownFamily(String),
    /// The wrong number of shape parameters for a family.
    #[error("family {family} takes {expected} shape parameter(s), got {got}")]
    ParamCount {
        /// Family name, e.g. "IH28".
        family: String,
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
        value: f64,
    },
    /// Shape parameters that give an unusable tile.
    #[error("{family} with parameters [{params}]: {culprit} give(s) a {problem}")]
    InvalidShape {
        /// Family name.
        family: String,
        /// The parameters as given.
        params: String,
        /// Which parameter(s) cause it, e.g. "v1" or "v0 and v2 together".
        culprit: String,
        /// What is wrong with the tile.
        problem: String,
    },
    /// A supercell size outside 1..=4 or a malformed "AxB" string.
    #[error("bad cell '{0}': expected AxB with 1 <= A, B <= 4, e.g. 2x1")]
    BadCell(String),
    /// A design spec string or JSON that cannot be read.
    #[error("bad design spec: {0}")]
    BadSpec(String),
    /// A joint that names an edge the cell does not have.
    #[error(
        "joint on edge {index} is out of range: the cell has {edges} unique edges (0..{edges})"
    )]
    JointIndex {
        /// The edge index given.
        index: usize,
        /// Number of unique edges of the cell.
        edges: usize,
    },
    /// A cell whose geometry does not tile the plane (a bug or an extreme parameter).
    #[error("cell geometry check failed: {0}")]
    CellGeometry(String),
    /// A setting (kerf, step sizes, method, tolerance) outside its range.
    #[error("invalid setting: {0}")]
    Settings(String),
    /// A design with nothing to deploy.
    #[error("{0}")]
    Rigid(String),
    /// A numerical routine that failed (non-convergence, non-finite values).
    #[error("numerical failure: {0}")]
    Numerical(String),
    /// The caller's progress callback asked to stop (a closed connection, Ctrl-C).
    #[error("cancelled")]
    Cancelled,
}

/// Result alias for the library.
pub type Result<T> = std::result::Result<T, Error>;

//! Python exceptions: one class per kind of library error, all below `isogami.IsogamiError`,
//! each carrying the library's one-line message unchanged.
//!
//! A library error is classed by the stage it comes from, looking through the wrapping a
//! caller stage adds: an unknown family inside a design spec is a `TilingError`, a bad kerf
//! inside a deployment a `SettingsError`, a cancelled deployment a `CancelledError`.

use isogami::deploy::DeployError as LibDeployError;
use isogami::topology::DesignError as LibDesignError;
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    isogami,
    IsogamiError,
    PyException,
    "Base class of every error the isogami library reports."
);
create_exception!(
    isogami,
    TilingError,
    IsogamiError,
    "An unknown tiling family, or shape parameters that give no usable tile (wrong count, NaN, a self-intersecting or inverted tile)."
);
create_exception!(
    isogami,
    CellError,
    IsogamiError,
    "A supercell size outside 1x1..4x4, or a cell whose geometry does not tile."
);
create_exception!(
    isogami,
    DesignError,
    IsogamiError,
    "A design spec string or design JSON that cannot be read, or joints that do not fit the cell."
);
create_exception!(
    isogami,
    KinematicsError,
    IsogamiError,
    "The mechanism (rigid tiles and pin joints) of a design cannot be assembled."
);
create_exception!(
    isogami,
    MobilityError,
    IsogamiError,
    "The mobility analysis failed (non-finite state, eigen-solver without convergence)."
);
create_exception!(
    isogami,
    ContactError,
    IsogamiError,
    "The contact model (kerf-inset collision polygons) cannot be built or queried."
);
create_exception!(
    isogami,
    DeployError,
    IsogamiError,
    "A deployment that cannot run or finish: a rigid design, a frame that fails its check, a comparison that fails."
);
create_exception!(
    isogami,
    CancelledError,
    DeployError,
    "A long call (deployment, export, inverse design) stopped before its end: the progress callback returned False or the timeout passed."
);
create_exception!(
    isogami,
    MeasureError,
    IsogamiError,
    "Expansion measures that cannot be computed (degenerate or inverted lattice, non-finite input)."
);
create_exception!(
    isogami,
    LinkageError,
    IsogamiError,
    "The linkage analysis of a design failed."
);
create_exception!(
    isogami,
    ExploreError,
    IsogamiError,
    "The topology enumeration failed."
);
create_exception!(
    isogami,
    SettingsError,
    IsogamiError,
    "A setting outside its allowed range (kerf, tolerances, step control, frame count, mode)."
);
create_exception!(
    isogami,
    StoreError,
    IsogamiError,
    "A design database that cannot be opened or read (missing, not an isogami database, damaged, other schema)."
);
create_exception!(
    isogami,
    QueryError,
    StoreError,
    "A catalogue query that cannot be run: an unknown facet value or measure, a NaN bound, an empty range."
);
create_exception!(
    isogami,
    ExportError,
    IsogamiError,
    "An export that cannot be made: patch size, scale, state or format settings out of range."
);
create_exception!(
    isogami,
    InverseError,
    IsogamiError,
    "An inverse-design target that cannot be read or is out of range, a request outside its limits, or no valid candidate design for it."
);
create_exception!(
    isogami,
    ShapeError,
    IsogamiError,
    "Shape-aware mobility that cannot be computed: a design without exactly one degree of freedom, a pinned parameter, a path that leaves the well-shaped tiles."
);

create_exception!(
    isogami,
    FiniteError,
    IsogamiError,
    "A finite sheet that cannot be made, deployed or graded: an empty or bad region, a request out of range, no one-DOF sheet in the region, a floppy sheet asked to deploy, a graded sheet's target that cannot be read (text or SVG file) or a graded run's file that cannot be loaded."
);

/// The Python exception of a library error.
pub fn library(e: isogami::Error) -> PyErr {
    use isogami::Error as E;
    let message = e.to_string();
    match &e {
        E::Tiling(_) | E::Design(LibDesignError::Tiling(_)) => TilingError::new_err(message),
        E::Cell(_) | E::Design(LibDesignError::Cell(_)) => CellError::new_err(message),
        E::Design(_) => DesignError::new_err(message),
        E::Kinematics(_) => KinematicsError::new_err(message),
        E::Mobility(_) => MobilityError::new_err(message),
        E::Contact(_) => ContactError::new_err(message),
        E::Deploy(d) => deploy(d, message),
        E::Measure(_) => MeasureError::new_err(message),
        E::Linkage(_) => LinkageError::new_err(message),
        E::Explore(_) => ExploreError::new_err(message),
        E::Settings(_) => SettingsError::new_err(message),
        E::Inverse(_) => InverseError::new_err(message),
        E::Shape(_) => ShapeError::new_err(message),
        E::Finite(_) => FiniteError::new_err(message),
        E::Graded(g) => graded(g, message),
        _ => IsogamiError::new_err(message),
    }
}

/// The class of a deployment error, looking through the wrapping of a comparison.
fn deploy(e: &LibDeployError, message: String) -> PyErr {
    match e {
        LibDeployError::Settings(_)
        | LibDeployError::ModeOutOfRange { .. }
        | LibDeployError::Grip { .. } => SettingsError::new_err(message),
        LibDeployError::Contact(_) => ContactError::new_err(message),
        LibDeployError::Mobility(_) => MobilityError::new_err(message),
        LibDeployError::Measure(_) => MeasureError::new_err(message),
        LibDeployError::Cancelled => CancelledError::new_err(message),
        LibDeployError::InMethod { error, .. } => deploy(error, message),
        _ => DeployError::new_err(message),
    }
}

/// The class of a graded-sheet error: a finite sheet's, but for settings and cancellation.
fn graded(e: &isogami::graded::GradedError, message: String) -> PyErr {
    use isogami::graded::GradedError as G;
    match e {
        G::BadSetting(_) => SettingsError::new_err(message),
        G::Cancelled => CancelledError::new_err(message),
        _ => FiniteError::new_err(message),
    }
}

/// The Python exception of a store error; `path` prefixes the message as the CLI does.
pub fn store(e: isogami_store::StoreError, path: &str) -> PyErr {
    let message = format!("{path}: {e}");
    match e {
        isogami_store::StoreError::InvalidQuery(_) => QueryError::new_err(message),
        _ => StoreError::new_err(message),
    }
}

/// The Python exception of a query vocabulary error.
pub fn query(e: isogami_store::query::QueryError) -> PyErr {
    QueryError::new_err(e.to_string())
}

/// Registers every exception class in the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    for (name, class) in [
        ("IsogamiError", py.get_type::<IsogamiError>()),
        ("TilingError", py.get_type::<TilingError>()),
        ("CellError", py.get_type::<CellError>()),
        ("DesignError", py.get_type::<DesignError>()),
        ("KinematicsError", py.get_type::<KinematicsError>()),
        ("MobilityError", py.get_type::<MobilityError>()),
        ("ContactError", py.get_type::<ContactError>()),
        ("DeployError", py.get_type::<DeployError>()),
        ("CancelledError", py.get_type::<CancelledError>()),
        ("MeasureError", py.get_type::<MeasureError>()),
        ("LinkageError", py.get_type::<LinkageError>()),
        ("ExploreError", py.get_type::<ExploreError>()),
        ("SettingsError", py.get_type::<SettingsError>()),
        ("StoreError", py.get_type::<StoreError>()),
        ("QueryError", py.get_type::<QueryError>()),
        ("ExportError", py.get_type::<ExportError>()),
        ("InverseError", py.get_type::<InverseError>()),
        ("ShapeError", py.get_type::<ShapeError>()),
        ("FiniteError", py.get_type::<FiniteError>()),
    ] {
        m.add(name, class)?;
    }
    Ok(())
}

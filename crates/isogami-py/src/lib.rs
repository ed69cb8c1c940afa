//! The `isogami` Python package's native module `isogami._isogami`: PyO3 bindings over the
//! library (`isogami::api`, the measures, the linkage analysis, `isogami::export`) and the design
//! database (`isogami-store`), never over the command line. Plain data in, numpy arrays and
//! plain Python values out; library errors become one exception class per kind; long calls
//! release the GIL and can be interrupted.
//!
//! One module per concern: `design`, `family`, `cell`, `mobility`, `settings`,
//! `deployment` (with `progress`), `measure`, `linkage`, `compare`, `query` and `database`,
//! `export`, `inverse`, `shape`, `finite` (finite sheets), `graded` (graded sheets), `errors`, and `convert` for the boundary's conversions.

mod cell;
mod compare;
mod convert;
mod database;
mod deployment;
mod deployment_state;
mod design;
mod errors;
mod export;
mod family;
mod finite;
mod graded;
mod inverse;
mod linkage;
mod measure;
mod mobility;
mod pickle;
mod progress;
mod pull;
mod query;
mod settings;
mod shape;

use pyo3::prelude::*;

#[pymodule]
fn _isogami(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    m.add_class::<design::PyDesign>()?;
    m.add_class::<family::PyFamily>()?;
    m.add_class::<cell::PyCell>()?;
    m.add_class::<mobility::PyAnalysis>()?;
    m.add_class::<mobility::PyMotion>()?;
    m.add_class::<settings::PyDeploySettings>()?;
    m.add_class::<deployment::PyDeployment>()?;
    m.add_class::<linkage::PyLinkages>()?;
    m.add_class::<compare::PyComparison>()?;
    m.add_class::<compare::PyMethodResult>()?;
    m.add_class::<query::PyQuery>()?;
    m.add_class::<database::PyDatabase>()?;
    m.add_class::<database::PyRecord>()?;
    m.add_class::<database::PyStoredDesign>()?;
    m.add_class::<inverse::PyInverseResult>()?;
    m.add_class::<finite::PyFiniteSheet>()?;
    m.add_class::<finite::PySheetDeployment>()?;
    m.add_class::<pull::PySheetPull>()?;
    m.add_class::<graded::PyGradedRun>()?;
    m.add_function(wrap_pyfunction!(pickle::_restore, m)?)?;
    m.add_function(wrap_pyfunction!(pickle::_compute_calls, m)?)?;
    m.add_function(wrap_pyfunction!(design::design, m)?)?;
    m.add_function(wrap_pyfunction!(family::families, m)?)?;
    m.add_function(wrap_pyfunction!(family::family, m)?)?;
    m.add_function(wrap_pyfunction!(cell::cell, m)?)?;
    m.add_function(wrap_pyfunction!(mobility::analyze, m)?)?;
    m.add_function(wrap_pyfunction!(deployment::deploy, m)?)?;
    m.add_function(wrap_pyfunction!(linkage::linkages, m)?)?;
    m.add_function(wrap_pyfunction!(compare::compare, m)?)?;
    m.add_function(wrap_pyfunction!(database::open_database, m)?)?;
    m.add_function(wrap_pyfunction!(export::export, m)?)?;
    m.add_function(wrap_pyfunction!(export::export_formats, m)?)?;
    m.add_function(wrap_pyfunction!(inverse::inverse, m)?)?;
    m.add_function(wrap_pyfunction!(shape::shape_mobility, m)?)?;
    m.add_function(wrap_pyfunction!(shape::follow_shape, m)?)?;
    m.add_function(wrap_pyfunction!(shape::rank_drop_shape, m)?)?;
    m.add_function(wrap_pyfunction!(shape::param_ranges_of, m)?)?;
    m.add_function(wrap_pyfunction!(finite::finite_sheet, m)?)?;
    m.add_function(wrap_pyfunction!(finite::deploy_sheet, m)?)?;
    m.add_function(wrap_pyfunction!(pull::pull_sheet, m)?)?;
    m.add_function(wrap_pyfunction!(graded::graded, m)?)?;
    m.add_function(wrap_pyfunction!(graded::load_graded, m)?)?;
    for f in [
        wrap_pyfunction!(measure::deformation_gradient, m)?,
        wrap_pyfunction!(measure::polar, m)?,
        wrap_pyfunction!(measure::principal_expansions, m)?,
        wrap_pyfunction!(measure::principal_direction, m)?,
        wrap_pyfunction!(measure::directional_expansion, m)?,
        wrap_pyfunction!(measure::expansion_profile, m)?,
        wrap_pyfunction!(measure::area_ratio, m)?,
        wrap_pyfunction!(measure::poisson_ratio, m)?,
    ] {
        m.add_function(f)?;
    }
    m.add("NAMED_DESIGNS", isogami::topology::NAMED_DESIGNS.to_vec())?;
    m.add(
        "SAMPLE_OPENING_DESIGNS",
        isogami::topology::SAMPLE_OPENING_DESIGNS.to_vec(),
    )?;
    m.add(
        "COMPARISON_DESIGNS",
        isogami::deploy::COMPARISON_DESIGNS.to_vec(),
    )?;
    m.add("DEPLOY_SETTINGS", settings::NAMES.to_vec())?;
    Ok(())
}

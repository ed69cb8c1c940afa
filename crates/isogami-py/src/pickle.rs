//! Pickling of results (for `ProcessPoolExecutor`, joblib, dask): a result pickles as the call
//! that made it, `isogami._rebuild(name, args, kwargs)`, and unpickling calls it again. The
//! library's result types (deployments, analyses, finite sheets) hold mechanisms and
//! trajectories that are not serialisable, and the library is deterministic, so the call
//! made again gives an equal result. A part of a result (a sheet of a sheet deployment, a
//! motion of an analysis, one method of a comparison) pickles as its parent's call and the
//! attribute it was read from (`isogami._part`).

use crate::settings::PyDeploySettings;
use isogami::deploy::DeploySettings;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use serde::Serialize;

/// How a result was made: `(name, args, kwargs)` for `isogami._rebuild`.
pub type Recipe = Py<PyTuple>;

/// The recipe `isogami.<name>(*args, **kwargs)`.
pub fn recipe<'py>(
    py: Python<'py>,
    name: &str,
    args: Vec<Bound<'py, PyAny>>,
    kwargs: &[(&str, Bound<'py, PyAny>)],
) -> PyResult<Recipe> {
    let d = PyDict::new(py);
    for (k, v) in kwargs {
        d.set_item(k, v)?;
    }
    let args = PyTuple::new(py, args)?;
    Ok(PyTuple::new(
        py,
        [
            name.into_pyobject(py)?.into_any(),
            args.into_any(),
            d.into_any(),
        ],
    )?
    .unbind())
}

/// The recipe of a part: `getattr(parent, attr)`, then called with or indexed by `key` unless
/// it is None.
pub fn part<'py>(
    py: Python<'py>,
    parent: &Recipe,
    attr: &str,
    key: Bound<'py, PyAny>,
) -> PyResult<Recipe> {
    recipe(
        py,
        "_part",
        vec![
            parent.bind(py).clone().into_any(),
            attr.into_pyobject(py)?.into_any(),
            key,
        ],
        &[],
    )
}

/// `__reduce__`'s value for a recipe.
pub fn reduce<'py>(
    py: Python<'py>,
    recipe: &Recipe,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
    Ok((
        py.import("isogami")?.getattr("_rebuild")?,
        recipe.bind(py).clone(),
    ))
}

/// Deployment settings as the `DeploySettings` object a recipe passes on.
pub fn settings(py: Python<'_>, s: DeploySettings) -> PyResult<Bound<'_, PyAny>> {
    Ok(Bound::new(py, PyDeploySettings { inner: s })?.into_any())
}

/// Equality of two serialisable values through their JSON (the CLI's form).
pub fn same<T: Serialize>(a: &T, b: &T) -> bool {
    match (serde_json::to_value(a), serde_json::to_value(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// A serialisable value's JSON as a Python str.
pub fn json<'py, T: Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| crate::errors::IsogamiError::new_err(format!("JSON output: {e}")))?;
    Ok(text.into_pyobject(py)?.into_any())
}

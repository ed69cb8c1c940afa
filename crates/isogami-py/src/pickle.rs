//! Pickling (for `ProcessPoolExecutor`, joblib, dask): a result pickles as its data, never as
//! the call that made it, so unpickling runs no computation.
//!
//! A computed result (`Deployment`, `Analysis`, `Motion`, `FiniteSheet`, `SheetDeployment`,
//! `SheetPull`, `Linkages`) implements [`Pickled`]: its data as serde JSON (the library types
//! derive it) plus its large float arrays as raw little-endian bytes. `__reduce__` gives
//! `isogami._restore(class, STATE_TAG, json, arrays)`, and [`restore`] reads it back, refusing
//! a state written under another tag with `pickle.UnpicklingError`. Small values (`Design`,
//! `Family`, `Cell`, `DeploySettings`, records, comparisons) pickle as the constructor call
//! that makes them ([`recipe`]), which computes nothing.
//!
//! Every entry point that computes (a [`crate::progress::Watch`], `analyze`, `linkages`)
//! counts itself in [`computing`]; `isogami._isogami._compute_calls()` reads the count, so a
//! test can prove that unpickling computed nothing.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyTuple};
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::sync::atomic::{AtomicU64, Ordering};

/// The tag of the pickled state's layout; a pickle with another tag is refused.
pub const STATE_TAG: &str = "isogami-state-1";

static COMPUTE_CALLS: AtomicU64 = AtomicU64::new(0);

/// Counts one call into the library's computations.
pub fn computing() {
    COMPUTE_CALLS.fetch_add(1, Ordering::Relaxed);
}

/// How many computations this process has started (for tests: unpickling starts none).
#[pyfunction]
pub fn _compute_calls() -> u64 {
    COMPUTE_CALLS.load(Ordering::Relaxed)
}

/// A result that pickles as its data.
pub trait Pickled: Sized {
    /// The class name `_restore` dispatches on.
    const CLASS: &'static str;
    /// The data (serialised as JSON) and the large float arrays (as bytes).
    fn save(&self) -> PyResult<(Vec<u8>, Vec<Vec<f64>>)>;
    /// The result from [`Pickled::save`]'s output.
    fn load(json: &[u8], arrays: Vec<Vec<f64>>) -> PyResult<Self>;
}

/// A serialisable value as JSON bytes.
pub fn to_json<T: Serialize>(value: &T) -> PyResult<Vec<u8>> {
    serde_json::to_vec(value)
        .map_err(|e| crate::errors::IsogamiError::new_err(format!("pickling: {e}")))
}

/// A value from JSON bytes written by [`to_json`]; `UnpicklingError` naming `class` if they
/// do not read.
pub fn from_json<T: DeserializeOwned>(py: Python<'_>, class: &str, json: &[u8]) -> PyResult<T> {
    serde_json::from_slice(json).map_err(|e| unpickling(py, format!("isogami.{class}: {e}")))
}

fn unpickling(py: Python<'_>, message: String) -> PyErr {
    match py
        .import("pickle")
        .and_then(|p| p.getattr("UnpicklingError"))
        .and_then(|c| c.call1((message.clone(),)))
    {
        Ok(e) => PyErr::from_value(e),
        Err(_) => PyValueError::new_err(message),
    }
}

/// `__reduce__`'s value for a [`Pickled`] result.
pub fn reduce_state<'py, T: Pickled>(
    py: Python<'py>,
    value: &T,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
    let (json, arrays) = value.save()?;
    let arrays = PyList::new(
        py,
        arrays.iter().map(|a| {
            let bytes: Vec<u8> = a.iter().flat_map(|v| v.to_le_bytes()).collect();
            PyBytes::new(py, &bytes)
        }),
    )?;
    let args = PyTuple::new(
        py,
        [
            T::CLASS.into_pyobject(py)?.into_any(),
            STATE_TAG.into_pyobject(py)?.into_any(),
            PyBytes::new(py, &json).into_any(),
            arrays.into_any(),
        ],
    )?;
    Ok((py.import("isogami")?.getattr("_restore")?, args))
}

fn load<'py, T>(py: Python<'py>, json: &[u8], arrays: Vec<Vec<f64>>) -> PyResult<Bound<'py, PyAny>>
where
    T: Pickled + pyo3::PyClass + Into<pyo3::PyClassInitializer<T>>,
{
    Ok(Bound::new(py, T::load(json, arrays)?)?.into_any())
}

/// Unpickling (`isogami._restore`): the result of class `class` from its state, without
/// computing anything. Refuses a state written under another tag than [`STATE_TAG`].
#[pyfunction]
pub fn _restore<'py>(
    py: Python<'py>,
    class: &str,
    tag: &str,
    json: &[u8],
    arrays: Vec<Vec<u8>>,
) -> PyResult<Bound<'py, PyAny>> {
    if tag != STATE_TAG {
        return Err(unpickling(
            py,
            format!(
                "isogami.{class} was pickled with state layout {tag:?}; this isogami ({}) reads \
                 {STATE_TAG:?}: compute it again with this version",
                env!("CARGO_PKG_VERSION")
            ),
        ));
    }
    let mut floats = Vec::with_capacity(arrays.len());
    for a in &arrays {
        if a.len() % 8 != 0 {
            return Err(unpickling(
                py,
                format!("isogami.{class}: an array of {} bytes", a.len()),
            ));
        }
        floats.push(
            a.chunks_exact(8)
                .map(|b| f64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
                .collect(),
        );
    }
    use crate::{deployment, finite, linkage, mobility, pull, query};
    match class {
        deployment::PyDeployment::CLASS => load::<deployment::PyDeployment>(py, json, floats),
        mobility::PyAnalysis::CLASS => load::<mobility::PyAnalysis>(py, json, floats),
        mobility::PyMotion::CLASS => load::<mobility::PyMotion>(py, json, floats),
        finite::PyFiniteSheet::CLASS => load::<finite::PyFiniteSheet>(py, json, floats),
        finite::PySheetDeployment::CLASS => load::<finite::PySheetDeployment>(py, json, floats),
        pull::PySheetPull::CLASS => load::<pull::PySheetPull>(py, json, floats),
        linkage::PyLinkages::CLASS => load::<linkage::PyLinkages>(py, json, floats),
        query::PyQuery::CLASS => load::<query::PyQuery>(py, json, floats),
        _ => Err(unpickling(
            py,
            format!("no isogami class {class:?} to unpickle"),
        )),
    }
}

/// A constructor call `isogami.<name>(*args, **kwargs)` for `isogami._rebuild`.
pub type Recipe = Py<PyTuple>;

/// The recipe `isogami.<name>(*args, **kwargs)` (values only: the call must compute nothing).
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

/// [`Pickled`] for a class whose data is one serde value in its `inner` field: pickled as
/// that value's JSON, without separate arrays.
#[macro_export]
macro_rules! pickled_inner {
    ($ty:ty, $class:literal) => {
        impl $crate::pickle::Pickled for $ty {
            const CLASS: &'static str = $class;
            fn save(&self) -> PyResult<(Vec<u8>, Vec<Vec<f64>>)> {
                Ok(($crate::pickle::to_json(&self.inner)?, Vec::new()))
            }
            fn load(json: &[u8], _arrays: Vec<Vec<f64>>) -> PyResult<Self> {
                let inner = Python::attach(|py| $crate::pickle::from_json(py, $class, json))?;
                Ok(Self { inner })
            }
        }
    };
}

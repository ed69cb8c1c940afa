//! Conversions at the Python boundary: library JSON to Python objects, numbers checked finite,
//! designs accepted as objects or text, small numpy helpers.

use crate::design::PyDesign;
use crate::errors;
use isogami::api::{resolve_design, Design};
use numpy::ndarray::{Array, Dimension, IntoDimension};
use numpy::PyArray;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use serde::Serialize;

/// A serialisable library value as the Python object `json.loads` makes of the JSON the CLI
/// prints for it (dicts, lists, floats that round-trip exactly).
pub fn to_python<'py, T: Serialize + ?Sized>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| errors::IsogamiError::new_err(format!("JSON output: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The design a Python argument names: an `isogami.Design`, or a str holding a name, a spec
/// string or design JSON (read and checked by the library).
pub fn design_of(obj: &Bound<'_, PyAny>) -> PyResult<Design> {
    if let Ok(d) = obj.cast::<PyDesign>() {
        return Ok(d.get().inner.clone());
    }
    if let Ok(text) = obj.extract::<String>() {
        return resolve_design(&text).map_err(errors::library);
    }
    Err(PyTypeError::new_err(format!(
        "design must be an isogami.Design or a str (a name, a spec string or design JSON), got {}",
        type_name(obj)
    )))
}

/// The type name of a Python object, for messages.
pub fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "?".into())
}

/// `value` if finite, else a `ValueError` naming `what`.
pub fn finite(what: &str, value: f64) -> PyResult<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(PyValueError::new_err(format!(
            "{what} is {value}: must be a finite number"
        )))
    }
}

/// A 2×2 matrix given as rows, every entry finite.
pub fn matrix(what: &str, rows: [[f64; 2]; 2]) -> PyResult<isogami::math::Mat2> {
    for v in rows.iter().flatten() {
        finite(what, *v)?;
    }
    Ok(isogami::math::Mat2::new(
        rows[0][0], rows[0][1], rows[1][0], rows[1][1],
    ))
}

/// A matrix as rows.
pub fn rows(m: &isogami::math::Mat2) -> [[f64; 2]; 2] {
    [[m[(0, 0)], m[(0, 1)]], [m[(1, 0)], m[(1, 1)]]]
}

/// A numpy array of `shape` from values in row-major order.
pub fn array<'py, D: Dimension, S: IntoDimension<Dim = D>>(
    py: Python<'py>,
    shape: S,
    values: Vec<f64>,
) -> PyResult<Bound<'py, PyArray<f64, D>>> {
    let a = Array::from_shape_vec(shape, values)
        .map_err(|e| errors::IsogamiError::new_err(format!("array shape: {e}")))?;
    Ok(PyArray::from_owned_array(py, a))
}

/// A numpy int64 array of `shape` from values in row-major order.
pub fn int_array<'py, D: Dimension, S: IntoDimension<Dim = D>>(
    py: Python<'py>,
    shape: S,
    values: Vec<i64>,
) -> PyResult<Bound<'py, PyArray<i64, D>>> {
    let a = Array::from_shape_vec(shape, values)
        .map_err(|e| errors::IsogamiError::new_err(format!("array shape: {e}")))?;
    Ok(PyArray::from_owned_array(py, a))
}

/// A point as a numpy array of shape (2,).
pub fn point<'py>(py: Python<'py>, p: [f64; 2]) -> Bound<'py, numpy::PyArray1<f64>> {
    numpy::PyArray1::from_slice(py, &p)
}

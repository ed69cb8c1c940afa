//! Conversions at the Python boundary: library JSON to Python objects, numbers checked finite,
//! designs accepted as objects or text, small numpy helpers.

use crate::design::PyDesign;
use crate::errors;
use isogami::api::{resolve_design, Design};
use numpy::ndarray::{Array, Dimension, IntoDimension};
use numpy::{PyArray, PyArrayMethods};
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
    // A database record or a design read back whole: its spec.
    if let Ok(r) = obj.cast::<crate::database::PyRecord>() {
        return resolve_design(r.get().spec()).map_err(errors::library);
    }
    if let Ok(s) = obj.cast::<crate::database::PyStoredDesign>() {
        return resolve_design(s.get().spec()).map_err(errors::library);
    }
    Err(PyTypeError::new_err(format!(
        "design must be an isogami.Design, a Record, a StoredDesign or a str (a name, a spec string or design JSON), got {}",
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

/// The Python int behind an integer argument: an int or anything with `__index__` (numpy's
/// integer scalars, 0-d integer arrays), never a bool; None for anything else.
pub fn index_of<'py>(obj: &Bound<'py, PyAny>) -> Option<Bound<'py, pyo3::types::PyInt>> {
    if obj.is_instance_of::<pyo3::types::PyBool>() {
        return None;
    }
    if let Ok(i) = obj.cast::<pyo3::types::PyInt>() {
        return Some(i.clone());
    }
    let index = obj.py().import("operator").ok()?.getattr("index").ok()?;
    let i = index.call1((obj,)).ok()?;
    i.cast_into::<pyo3::types::PyInt>().ok()
}

/// An integer argument in `low..=high`: a `TypeError` naming `what` for a non-integer, a
/// `ValueError` naming it and showing the value as given (never wrapped) out of range.
pub fn int_in(what: &str, obj: &Bound<'_, PyAny>, low: i64, high: i64) -> PyResult<i64> {
    let i = index_of(obj).ok_or_else(|| {
        PyTypeError::new_err(format!("{what} must be an int, got {}", type_name(obj)))
    })?;
    match i.extract::<i64>() {
        Ok(v) if (low..=high).contains(&v) => Ok(v),
        _ => {
            let shown = i.repr().map(|r| r.to_string()).unwrap_or_default();
            let range = if high == i64::MAX {
                format!("a non-negative int (at least {low})")
            } else {
                format!("an int in {low}..={high}")
            };
            Err(PyValueError::new_err(format!(
                "{what} must be {range}, got {shown}"
            )))
        }
    }
}

/// A count argument (an int >= `low`), with `default` when it is None or not given.
pub fn count_or(
    what: &str,
    obj: Option<&Bound<'_, PyAny>>,
    low: usize,
    default: usize,
) -> PyResult<usize> {
    match obj {
        Some(o) if !o.is_none() => int_in(what, o, low as i64, i64::MAX).map(|v| v as usize),
        _ => Ok(default),
    }
}

/// 2×2 matrices from one matrix (nested sequences or an array of shape (2, 2)) or a stack of
/// them (an array of shape (..., 2, 2), such as ``Deployment.F``): the leading shape (None
/// for one matrix) and the matrices in row-major order, every entry finite.
#[allow(clippy::type_complexity)]
pub fn matrices(
    what: &str,
    obj: &Bound<'_, PyAny>,
) -> PyResult<(Option<Vec<usize>>, Vec<isogami::math::Mat2>)> {
    let py = obj.py();
    if obj.is_none() {
        return Err(PyTypeError::new_err(format!(
            "{what} must be a 2x2 matrix or a stack of them (shape (..., 2, 2)), got None"
        )));
    }
    let np = py.import("numpy")?;
    let bad = |detail: String| {
        PyValueError::new_err(format!(
            "{what} must be a 2x2 matrix or a stack of them (shape (..., 2, 2)), {detail}"
        ))
    };
    let a = np
        .call_method1("asarray", (obj,))
        .and_then(|a| a.call_method1("astype", ("float64",)))
        .map_err(|_| bad(format!("got {}", type_name(obj))))?;
    let a = a
        .cast_into::<numpy::PyArrayDyn<f64>>()
        .map_err(|_| bad("got something else".into()))?;
    let ro = a.readonly();
    let view = ro.as_array();
    let shape = view.shape().to_vec();
    if shape.len() < 2 || shape[shape.len() - 2..] != [2, 2] {
        return Err(bad(format!("got shape {shape:?}")));
    }
    let values: Vec<f64> = view.iter().copied().collect();
    let mut out = Vec::with_capacity(values.len() / 4);
    for m in values.chunks_exact(4) {
        out.push(matrix(what, [[m[0], m[1]], [m[2], m[3]]])?);
    }
    let lead = shape[..shape.len() - 2].to_vec();
    Ok(((!lead.is_empty()).then_some(lead), out))
}

/// The two integers of a pair argument — a tuple, a list, a numpy array or any other
/// iterable of exactly two integers (ints, numpy integer scalars, 0-d integer arrays; never
/// a bool or a float) — as Python ints, values as given (range checks are the caller's).
/// None for anything else (a str is not a pair: callers read "AxB" first).
pub fn int_pair<'py>(obj: &Bound<'py, PyAny>) -> Option<[Bound<'py, pyo3::types::PyInt>; 2]> {
    if obj.is_instance_of::<pyo3::types::PyString>() || obj.is_instance_of::<pyo3::types::PyBytes>()
    {
        return None;
    }
    let items: Vec<Bound<'py, PyAny>> = obj.try_iter().ok()?.collect::<PyResult<_>>().ok()?;
    match &items[..] {
        [a, b] => Some([index_of(a)?, index_of(b)?]),
        _ => None,
    }
}

/// A pair argument of non-negative sizes (see [`int_pair`]); `Err(shown)` for a pair out of
/// `usize`, with the values as given; None when it is no pair of ints.
pub fn size_pair(obj: &Bound<'_, PyAny>) -> Option<Result<(usize, usize), String>> {
    let [a, b] = int_pair(obj)?;
    let size = |v: &Bound<'_, pyo3::types::PyInt>| {
        v.extract::<i64>()
            .ok()
            .and_then(|n| usize::try_from(n).ok())
    };
    Some(match (size(&a), size(&b)) {
        (Some(x), Some(y)) => Ok((x, y)),
        _ => Err(format!("({a}, {b})")),
    })
}

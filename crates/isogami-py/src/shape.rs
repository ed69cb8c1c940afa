//! Shape-aware mobility from Python (the library's `shape_space`): whether a design's one
//! degree of freedom survives shape changes, its shape constraints, moving a parameter along
//! them, the rank-drop search of a rigid design's shapes, and each parameter's valid range.

use crate::convert::{design_of, to_python};
use crate::design::PyDesign;
use crate::errors;
use isogami::shape_space::{classify, follow, param_ranges, rank_drop, ShapeError, ShapeSettings};
use pyo3::prelude::*;

fn shape_error(e: ShapeError) -> PyErr {
    errors::ShapeError::new_err(e.to_string())
}

/// Whether a design's one degree of freedom survives shape changes: a dict with ``class``
/// (``"generic"``, ``"special"`` or ``"fixed_shape"``), ``samples`` and ``samples_one_dof``
/// (nearby shapes tried, and how many kept one DOF), ``self_stresses``, ``constraints`` (unit
/// normals n in parameter space: a shape change δp keeps one DOF to first order when
/// n·δp = 0) and ``pinned`` (parameters no tangent direction moves). ShapeError when the
/// design does not have one DOF.
#[pyfunction]
pub fn shape_mobility<'py>(
    py: Python<'py>,
    design: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let d = design_of(design)?;
    let m = py
        .detach(|| classify(&d, &ShapeSettings::default()))
        .map_err(shape_error)?;
    to_python(py, &m)
}

/// The design with shape parameter ``index`` moved to ``value`` and the others adjusted so
/// that it keeps one degree of freedom (a generic design just takes the value). ShapeError
/// when the parameter is pinned, the path leaves the well-shaped tiles or loses the motion.
#[pyfunction]
pub fn follow_shape(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    index: &Bound<'_, PyAny>,
    value: f64,
) -> PyResult<PyDesign> {
    let index = crate::convert::int_in("index", index, 0, i64::MAX)? as usize;
    let d = design_of(design)?;
    let moved = py
        .detach(|| follow(&d, index, value, &ShapeSettings::default()))
        .map_err(shape_error)?;
    Ok(PyDesign {
        inner: moved.design,
    })
}

/// A shape of the design's family and topology with exactly one degree of freedom, searched
/// within the exploration's sampling box (for a design rigid at its own shape); None when
/// none is found.
#[pyfunction]
pub fn rank_drop_shape(py: Python<'_>, design: &Bound<'_, PyAny>) -> PyResult<Option<PyDesign>> {
    let d = design_of(design)?;
    let found = py
        .detach(|| rank_drop(&d, &ShapeSettings::default()))
        .map_err(shape_error)?;
    Ok(found.map(|r| PyDesign { inner: r.design }))
}

/// The valid range of each shape parameter of the design, the others fixed: a list of dicts
/// with ``index``, ``value``, ``lo``, ``hi`` (the interval around the value where the design
/// builds and its tiles inset by half of ``kerf``, in units of the mean edge length),
/// ``lo_open`` / ``hi_open`` (the end is the searched window's edge, value ± 2 scales),
/// ``well_shaped`` (``(lo, hi)`` where the tile also passes the exploration's shape-quality
/// rule, or None) and ``tol`` (the bisection tolerance). None when the design does not build
/// at that kerf.
#[pyfunction]
#[pyo3(signature = (design, kerf=0.01))]
pub fn param_ranges_of<'py>(
    py: Python<'py>,
    design: &Bound<'py, PyAny>,
    kerf: f64,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let d = design_of(design)?;
    if !kerf.is_finite() || kerf <= 0.0 {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "kerf {kerf} must be a positive finite number"
        )));
    }
    match py.detach(|| param_ranges(&d, kerf)) {
        Some(r) => Ok(Some(to_python(py, &r)?)),
        None => Ok(None),
    }
}

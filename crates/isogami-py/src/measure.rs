//! The library's expansion measures as functions of numbers (paper §4.3): deformation
//! gradient, polar decomposition, principal and directional expansions, area ratio, Poisson
//! ratio. Matrices are 2×2, given and returned as rows (nested sequences or numpy arrays).

use crate::convert::{array, finite, matrices, matrix, rows};
use crate::errors;
use isogami::math::Vec2;
use isogami::measure;
use numpy::PyArray2;
use pyo3::prelude::*;

fn vector(what: &str, v: [f64; 2]) -> PyResult<Vec2> {
    Ok(Vec2::new(finite(what, v[0])?, finite(what, v[1])?))
}

fn matrix_array<'py>(py: Python<'py>, m: [[f64; 2]; 2]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    array(py, (2, 2), m.into_iter().flatten().collect())
}

/// The deformation gradient F with [u w] = F [u0 w0] (paper eq. 10), from the closed tiling
/// vectors ``u0``, ``w0`` and the current ones ``u``, ``w``. Raises ``MeasureError`` when u0
/// and w0 are (nearly) parallel, ``ValueError`` for a non-finite input.
#[pyfunction]
pub fn deformation_gradient<'py>(
    py: Python<'py>,
    u0: [f64; 2],
    w0: [f64; 2],
    u: [f64; 2],
    w: [f64; 2],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let f = measure::deformation_gradient(
        &vector("u0", u0)?,
        &vector("w0", w0)?,
        &vector("u", u)?,
        &vector("w", w)?,
    )
    .map_err(|e| errors::library(e.into()))?;
    matrix_array(py, rows(&f))
}

/// Per-matrix values over one matrix or a stack: a scalar for one matrix, an array of the
/// stack's leading shape (plus `extra`) for a stack.
fn over<'py>(
    py: Python<'py>,
    what: &str,
    obj: &Bound<'py, PyAny>,
    extra: &[usize],
    f: impl Fn(&isogami::math::Mat2) -> PyResult<Vec<f64>>,
) -> PyResult<Bound<'py, PyAny>> {
    let (lead, ms) = matrices(what, obj)?;
    let mut values = Vec::new();
    for m in &ms {
        values.extend(f(m)?);
    }
    match lead {
        None if extra.is_empty() => Ok(values[0].into_pyobject(py)?.into_any()),
        None => Ok(array(py, extra.to_vec(), values)?.into_any()),
        Some(mut shape) => {
            shape.extend_from_slice(extra);
            Ok(array(py, shape, values)?.into_any())
        }
    }
}

/// The polar decomposition F = RU: returns ``(R, U)``, R a rotation and U symmetric positive
/// definite. ``F`` may be a stack of shape (..., 2, 2) (``Deployment.F``); then R and U are
/// stacks of that shape. Raises ``MeasureError`` when det F <= 0.
#[pyfunction]
pub fn polar<'py>(
    py: Python<'py>,
    f: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (lead, ms) = matrices("F", f)?;
    let (mut r, mut u) = (Vec::new(), Vec::new());
    for m in &ms {
        let (a, b) = measure::polar(m).map_err(|e| errors::library(e.into()))?;
        r.extend(rows(&a).into_iter().flatten());
        u.extend(rows(&b).into_iter().flatten());
    }
    let mut shape = lead.unwrap_or_default();
    shape.extend([2, 2]);
    Ok((
        array(py, shape.clone(), r)?.into_any(),
        array(py, shape, u)?.into_any(),
    ))
}

/// The principal expansions ``(min, max)`` of a stretch tensor U: the eigenvalues of U − I.
/// For a stack of shape (..., 2, 2), an array of shape (..., 2).
#[pyfunction]
pub fn principal_expansions<'py>(
    py: Python<'py>,
    u: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    if matrices("U", u)?.0.is_none() {
        let m = matrices("U", u)?.1[0];
        return Ok(measure::principal_expansions(&m)
            .into_pyobject(py)?
            .into_any());
    }
    over(py, "U", u, &[2], |m| {
        let (a, b) = measure::principal_expansions(m);
        Ok(vec![a, b])
    })
}

/// The direction of the largest expansion of U, an angle in (−π/2, π/2] (0 when U is
/// isotropic). For a stack of shape (..., 2, 2), an array of shape (...).
#[pyfunction]
pub fn principal_direction<'py>(
    py: Python<'py>,
    u: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    over(py, "U", u, &[], |m| {
        Ok(vec![measure::principal_direction(m)])
    })
}

/// The directional expansion ε(θ) = dᵀ(U − I)d with d = (cos θ, sin θ). For a stack of
/// shape (..., 2, 2), an array of shape (...).
#[pyfunction]
pub fn directional_expansion<'py>(
    py: Python<'py>,
    u: &Bound<'py, PyAny>,
    theta: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let theta = finite("theta", theta)?;
    over(py, "U", u, &[], |m| {
        Ok(vec![measure::directional_expansion(m, theta)])
    })
}

/// The polar profile of U: an array of shape (samples, 2) of (θ_k, ε(θ_k)), θ_k = 2πk/samples.
#[pyfunction]
#[pyo3(signature = (u, samples=None), text_signature = "(u, samples=180)")]
pub fn expansion_profile<'py>(
    py: Python<'py>,
    u: [[f64; 2]; 2],
    samples: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let samples = crate::convert::count_or("samples", samples, 0, 180)?;
    if !(3..=100_000).contains(&samples) {
        return Err(errors::SettingsError::new_err(format!(
            "invalid setting: samples {samples} must lie in 3..=100000"
        )));
    }
    let p = measure::expansion_profile(&matrix("U", u)?, samples);
    array(
        py,
        (p.len(), 2),
        p.into_iter().flat_map(|(a, e)| [a, e]).collect(),
    )
}

/// The area ratio det F of the deployed to the closed cell. For a stack of shape
/// (..., 2, 2) (``Deployment.F``), an array of shape (...).
#[pyfunction]
pub fn area_ratio<'py>(py: Python<'py>, f: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    over(py, "F", f, &[], |m| Ok(vec![measure::area_ratio(m)]))
}

/// The effective Poisson ratio −ε_min/ε_max of one frame (−1 for isotropic expansion,
/// positive when one direction shrinks while the other grows); None when ε_max is within
/// 1e-9 of zero or an input is not finite.
#[pyfunction]
pub fn poisson_ratio(min_expansion: f64, max_expansion: f64) -> Option<f64> {
    measure::effective_poisson_ratio(min_expansion, max_expansion)
}

//! The library's expansion measures as functions of numbers (paper §4.3): deformation
//! gradient, polar decomposition, principal and directional expansions, area ratio, Poisson
//! ratio. Matrices are 2×2, given and returned as rows (nested sequences or numpy arrays).

use crate::convert::{array, finite, matrix, rows};
use crate::errors;
use isogami::math::Vec2;
use isogami::measure;
use numpy::PyArray2;
use pyo3::prelude::*;

fn vector(what: &str, v: [f64; 2]) -> PyResult<Vec2> {
    Ok(Vec2::new(finite(what, v[0])?, finite(what, v[1])?))
}

/// A 2×2 numpy array.
type Matrix<'py> = Bound<'py, PyArray2<f64>>;

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

/// The polar decomposition F = RU: returns ``(R, U)``, R a rotation and U symmetric positive
/// definite. Raises ``MeasureError`` when det F <= 0.
#[pyfunction]
pub fn polar<'py>(py: Python<'py>, f: [[f64; 2]; 2]) -> PyResult<(Matrix<'py>, Matrix<'py>)> {
    let (r, u) = measure::polar(&matrix("F", f)?).map_err(|e| errors::library(e.into()))?;
    Ok((matrix_array(py, rows(&r))?, matrix_array(py, rows(&u))?))
}

/// The principal expansions ``(min, max)`` of a stretch tensor U: the eigenvalues of U − I.
#[pyfunction]
pub fn principal_expansions(u: [[f64; 2]; 2]) -> PyResult<(f64, f64)> {
    Ok(measure::principal_expansions(&matrix("U", u)?))
}

/// The direction of the largest expansion of U, an angle in (−π/2, π/2] (0 when U is
/// isotropic).
#[pyfunction]
pub fn principal_direction(u: [[f64; 2]; 2]) -> PyResult<f64> {
    Ok(measure::principal_direction(&matrix("U", u)?))
}

/// The directional expansion ε(θ) = dᵀ(U − I)d with d = (cos θ, sin θ).
#[pyfunction]
pub fn directional_expansion(u: [[f64; 2]; 2], theta: f64) -> PyResult<f64> {
    Ok(measure::directional_expansion(
        &matrix("U", u)?,
        finite("theta", theta)?,
    ))
}

/// The polar profile of U: an array of shape (samples, 2) of (θ_k, ε(θ_k)), θ_k = 2πk/samples.
#[pyfunction]
#[pyo3(signature = (u, samples=180))]
pub fn expansion_profile<'py>(
    py: Python<'py>,
    u: [[f64; 2]; 2],
    samples: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
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

/// The area ratio det F of the deployed to the closed cell.
#[pyfunction]
pub fn area_ratio(f: [[f64; 2]; 2]) -> PyResult<f64> {
    Ok(measure::area_ratio(&matrix("F", f)?))
}

/// The effective Poisson ratio −ε_min/ε_max of one frame (−1 for isotropic expansion,
/// positive when one direction shrinks while the other grows); None when ε_max is within
/// 1e-9 of zero or an input is not finite.
#[pyfunction]
pub fn poisson_ratio(min_expansion: f64, max_expansion: f64) -> Option<f64> {
    measure::effective_poisson_ratio(min_expansion, max_expansion)
}

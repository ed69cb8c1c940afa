//! `isogami.Family`: the 81 isohedral tiling families with their parameters, parameter
//! ranges, prototiles and shape samples.

use crate::convert::{array, to_python};
use crate::errors;
use isogami::catalog::CatalogSettings;
use isogami::tiling::{param_ranges, shape_grid, Family, Tiling};
use numpy::PyArray2;
use pyo3::prelude::*;

/// One of the 81 realizable isohedral tiling families IH1…IH93 (Kaplan's numbering).
///
/// Get them with ``isogami.families()`` or ``isogami.family("IH28")``.
#[pyclass(name = "Family", module = "isogami", frozen)]
pub struct PyFamily {
    pub inner: Family,
}

/// The exploration's default sampling span.
fn default_span() -> f64 {
    CatalogSettings::default().shape_span
}

#[pymethods]
impl PyFamily {
    /// The family's name, e.g. ``"IH28"``.
    #[getter]
    fn name(&self) -> String {
        self.inner.name()
    }

    /// Kaplan's number, e.g. 28.
    #[getter]
    fn number(&self) -> u8 {
        self.inner.number()
    }

    /// Number of shape parameters v0…v5.
    #[getter]
    fn param_count(&self) -> usize {
        self.inner.param_count()
    }

    /// Kaplan's default shape parameters.
    #[getter]
    fn default_params(&self) -> Vec<f64> {
        self.inner.default_params()
    }

    /// Number of prototile vertices (tiling vertices).
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.info().vertex_count
    }

    /// Tiles (aspects) in the minimal translational cell.
    #[getter]
    fn aspect_count(&self) -> usize {
        self.inner.info().aspect_count
    }

    /// The shape class of every prototile edge: dicts with ``kind`` (``"J"``, ``"U"``,
    /// ``"S"`` or ``"I"``), ``shape_id`` and ``reversed``.
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.info().edges)
    }

    /// The range each shape parameter is sampled over by the exploration: an array of shape
    /// (param_count, 2) of (low, high) = default ± span·max(|default|, 0.25). ``span``
    /// defaults to the exploration's (0.3). Not every point of the box gives a valid tile:
    /// ``check_params`` says which do.
    #[pyo3(signature = (span=None))]
    fn param_ranges<'py>(
        &self,
        py: Python<'py>,
        span: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let span = positive_span(span)?;
        let ranges = param_ranges(self.inner, span);
        let n = ranges.len();
        array(
            py,
            (n, 2),
            ranges.into_iter().flat_map(|(a, b)| [a, b]).collect(),
        )
    }

    /// The prototile's vertices (counter-clockwise) at ``params`` (default: the defaults), as
    /// an array of shape (vertex_count, 2). Raises ``TilingError`` for parameters that give no
    /// valid tile, naming the culprit parameter.
    #[pyo3(signature = (params=None))]
    fn prototile<'py>(
        &self,
        py: Python<'py>,
        params: Option<Vec<f64>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let tiling = self.tiling(params)?;
        let p = tiling.prototile();
        array(
            py,
            (p.len(), 2),
            p.iter().flat_map(|v| [v.x, v.y]).collect(),
        )
    }

    /// Checks shape parameters: returns None when they give a valid tiling, raises
    /// ``TilingError`` (naming the parameter and the problem) when not.
    fn check_params(&self, params: Vec<f64>) -> PyResult<()> {
        self.tiling(Some(params)).map(|_| ())
    }

    /// Well-shaped parameter vectors on the exploration's grid: ``levels`` values per
    /// parameter (2..16) over ``param_ranges(span)``, at most ``max_samples`` vectors
    /// (1..10000), the defaults first. Raises ``SettingsError`` outside those ranges.
    #[pyo3(signature = (levels=3, span=None, max_samples=12))]
    fn sample_params(
        &self,
        levels: usize,
        span: Option<f64>,
        max_samples: usize,
    ) -> PyResult<Vec<Vec<f64>>> {
        let s = sampling(levels, span, max_samples)?;
        Ok(shape_grid(self.inner, levels, s.shape_span, max_samples))
    }

    /// The family's facts as ``isogami families --json`` lists them.
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.info())
    }

    /// Pickles as ``isogami.family(name)`` (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let r = crate::pickle::recipe(
            py,
            "family",
            vec![self.inner.name().into_pyobject(py)?.into_any()],
            &[],
        )?;
        crate::pickle::reduce(py, &r)
    }

    fn __repr__(&self) -> String {
        format!(
            "isogami.Family('{}', params={:?})",
            self.inner.name(),
            self.inner.default_params()
        )
    }

    fn __str__(&self) -> String {
        self.inner.name()
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyFamily>()
            .is_ok_and(|o| o.get().inner == self.inner)
    }

    fn __hash__(&self) -> u64 {
        u64::from(self.inner.number())
    }
}

impl PyFamily {
    fn tiling(&self, params: Option<Vec<f64>>) -> PyResult<Tiling> {
        let params = params.unwrap_or_else(|| self.inner.default_params());
        Tiling::new(self.inner, &params).map_err(|e| errors::library(e.into()))
    }
}

/// Sampling settings checked by the exploration's own rules (span in (0, 2], levels in
/// 2..=16, samples in 1..=10000).
fn sampling(levels: usize, span: Option<f64>, samples: usize) -> PyResult<CatalogSettings> {
    let settings = CatalogSettings {
        samples,
        shape_levels: levels,
        shape_span: span.unwrap_or_else(default_span),
        ..CatalogSettings::default()
    };
    settings.validate().map_err(|e| errors::library(e.into()))?;
    Ok(settings)
}

/// A sampling span checked as the exploration checks it.
fn positive_span(span: Option<f64>) -> PyResult<f64> {
    let d = CatalogSettings::default();
    Ok(sampling(d.shape_levels, span, d.samples)?.shape_span)
}

/// All 81 families in Kaplan's order.
#[pyfunction]
pub fn families() -> Vec<PyFamily> {
    Family::all().map(|inner| PyFamily { inner }).collect()
}

/// The family named ``name`` (``"IH28"``, ``"ih28"``, ``"28"``) or numbered ``name`` (an
/// int). Raises ``TilingError`` for a family that is not one of the 81.
#[pyfunction]
pub fn family(name: &Bound<'_, PyAny>) -> PyResult<PyFamily> {
    crate::design::family_of(name).map(|inner| PyFamily { inner })
}

//! `isogami.compare`: rigid modes, NCM and springs on the same design (paper §5, Fig. 4),
//! each summarised by how far it got along the rigid-modes path and how much it opened.

use crate::convert::{design_of, to_python};
use crate::deployment::settings_of;
use crate::progress::Watch;
use isogami::api::compare_with;
use isogami::deploy::{DesignComparison, MethodResult};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A method result read back from its JSON (the library's type serialises only; for
/// unpickling, every field as it serialises).
#[derive(serde::Deserialize)]
struct MethodResultState {
    method: isogami::deploy::Method,
    final_t: f64,
    path_distance: f64,
    max_area_ratio: f64,
    max_area_t: f64,
    final_area_ratio: f64,
    max_expansion: f64,
    min_expansion: f64,
    max_tile_rotation: f64,
    reached_peak_area: bool,
    end_reason: isogami::deploy::EndReason,
    steps: usize,
    attempts: usize,
    millis: f64,
}

impl From<MethodResultState> for MethodResult {
    fn from(s: MethodResultState) -> MethodResult {
        MethodResult {
            method: s.method,
            final_t: s.final_t,
            path_distance: s.path_distance,
            max_area_ratio: s.max_area_ratio,
            max_area_t: s.max_area_t,
            final_area_ratio: s.final_area_ratio,
            max_expansion: s.max_expansion,
            min_expansion: s.min_expansion,
            max_tile_rotation: s.max_tile_rotation,
            reached_peak_area: s.reached_peak_area,
            end_reason: s.end_reason,
            steps: s.steps,
            attempts: s.attempts,
            millis: s.millis,
        }
    }
}

/// A comparison read back from its JSON.
#[derive(serde::Deserialize)]
struct ComparisonState {
    design: String,
    dof: usize,
    results: Vec<MethodResultState>,
}

fn bad_json(e: serde_json::Error) -> PyErr {
    PyValueError::new_err(format!("text: not a comparison's JSON: {e}"))
}

/// One method's result in a comparison (lengths in units of L, angles in radians).
#[pyclass(name = "MethodResult", module = "isogami", frozen)]
pub struct PyMethodResult {
    inner: MethodResult,
}

#[pymethods]
impl PyMethodResult {
    /// ``"rigid-modes"``, ``"ncm"`` or ``"springs"``.
    #[getter]
    fn method(&self) -> String {
        self.inner.method.to_string()
    }
    /// t of the last state along the rigid-modes path (1 = its contact limit).
    #[getter]
    fn final_t(&self) -> f64 {
        self.inner.final_t
    }
    /// State-space distance of the last state from the rigid-modes path.
    #[getter]
    fn path_distance(&self) -> f64 {
        self.inner.path_distance
    }
    /// Largest area ratio over the method's states.
    #[getter]
    fn max_area_ratio(&self) -> f64 {
        self.inner.max_area_ratio
    }
    /// t along the rigid-modes path where that largest area was reached.
    #[getter]
    fn max_area_t(&self) -> f64 {
        self.inner.max_area_t
    }
    /// Area ratio of the last state.
    #[getter]
    fn final_area_ratio(&self) -> f64 {
        self.inner.final_area_ratio
    }
    /// Largest principal expansion.
    #[getter]
    fn max_expansion(&self) -> f64 {
        self.inner.max_expansion
    }
    /// Smallest principal expansion.
    #[getter]
    fn min_expansion(&self) -> f64 {
        self.inner.min_expansion
    }
    /// Largest tile rotation (radians).
    #[getter]
    fn max_tile_rotation(&self) -> f64 {
        self.inner.max_tile_rotation
    }
    /// Whether the rigid-modes path's largest area was reached (within 1 % of the opening).
    #[getter]
    fn reached_peak_area(&self) -> bool {
        self.inner.reached_peak_area
    }
    /// Why the method stopped (the ``kind`` of the end reason).
    #[getter]
    fn end_reason(&self, py: Python<'_>) -> PyResult<String> {
        to_python(py, &self.inner.end_reason)?
            .get_item("kind")?
            .extract()
    }
    /// Accepted states.
    #[getter]
    fn steps(&self) -> usize {
        self.inner.steps
    }
    /// Attempted steps.
    #[getter]
    fn attempts(&self) -> usize {
        self.inner.attempts
    }
    /// Wall time in milliseconds.
    #[getter]
    fn millis(&self) -> f64 {
        self.inner.millis
    }
    /// The result as ``isogami compare --json`` prints it.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner)
    }
    /// Pickles as its fields exactly (``MethodResult._from_json``) (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let r = crate::pickle::recipe(
            py,
            "MethodResult._from_json",
            vec![crate::pickle::json(py, &self.inner)?],
            &[],
        )?;
        crate::pickle::reduce(py, &r)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Self>().is_ok_and(|o| {
            let o = o.get();
            crate::pickle::same(&o.inner, &self.inner)
        })
    }

    /// A method result from its JSON (for unpickling).
    #[staticmethod]
    fn _from_json(text: &str) -> PyResult<PyMethodResult> {
        let s: MethodResultState = serde_json::from_str(text).map_err(bad_json)?;
        Ok(PyMethodResult { inner: s.into() })
    }

    fn __repr__(&self) -> String {
        format!(
            "isogami.MethodResult({}: t {:.3}, area up to {:.4}, {})",
            self.inner.method, self.inner.final_t, self.inner.max_area_ratio, self.inner.end_reason
        )
    }
}

/// The comparison of the three methods on one design.
#[pyclass(name = "Comparison", module = "isogami", frozen)]
pub struct PyComparison {
    inner: DesignComparison,
}

#[pymethods]
impl PyComparison {
    /// The design's spec string.
    #[getter]
    fn design(&self) -> String {
        self.inner.design.clone()
    }
    /// Degrees of freedom of the closed sheet.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof
    }
    /// One result per method: rigid modes, NCM, springs.
    #[getter]
    fn results(&self) -> Vec<PyMethodResult> {
        self.inner
            .results
            .iter()
            .cloned()
            .map(|inner| PyMethodResult { inner })
            .collect()
    }
    /// The result of one method by name.
    fn result(&self, method: &str) -> PyResult<PyMethodResult> {
        self.inner
            .results
            .iter()
            .find(|r| r.method.to_string() == method)
            .cloned()
            .map(|inner| PyMethodResult { inner })
            .ok_or_else(|| {
                crate::errors::SettingsError::new_err(format!(
                    "invalid setting: method '{}' must be one of rigid-modes, ncm, springs",
                    method.escape_debug()
                ))
            })
    }
    /// The comparison as one element of ``isogami compare --json``.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner)
    }
    fn __len__(&self) -> usize {
        self.inner.results.len()
    }
    /// Pickles as its fields exactly (``Comparison._from_json``) (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let r = crate::pickle::recipe(
            py,
            "Comparison._from_json",
            vec![crate::pickle::json(py, &self.inner)?],
            &[],
        )?;
        crate::pickle::reduce(py, &r)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Self>().is_ok_and(|o| {
            let o = o.get();
            crate::pickle::same(&o.inner, &self.inner)
        })
    }

    /// A comparison from its JSON (for unpickling).
    #[staticmethod]
    fn _from_json(text: &str) -> PyResult<PyComparison> {
        let s: ComparisonState = serde_json::from_str(text).map_err(bad_json)?;
        Ok(PyComparison {
            inner: DesignComparison {
                design: s.design,
                dof: s.dof,
                results: s.results.into_iter().map(Into::into).collect(),
            },
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "isogami.Comparison({}: {})",
            self.inner.design,
            self.inner
                .results
                .iter()
                .map(|r| format!("{} t {:.3}", r.method, r.final_t))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

/// Runs rigid modes, NCM and springs on ``design`` with otherwise equal settings (paper §5,
/// Fig. 4): how far along the rigid-modes path each gets and how much it opens.
///
/// ``settings`` and keyword overrides as for ``deploy`` (the method is ignored); ``progress``
/// and ``timeout`` as for ``deploy`` (the state count restarts with each method). Runs with
/// the GIL released; Ctrl-C interrupts it.
#[pyfunction]
#[pyo3(signature = (design, settings=None, *, progress=None, timeout=None, **overrides))]
pub fn compare(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    settings: Option<&Bound<'_, PyAny>>,
    progress: Option<Bound<'_, PyAny>>,
    timeout: Option<f64>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyComparison> {
    let settings = settings_of(settings, overrides)?;
    let design = design_of(design)?;
    let mut watch = Watch::new(progress.filter(|p| !p.is_none()), timeout)?;
    let result = py.detach(|| compare_with(&design, &settings, &mut |n| watch.tick(n)));
    let inner = watch.finish(result)?;
    Ok(PyComparison { inner })
}

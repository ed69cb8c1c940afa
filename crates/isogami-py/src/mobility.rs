//! `isogami.analyze`: the mobility of a design in its closed state (degrees of freedom,
//! spectrum and gap, first-order motions) as numpy arrays.

use crate::convert::{array, design_of, point, to_python};
use crate::errors;
use isogami::api::{analyze as lib_analyze, Analysis};
use isogami::mobility::{MobilitySettings, Motion};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

/// One first-order motion: a unit vector of the non-dimensional state space (lengths in
/// units of the mean edge length L), signed so that it opens the sheet.
#[pyclass(name = "Motion", module = "isogami", frozen)]
pub struct PyMotion {
    inner: Motion,
}

/// A motion's vector, skipped by its JSON, from the pickled arrays.
fn with_vector(mut m: Motion, vector: Option<Vec<f64>>) -> Motion {
    m.vector = isogami::math::DVec::from_vec(vector.unwrap_or_default());
    m
}

impl crate::pickle::Pickled for PyMotion {
    const CLASS: &'static str = "Motion";
    fn save(&self) -> PyResult<(Vec<u8>, Vec<Vec<f64>>)> {
        let v = self.inner.vector.as_slice().to_vec();
        Ok((crate::pickle::to_json(&self.inner)?, vec![v]))
    }
    fn load(json: &[u8], arrays: Vec<Vec<f64>>) -> PyResult<Self> {
        let m = Python::attach(|py| crate::pickle::from_json(py, Self::CLASS, json))?;
        Ok(PyMotion {
            inner: with_vector(m, arrays.into_iter().next()),
        })
    }
}

impl crate::pickle::Pickled for PyAnalysis {
    const CLASS: &'static str = "Analysis";
    /// The vectors of the motion, then of every mode.
    fn save(&self) -> PyResult<(Vec<u8>, Vec<Vec<f64>>)> {
        let m = &self.inner.mobility;
        let vectors = m
            .motion
            .iter()
            .chain(&m.modes)
            .map(|m| m.vector.as_slice().to_vec())
            .collect();
        Ok((crate::pickle::to_json(&self.inner)?, vectors))
    }
    fn load(json: &[u8], arrays: Vec<Vec<f64>>) -> PyResult<Self> {
        let mut inner: Analysis =
            Python::attach(|py| crate::pickle::from_json(py, Self::CLASS, json))?;
        let mut vectors = arrays.into_iter();
        let m = &mut inner.mobility;
        m.motion = m.motion.take().map(|v| with_vector(v, vectors.next()));
        m.modes = std::mem::take(&mut m.modes)
            .into_iter()
            .map(|v| with_vector(v, vectors.next()))
            .collect();
        Ok(PyAnalysis { inner })
    }
}

#[pymethods]
impl PyMotion {
    /// Velocity of every tile, shape (tiles, 3): vx, vy (units of L) and omega (radians);
    /// tile 0 is held fixed.
    #[getter]
    fn tiles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = &self.inner.tiles;
        array(
            py,
            (t.len(), 3),
            t.iter().flat_map(|v| [v.vx, v.vy, v.omega]).collect(),
        )
    }

    /// Rate of the tiling vector u, shape (2,).
    #[getter]
    fn u<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        point(py, self.inner.u)
    }

    /// Rate of the tiling vector w, shape (2,).
    #[getter]
    fn w<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        point(py, self.inner.w)
    }

    /// Rate of change of the cell area det[u w] along this motion (positive: opening).
    #[getter]
    fn area_rate(&self) -> f64 {
        self.inner.area_rate
    }

    /// The whole unit vector in state order (x, y, θ per tile, then u, w).
    #[getter]
    fn vector<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.inner.vector.as_slice())
    }

    /// Pickles as its data (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        crate::pickle::reduce_state(py, self)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Self>()
            .is_ok_and(|o| o.get().inner == self.inner)
    }

    fn __repr__(&self) -> String {
        format!(
            "isogami.Motion({} tiles, area rate {:+.6})",
            self.inner.tiles.len(),
            self.inner.area_rate
        )
    }
}

/// The mobility analysis of a design (paper §3.2): the spectrum of H = JᵀJ with tile 0
/// fixed, the zero-eigenvalue count against a relative tolerance, the gap that separates
/// zero from non-zero eigenvalues, and the first-order motions.
#[pyclass(name = "Analysis", module = "isogami", frozen)]
pub struct PyAnalysis {
    inner: Analysis,
}

#[pymethods]
impl PyAnalysis {
    /// The design's spec string.
    #[getter]
    fn design(&self) -> String {
        self.inner.design.clone()
    }

    /// Tiles in the cell.
    #[getter]
    fn tiles(&self) -> usize {
        self.inner.tiles
    }

    /// Unique edges of the cell.
    #[getter]
    fn edges(&self) -> usize {
        self.inner.edges
    }

    /// Pin joints.
    #[getter]
    fn joints(&self) -> usize {
        self.inner.joints
    }

    /// Mean edge length L (tiling units).
    #[getter]
    fn length_scale(&self) -> f64 {
        self.inner.length_scale
    }

    /// Degrees of freedom: 0 rigid, 1 self-deployable, more under-constrained.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.mobility.dof
    }

    /// All eigenvalues of the reduced non-dimensional H, ascending (numpy array).
    #[getter]
    fn eigenvalues<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.mobility.eigenvalues)
    }

    /// Same as ``eigenvalues``: the spectrum of H.
    #[getter]
    fn spectrum<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.eigenvalues(py)
    }

    /// The zero threshold used: tol · max(λ_max, 1).
    #[getter]
    fn threshold(&self) -> f64 {
        self.inner.mobility.threshold
    }

    /// Largest eigenvalue counted as zero (None when rigid).
    #[getter]
    fn largest_zero(&self) -> Option<f64> {
        self.inner.mobility.largest_zero
    }

    /// Smallest eigenvalue counted as non-zero (None when all are zero).
    #[getter]
    fn smallest_nonzero(&self) -> Option<f64> {
        self.inner.mobility.smallest_nonzero
    }

    /// log10(smallest_nonzero / largest_zero): decades between the zero and non-zero groups
    /// (None when a group is empty; capped at 300).
    #[getter]
    fn gap_decades(&self) -> Option<f64> {
        self.inner.mobility.gap_decades
    }

    /// The gap as a numpy array ``[largest_zero, smallest_nonzero]`` (empty when either is
    /// missing): the two eigenvalues the DOF count was decided between.
    #[getter]
    fn gap<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let m = &self.inner.mobility;
        match (m.largest_zero, m.smallest_nonzero) {
            (Some(z), Some(nz)) => PyArray1::from_slice(py, &[z, nz]),
            _ => PyArray1::from_slice(py, &[]),
        }
    }

    /// The opening direction (None when rigid): for one DOF the null vector signed to open
    /// the sheet; for several, the unit combination that opens it fastest.
    #[getter]
    fn motion(&self) -> Option<PyMotion> {
        self.inner
            .mobility
            .motion
            .clone()
            .map(|inner| PyMotion { inner })
    }

    /// A basis of all first-order motions (``dof`` of them).
    #[getter]
    fn modes(&self) -> Vec<PyMotion> {
        self.inner
            .mobility
            .modes
            .iter()
            .map(|m| PyMotion { inner: m.clone() })
            .collect()
    }

    /// The analysis as ``isogami analyze --json`` prints it.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner)
    }

    /// Pickles as its data (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        crate::pickle::reduce_state(py, self)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Self>()
            .is_ok_and(|o| crate::pickle::same(&o.get().inner, &self.inner))
    }

    fn __repr__(&self) -> String {
        format!(
            "isogami.Analysis({}: dof {}, {} tiles, {} joints)",
            self.inner.design, self.inner.mobility.dof, self.inner.tiles, self.inner.joints
        )
    }
}

/// Mobility of ``design`` (an ``isogami.Design``, a name, a spec string or design JSON) in
/// its closed state.
///
/// ``tol`` is the relative zero tolerance on the eigenvalues of the non-dimensional H
/// (default 1e-9, must lie in (0, 1)). Returns an ``Analysis`` with ``dof``, ``eigenvalues``
/// (numpy), ``gap_decades``, ``motion`` and ``modes``. Raises ``SettingsError`` for a bad
/// tolerance and the design's errors for a bad design.
#[pyfunction]
#[pyo3(signature = (design, tol=None))]
pub fn analyze(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    tol: Option<f64>,
) -> PyResult<PyAnalysis> {
    let design = design_of(design)?;
    let settings = MobilitySettings {
        rel_tol: tol.unwrap_or(MobilitySettings::default().rel_tol),
    };
    crate::pickle::computing();
    let inner = py
        .detach(|| lib_analyze(&design, settings))
        .map_err(errors::library)?;
    Ok(PyAnalysis { inner })
}

//! `isogami.DeploySettings`: every setting of a deployment (method, contact, step control,
//! tolerances, limits, mode), with the library's defaults and checks.

use crate::convert::type_name;
use crate::errors;
use isogami::contact::ContactSettings;
use isogami::deploy::{DeploySettings, Method};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The names of every setting, in the order they are documented.
pub const NAMES: &[&str] = &[
    "method",
    "kerf",
    "dhat",
    "stiffness",
    "step_weight",
    "initial_step",
    "max_step",
    "max_halvings",
    "growth",
    "max_steps",
    "step_tolerance",
    "joint_tolerance",
    "frame_joint_tolerance",
    "max_attempts",
    "max_stretch",
    "mobility_tol",
    "mode",
];

/// Settings of a deployment; lengths in units of the mean edge length L.
///
/// Every argument is keyword-only and defaults to the library's value:
///
/// - ``method``: ``"rigid-modes"`` (the paper's method, default), ``"ncm"`` (nonlinear
///   compliant modes, Duenser et al. 2022) or ``"springs"`` (Liu et al. 2022a).
/// - ``kerf`` (0.01): physical cut width, in [1e-4, 0.2]; the collision polygons are the
///   tiles inset by kerf / 2. Setting it sets ``dhat`` to kerf / 2 unless ``dhat`` is given.
/// - ``dhat`` (kerf / 2): barrier activation distance, 0 < dhat < kerf.
/// - ``stiffness`` (1.0): barrier stiffness κ.
/// - ``step_weight`` (1e-4): weight w of the progress term E_step.
/// - ``initial_step`` (0.02), ``max_step`` (0.1), ``growth`` (1.5), ``max_halvings`` (10):
///   step length control (β halves on failure, grows after success; a step failing at
///   ``max_halvings`` halvings ends the deployment).
/// - ``max_steps`` (5000), ``max_attempts`` (20000): limits on accepted and attempted steps.
/// - ``step_tolerance`` (1e-3), ``joint_tolerance`` (1e-9), ``frame_joint_tolerance``
///   (1e-8): acceptance tolerances of a step, a state and a reported frame.
/// - ``max_stretch`` (100): a cell grown beyond this multiple of its closed size diverged.
/// - ``mobility_tol`` (1e-9): relative zero tolerance of the mobility analysis.
/// - ``mode`` (None): for a design with several DOF, open along basis motion ``mode``
///   instead of the fastest-opening combination.
///
/// Values are checked when a deployment starts (or by ``validate()``): ``SettingsError``
/// names the setting, the value and the allowed range. ``replace(**changes)`` returns a copy
/// with some settings changed.
#[pyclass(name = "DeploySettings", module = "isogami", frozen)]
#[derive(Clone)]
pub struct PyDeploySettings {
    pub inner: DeploySettings,
}

/// `settings` with the keyword arguments of `changes` applied (kerf first, so that an explicit
/// dhat wins over kerf / 2).
pub fn apply(
    mut settings: DeploySettings,
    changes: &[(String, Bound<'_, PyAny>)],
) -> PyResult<DeploySettings> {
    let kerf_first = changes
        .iter()
        .filter(|(k, _)| k == "kerf")
        .chain(changes.iter().filter(|(k, _)| k != "kerf"));
    for (key, value) in kerf_first {
        set(&mut settings, key, value)?;
    }
    Ok(settings)
}

/// The keyword arguments of a dict, in order.
pub fn pairs<'py>(
    kwargs: Option<&Bound<'py, PyDict>>,
) -> PyResult<Vec<(String, Bound<'py, PyAny>)>> {
    let mut out = Vec::new();
    if let Some(d) = kwargs {
        for (k, v) in d.iter() {
            out.push((k.extract::<String>()?, v));
        }
    }
    Ok(out)
}

fn number(key: &str, value: &Bound<'_, PyAny>) -> PyResult<f64> {
    value.extract::<f64>().map_err(|_| {
        PyTypeError::new_err(format!("{key} must be a number, got {}", type_name(value)))
    })
}

fn count<T: for<'a, 'py> FromPyObject<'a, 'py>>(
    key: &str,
    value: &Bound<'_, PyAny>,
) -> PyResult<T> {
    value.extract::<T>().map_err(|_| {
        PyTypeError::new_err(format!(
            "{key} must be a non-negative int, got {} {}",
            type_name(value),
            value.repr().map(|r| r.to_string()).unwrap_or_default()
        ))
    })
}

/// Sets one setting by name.
fn set(s: &mut DeploySettings, key: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    match key {
        "method" => {
            let text: String = value.extract().map_err(|_| {
                PyTypeError::new_err(format!("method must be a str, got {}", type_name(value)))
            })?;
            s.method = text
                .parse::<Method>()
                .map_err(|e| errors::library(e.into()))?;
        }
        "kerf" => {
            s.contact = ContactSettings {
                stiffness: s.contact.stiffness,
                ..ContactSettings::with_kerf(number(key, value)?)
            }
        }
        "dhat" => s.contact.dhat = number(key, value)?,
        "stiffness" => s.contact.stiffness = number(key, value)?,
        "step_weight" => s.step_weight = number(key, value)?,
        "initial_step" => s.initial_step = number(key, value)?,
        "max_step" => s.max_step = number(key, value)?,
        "max_halvings" => s.max_halvings = count(key, value)?,
        "growth" => s.growth = number(key, value)?,
        "max_steps" => s.max_steps = count(key, value)?,
        "step_tolerance" => s.step_tolerance = number(key, value)?,
        "joint_tolerance" => s.joint_tolerance = number(key, value)?,
        "frame_joint_tolerance" => s.frame_joint_tolerance = number(key, value)?,
        "max_attempts" => s.max_attempts = count(key, value)?,
        "max_stretch" => s.max_stretch = number(key, value)?,
        "mobility_tol" => s.mobility.rel_tol = number(key, value)?,
        "mode" => {
            s.mode = if value.is_none() {
                None
            } else {
                Some(count(key, value)?)
            }
        }
        other => {
            return Err(PyTypeError::new_err(format!(
                "unexpected setting '{}'; deployment settings are: {}",
                other.escape_debug(),
                NAMES.join(", ")
            )))
        }
    }
    Ok(())
}

#[pymethods]
impl PyDeploySettings {
    #[new]
    #[pyo3(signature = (**settings))]
    fn new(settings: Option<&Bound<'_, PyDict>>) -> PyResult<PyDeploySettings> {
        let inner = apply(DeploySettings::default(), &pairs(settings)?)?;
        Ok(PyDeploySettings { inner })
    }

    /// A copy with the given settings changed (same keywords as the constructor).
    #[pyo3(signature = (**changes))]
    fn replace(&self, changes: Option<&Bound<'_, PyDict>>) -> PyResult<PyDeploySettings> {
        let inner = apply(self.inner, &pairs(changes)?)?;
        Ok(PyDeploySettings { inner })
    }

    /// Checks every setting; raises ``SettingsError`` naming the first one out of range.
    fn validate(&self) -> PyResult<()> {
        self.inner.validate().map_err(|e| errors::library(e.into()))
    }

    /// ``"rigid-modes"``, ``"ncm"`` or ``"springs"``.
    #[getter]
    fn method(&self) -> String {
        self.inner.method.to_string()
    }
    /// Cut width relative to the mean edge length.
    #[getter]
    fn kerf(&self) -> f64 {
        self.inner.contact.kerf
    }
    /// Barrier activation distance.
    #[getter]
    fn dhat(&self) -> f64 {
        self.inner.contact.dhat
    }
    /// Barrier stiffness.
    #[getter]
    fn stiffness(&self) -> f64 {
        self.inner.contact.stiffness
    }
    /// Weight of the progress term E_step.
    #[getter]
    fn step_weight(&self) -> f64 {
        self.inner.step_weight
    }
    /// First step length β.
    #[getter]
    fn initial_step(&self) -> f64 {
        self.inner.initial_step
    }
    /// Largest step length β.
    #[getter]
    fn max_step(&self) -> f64 {
        self.inner.max_step
    }
    /// Halvings of the initial β before the deployment ends.
    #[getter]
    fn max_halvings(&self) -> u32 {
        self.inner.max_halvings
    }
    /// Growth factor of β after a success.
    #[getter]
    fn growth(&self) -> f64 {
        self.inner.growth
    }
    /// Largest number of accepted steps.
    #[getter]
    fn max_steps(&self) -> usize {
        self.inner.max_steps
    }
    /// Relative tolerance on a step's progress.
    #[getter]
    fn step_tolerance(&self) -> f64 {
        self.inner.step_tolerance
    }
    /// Largest joint residual of an accepted state (units of L).
    #[getter]
    fn joint_tolerance(&self) -> f64 {
        self.inner.joint_tolerance
    }
    /// Largest joint residual of a reported frame (units of L).
    #[getter]
    fn frame_joint_tolerance(&self) -> f64 {
        self.inner.frame_joint_tolerance
    }
    /// Largest number of attempted steps.
    #[getter]
    fn max_attempts(&self) -> usize {
        self.inner.max_attempts
    }
    /// Growth of the cell beyond which the run counts as diverged.
    #[getter]
    fn max_stretch(&self) -> f64 {
        self.inner.max_stretch
    }
    /// Relative zero tolerance of the mobility analysis.
    #[getter]
    fn mobility_tol(&self) -> f64 {
        self.inner.mobility.rel_tol
    }
    /// Basis motion to open along (None: the fastest-opening combination).
    #[getter]
    fn mode(&self) -> Option<usize> {
        self.inner.mode
    }

    /// Every setting as a dict (the constructor's keywords).
    fn to_dict<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(slf.py());
        for name in NAMES {
            d.set_item(name, slf.getattr(name)?)?;
        }
        Ok(d)
    }

    /// Pickles as ``DeploySettings(**to_dict())`` (unset ``mode`` left out).
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let py = slf.py();
        let d = Self::to_dict(slf)?;
        let kwargs: Vec<(String, Bound<'py, PyAny>)> = d
            .iter()
            .filter(|(_, v)| !v.is_none())
            .map(|(k, v)| Ok((k.extract::<String>()?, v)))
            .collect::<PyResult<_>>()?;
        let kwargs: Vec<(&str, Bound<'py, PyAny>)> = kwargs
            .iter()
            .map(|(k, v)| (k.as_str(), v.clone()))
            .collect();
        let r = crate::pickle::recipe(py, "DeploySettings", vec![], &kwargs)?;
        crate::pickle::reduce(py, &r)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyDeploySettings>()
            .is_ok_and(|o| o.get().inner == self.inner)
    }

    fn __repr__(slf: &Bound<'_, Self>) -> PyResult<String> {
        let parts: Vec<String> = NAMES
            .iter()
            .map(|n| {
                let v = slf.getattr(*n)?.repr()?.to_string();
                Ok(format!("{n}={v}"))
            })
            .collect::<PyResult<_>>()?;
        Ok(format!("isogami.DeploySettings({})", parts.join(", ")))
    }
}

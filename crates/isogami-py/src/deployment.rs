//! `isogami.deploy` and `isogami.Deployment`: a deployment from the closed state to the contact
//! limit with any method and setting, its report and per-frame measures as numpy arrays.
//! The library call runs with the GIL released.

use crate::convert::{array, design_of, int_array, to_python};
use crate::deployment_state::Held;
use crate::errors;
use crate::progress::Watch;
use crate::settings::{apply, pairs, PyDeploySettings};
use isogami::api::{
    deploy as lib_deploy, resolve_design, DeployRequest, Deployment, FrameSelection,
};
use isogami::contact::{ContactModel, ContactSettings};
use isogami::deploy::{DeploySettings, FrameReport};
use isogami::kinematics::Mechanism;
use isogami::measure::{classify_with, expansion_profile, ClassifyTolerances, FrameMeasures};
use isogami::render::deployment_frame_svgs;
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::{PyIndexError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::OnceLock;

/// A finished deployment: the report ``isogami deploy --json`` prints, and its frames as
/// numpy arrays (n frames, evenly spaced in t unless every step was asked for).
///
/// Per-frame arrays: ``t`` (n,), ``step`` (n,), ``F`` (n, 2, 2) deformation gradient,
/// ``U`` (n, 2, 2) right stretch, ``principal_expansions`` (n, 2) as (min, max),
/// ``principal_angle`` (n,), ``area_ratio`` (n,), ``lattice_rotation`` (n,),
/// ``tile_rotations`` (n, tiles), ``tile_poses`` (n, tiles, 3) as (x, y, θ),
/// ``tiling_vectors`` (n, 2, 2) as (u, w), ``joint_residual`` (n,), ``clearance`` (n,),
/// ``states`` (n, unknowns). Summary numbers (``max_area_ratio``, ``behaviour``, ...) are
/// attributes; ``report()`` gives the whole report as a dict.
#[pyclass(name = "Deployment", module = "isogami", frozen)]
pub struct PyDeployment {
    pub(crate) inner: Held,
    /// The mechanism and contact model, for drawing: built from the design when first
    /// needed (an unpickled deployment has only its data).
    pub(crate) scene: OnceLock<(Mechanism, ContactModel)>,
}

impl PyDeployment {
    fn new(d: Deployment, contact: ContactSettings) -> Self {
        let scene = OnceLock::new();
        let _ = scene.set((d.mechanism, d.contact));
        PyDeployment {
            inner: Held {
                report: d.report,
                frames: d.frames,
                contact,
            },
            scene,
        }
    }

    /// The mechanism and contact model (built from the design on first use).
    fn scene(&self) -> PyResult<&(Mechanism, ContactModel)> {
        if let Some(s) = self.scene.get() {
            return Ok(s);
        }
        let design = resolve_design(&self.inner.report.design).map_err(errors::library)?;
        let cell = design.cell().map_err(|e| errors::library(e.into()))?;
        let mech = Mechanism::new(&cell, &design.joints).map_err(|e| errors::library(e.into()))?;
        let contact =
            ContactModel::new(&mech, self.inner.contact).map_err(|e| errors::library(e.into()))?;
        Ok(self.scene.get_or_init(|| (mech, contact)))
    }

    fn frames(&self) -> &[FrameReport] {
        &self.inner.report.frames
    }

    fn per_frame<'py>(
        &self,
        py: Python<'py>,
        pick: impl Fn(&FrameReport) -> f64,
    ) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> = self.frames().iter().map(pick).collect();
        PyArray1::from_vec(py, v)
    }

    fn per_frame_matrix<'py>(
        &self,
        py: Python<'py>,
        pick: impl Fn(&FrameReport) -> [[f64; 2]; 2],
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let f = self.frames();
        let v = f
            .iter()
            .flat_map(|r| pick(r).into_iter().flatten())
            .collect();
        array(py, (f.len(), 2, 2), v)
    }

    fn tile_count(&self) -> usize {
        self.frames().first().map_or(0, |f| f.tiles.len())
    }

    /// A frame index from a Python index (negative counts from the end) or the frame nearest
    /// to t.
    fn frame_of(&self, frame: Option<isize>, t: Option<f64>) -> PyResult<usize> {
        let n = self.frames().len();
        match (frame, t) {
            (Some(_), Some(_)) => Err(PyTypeError::new_err("give frame or t, not both")),
            (Some(k), None) => {
                let i = if k < 0 { n as isize + k } else { k };
                usize::try_from(i).ok().filter(|&i| i < n).ok_or_else(|| {
                    PyIndexError::new_err(format!("frame {k} out of range for {n} frames"))
                })
            }
            (None, Some(t)) => self.nearest(t),
            (None, None) => Ok(n.saturating_sub(1)),
        }
    }

    fn nearest(&self, t: f64) -> PyResult<usize> {
        let t = crate::convert::finite("t", t)?;
        self.frames()
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1.t - t).abs().total_cmp(&(b.1.t - t).abs()))
            .map(|(k, _)| k)
            .ok_or_else(|| PyIndexError::new_err("a deployment without frames"))
    }

    fn measures(&self) -> Vec<FrameMeasures> {
        self.inner
            .frames
            .iter()
            .map(|f| f.measures.clone())
            .collect()
    }
}

#[pymethods]
impl PyDeployment {
    /// The design's spec string.
    #[getter]
    fn design(&self) -> String {
        self.inner.report.design.clone()
    }
    /// The method: ``"rigid-modes"``, ``"ncm"`` or ``"springs"``.
    #[getter]
    fn method(&self) -> String {
        self.inner.report.method.to_string()
    }
    /// Kerf relative to the mean edge length.
    #[getter]
    fn kerf(&self) -> f64 {
        self.inner.report.kerf
    }
    /// Mean edge length L (tiling units).
    #[getter]
    fn length_scale(&self) -> f64 {
        self.inner.report.length_scale
    }
    /// Degrees of freedom of the closed state (1 for a self-deployable sheet).
    #[getter]
    fn dof(&self) -> usize {
        self.inner.report.dof
    }
    /// Why the deployment ended: ``"contact_limit"``, ``"locked"``, ``"step_size_exhausted"``,
    /// ``"stalled"``, ``"max_steps"``, ``"diverged"`` or ``"solver_failure"`` (see
    /// ``report()["end_reason"]`` for diagnostics).
    #[getter]
    fn end_reason(&self, py: Python<'_>) -> PyResult<String> {
        to_python(py, &self.inner.report.end_reason)?
            .get_item("kind")?
            .extract()
    }
    /// States of the trajectory, the closed one included.
    #[getter]
    fn steps(&self) -> usize {
        self.inner.report.steps
    }
    /// Attempted steps, accepted or not.
    #[getter]
    fn attempts(&self) -> usize {
        self.inner.report.attempts
    }
    /// Arc length of the path (non-dimensional).
    #[getter]
    fn arc_length(&self) -> f64 {
        self.inner.report.arc_length
    }
    /// Largest joint residual over every accepted state (relative to L).
    #[getter]
    fn max_joint_residual(&self) -> f64 {
        self.inner.report.max_joint_residual
    }
    /// Smallest clearance between collision polygons over every accepted state (relative to
    /// L).
    #[getter]
    fn min_clearance(&self) -> f64 {
        self.inner.report.min_clearance
    }
    /// Behaviour class: ``"isotropic_auxetic"``, ``"anisotropic_auxetic"``,
    /// ``"orthotropic_positive_poisson"``, or None when the sheet does not expand.
    #[getter]
    fn behaviour(&self) -> Option<String> {
        self.inner.report.behaviour.map(|b| b.to_string())
    }
    /// Largest principal expansion reached.
    #[getter]
    fn max_expansion(&self) -> f64 {
        self.inner.report.max_expansion
    }
    /// Smallest principal expansion reached.
    #[getter]
    fn min_expansion(&self) -> f64 {
        self.inner.report.min_expansion
    }
    /// Largest area ratio det F reached.
    #[getter]
    fn max_area_ratio(&self) -> f64 {
        self.inner.report.max_area_ratio
    }
    /// Largest tile rotation reached (radians).
    #[getter]
    fn max_tile_rotation(&self) -> f64 {
        self.inner.report.max_tile_rotation
    }

    /// Normalised arc length of every frame, 0 closed … 1 at the end.
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.t)
    }
    /// Raw step index of every frame (int).
    #[getter]
    fn step<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let f = self.frames();
        int_array(py, f.len(), f.iter().map(|r| r.step as i64).collect())
    }
    /// Deformation gradient F per frame, [u w] = F [ū w̄], shape (n, 2, 2).
    #[getter(F)]
    fn deformation_gradient<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        self.per_frame_matrix(py, |f| f.f)
    }
    /// Right stretch tensor U of F = RU per frame, shape (n, 2, 2).
    #[getter(U)]
    fn stretch<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        self.per_frame_matrix(py, |f| f.measures.u)
    }
    /// Principal expansions (eigenvalues of U − I) per frame, shape (n, 2) as (min, max).
    #[getter]
    fn principal_expansions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let f = self.frames();
        array(
            py,
            (f.len(), 2),
            f.iter()
                .flat_map(|r| [r.measures.min_expansion, r.measures.max_expansion])
                .collect(),
        )
    }
    /// Direction of the largest expansion per frame (radians, in (−π/2, π/2]).
    #[getter]
    fn principal_angle<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.measures.principal_angle)
    }
    /// Area ratio det F per frame.
    #[getter]
    fn area_ratio<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.measures.area_ratio)
    }
    /// Rotation of the sheet as a whole per frame (radians).
    #[getter]
    fn lattice_rotation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.measures.lattice_rotation)
    }
    /// Rotation of every tile relative to the closed state with the sheet's turn removed,
    /// shape (n, tiles), radians.
    #[getter]
    fn tile_rotations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let f = self.frames();
        let v = f
            .iter()
            .flat_map(|r| r.measures.tile_rotations.iter().copied())
            .collect();
        array(py, (f.len(), self.tile_count()), v)
    }
    /// Pose of every tile per frame, shape (n, tiles, 3): centroid x, y (tiling units) and
    /// rotation θ from the closed state (radians; tile 0 held fixed).
    #[getter]
    fn tile_poses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let f = self.frames();
        let v = f
            .iter()
            .flat_map(|r| r.tiles.iter().flat_map(|p| [p.x, p.y, p.theta]))
            .collect();
        array(py, (f.len(), self.tile_count(), 3), v)
    }
    /// Tiling vectors per frame, shape (n, 2, 2): ``[:, 0]`` is u, ``[:, 1]`` is w (tiling
    /// units).
    #[getter]
    fn tiling_vectors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        self.per_frame_matrix(py, |f| [f.u, f.w])
    }
    /// Largest joint residual per frame, recomputed independently of the solver (units of L).
    #[getter]
    fn joint_residual<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.joint_residual)
    }
    /// Smallest clearance between collision polygons per frame (units of L).
    #[getter]
    fn clearance<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.min_clearance)
    }
    /// The non-dimensional state vector of every frame (x, y, θ per tile, then u, w; lengths
    /// in units of L), shape (n, unknowns).
    #[getter]
    fn states<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let f = &self.inner.frames;
        let m = f.first().map_or(0, |r| r.q.len());
        let v = f.iter().flat_map(|r| r.q.iter().copied()).collect();
        array(py, (f.len(), m), v)
    }

    /// Index of the frame nearest to deployment parameter ``t``.
    fn frame_index(&self, t: f64) -> PyResult<usize> {
        self.nearest(t)
    }

    /// The directional expansion ε(θ) = dᵀ(U − I)d of one frame over ``samples`` directions θ
    /// in [0, 2π): an array of shape (samples, 2) of (θ, ε), for a polar plot. The frame is
    /// ``frame`` (an index, negative from the end) or the one nearest to ``t``; by default
    /// the last.
    #[pyo3(signature = (t=None, frame=None, samples=None), text_signature = "($self, t=None, frame=None, samples=180)")]
    fn profile<'py>(
        &self,
        py: Python<'py>,
        t: Option<f64>,
        frame: Option<isize>,
        samples: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let samples = crate::convert::count_or("samples", samples, 0, 180)?;
        if !(3..=100_000).contains(&samples) {
            return Err(errors::SettingsError::new_err(format!(
                "invalid setting: samples {samples} must lie in 3..=100000"
            )));
        }
        let k = self.frame_of(frame, t)?;
        let u = self.inner.frames[k].measures.u_matrix();
        let p = expansion_profile(&u, samples);
        let n = p.len();
        array(
            py,
            (n, 2),
            p.into_iter().flat_map(|(a, e)| [a, e]).collect(),
        )
    }

    /// The behaviour class of this trajectory's frames under other thresholds than the
    /// report's (isotropic 0.05, orthotropic 0.02, absolute 1e-6; the first two in units of
    /// the largest expansion): see the library's measure::classify for the rule.
    #[pyo3(signature = (isotropic=0.05, orthotropic=0.02, absolute=1e-6))]
    fn classify(
        &self,
        isotropic: f64,
        orthotropic: f64,
        absolute: f64,
    ) -> PyResult<Option<String>> {
        let tol = ClassifyTolerances {
            isotropic: crate::convert::finite("isotropic", isotropic)?,
            orthotropic: crate::convert::finite("orthotropic", orthotropic)?,
            absolute: crate::convert::finite("absolute", absolute)?,
            ..ClassifyTolerances::default()
        };
        Ok(classify_with(&self.measures(), tol).map(|b| b.to_string()))
    }

    /// The report as ``isogami deploy --json`` prints it (a dict).
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.report)
    }

    /// The report as JSON text.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.inner.report)
            .map_err(|e| errors::IsogamiError::new_err(e.to_string()))
    }

    /// One SVG per frame (3×3 cells, the centre cell's collision polygons outlined, labelled
    /// with t), ``width`` pixels wide, in one shared view box.
    #[pyo3(signature = (width=480.0))]
    fn frame_svgs(&self, width: f64) -> PyResult<Vec<String>> {
        let width = crate::convert::finite("width", width)?.clamp(16.0, 8192.0);
        let (mechanism, contact) = self.scene()?;
        Ok(deployment_frame_svgs(
            mechanism,
            contact,
            &self.inner.frames,
            width,
        ))
    }

    fn _repr_svg_(&self) -> PyResult<String> {
        let last = self.inner.frames.len().saturating_sub(1);
        let (mechanism, contact) = self.scene()?;
        Ok(
            deployment_frame_svgs(mechanism, contact, &self.inner.frames[last..], 360.0)
                .pop()
                .unwrap_or_default(),
        )
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
            .is_ok_and(|o| crate::pickle::same(&o.get().inner.report, &self.inner.report))
    }

    /// One row per frame as a pandas DataFrame (needs pandas): ``t``, ``step``,
    /// ``area_ratio``, ``min_expansion``, ``max_expansion``, ``principal_angle``,
    /// ``lattice_rotation``, ``joint_residual`` and ``clearance``, indexed by frame number.
    fn dataframe<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        let pandas = py.import("pandas").map_err(|_| {
            pyo3::exceptions::PyImportError::new_err(
                "Deployment.dataframe needs pandas (pip install pandas); the per-frame \
                 arrays (t, area_ratio, ...) are attributes",
            )
        })?;
        let columns = PyDict::new(py);
        for name in ["t", "step", "area_ratio"] {
            columns.set_item(name, slf.getattr(name)?)?;
        }
        let me = slf.get();
        columns.set_item(
            "min_expansion",
            me.per_frame(py, |r| r.measures.min_expansion),
        )?;
        columns.set_item(
            "max_expansion",
            me.per_frame(py, |r| r.measures.max_expansion),
        )?;
        for name in [
            "principal_angle",
            "lattice_rotation",
            "joint_residual",
            "clearance",
        ] {
            columns.set_item(name, slf.getattr(name)?)?;
        }
        let df = pandas.getattr("DataFrame")?.call1((columns,))?;
        df.getattr("index")?.setattr("name", "frame")?;
        Ok(df)
    }

    fn __len__(&self) -> usize {
        self.frames().len()
    }

    fn __repr__(&self) -> String {
        let r = &self.inner.report;
        format!(
            "isogami.Deployment({}: {} frames, {}, area ratio up to {:.4})",
            r.design,
            r.frames.len(),
            r.end_reason,
            r.max_area_ratio
        )
    }
}

/// The frame selection of the `frames` argument: an int (about that many, evenly in t) or
/// "all" (every accepted state).
fn frame_selection(frames: &Bound<'_, PyAny>) -> PyResult<FrameSelection> {
    if let Ok(text) = frames.extract::<String>() {
        return match text.as_str() {
            "all" => Ok(FrameSelection::AllSteps),
            _ => Err(PyTypeError::new_err(format!(
                "frames must be an int or 'all', got '{}'",
                text.escape_debug()
            ))),
        };
    }
    if frames.is_instance_of::<pyo3::types::PyBool>() {
        return Err(PyTypeError::new_err(
            "frames must be an int or 'all', got bool",
        ));
    }
    let n = crate::convert::index_of(frames).ok_or_else(|| {
        PyTypeError::new_err(format!(
            "frames must be an int or 'all', got {}",
            crate::convert::type_name(frames)
        ))
    })?;
    // The library checks the range and names it; a negative or huge count is out of range
    // too, and shown as given.
    match n
        .extract::<i64>()
        .ok()
        .and_then(|n| usize::try_from(n).ok())
    {
        Some(n) => Ok(FrameSelection::Evenly(n)),
        None => Err(errors::SettingsError::new_err(format!(
            "invalid setting: frame count {n} must lie in 2..={}",
            isogami::api::MAX_FRAME_COUNT
        ))),
    }
}

/// Settings from an optional `DeploySettings` and keyword overrides.
pub fn settings_of(
    settings: Option<&Bound<'_, PyAny>>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<DeploySettings> {
    let base = match settings {
        None => DeploySettings::default(),
        Some(s) if s.is_none() => DeploySettings::default(),
        Some(s) => {
            s.cast::<PyDeploySettings>()
                .map_err(|_| {
                    PyTypeError::new_err(format!(
                        "settings must be an isogami.DeploySettings, got {}",
                        crate::convert::type_name(s)
                    ))
                })?
                .get()
                .inner
        }
    };
    apply(base, &pairs(overrides)?)
}

/// Deploys ``design`` (an ``isogami.Design``, a name, a spec string or design JSON) from its
/// closed state to the contact limit (paper §3.2).
///
/// ``settings`` is an ``isogami.DeploySettings``; any of its fields may also be given as a
/// keyword (``method="ncm"``, ``kerf=0.02``, ``max_steps=200``, ...), overriding it.
/// ``frames`` is the number of frames to report, exactly (default 60; 2..10000, accepted
/// states nearest to evenly spaced t, with states inserted between them when the deployment
/// has fewer) or ``"all"`` for every accepted state. The report's summaries are over every
/// accepted state whatever ``frames`` is.
///
/// ``progress``, if given, is called as ``progress(states)`` after every accepted step;
/// returning False stops the run with ``CancelledError``, and an exception it raises is
/// raised from ``deploy``. ``timeout`` (seconds) stops a run that takes longer with
/// ``CancelledError``. The GIL is released while the library runs, so deployments in several
/// threads run in parallel; Ctrl-C interrupts a run (``KeyboardInterrupt``).
///
/// Returns a ``Deployment``. Raises ``SettingsError`` for a setting out of range (before
/// anything runs), ``DeployError`` for a rigid design or a failed frame check, and the
/// design's own errors for a bad design.
///
/// >>> run = isogami.deploy("rotating-squares")
/// >>> round(float(run.area_ratio.max()), 3)   # squares turned by 45°: (cos + sin)² = 2
/// 2.0
#[pyfunction]
#[pyo3(signature = (design, settings=None, *, frames=None, progress=None, timeout=None, **overrides))]
pub fn deploy(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    settings: Option<&Bound<'_, PyAny>>,
    frames: Option<&Bound<'_, PyAny>>,
    progress: Option<Bound<'_, PyAny>>,
    timeout: Option<f64>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyDeployment> {
    let settings = settings_of(settings, overrides)?;
    let frames = match frames {
        Some(f) if !f.is_none() => frame_selection(f)?,
        _ => DeployRequest::default().frames,
    };
    let request = DeployRequest { settings, frames };
    request.validate().map_err(|e| errors::library(e.into()))?;
    let design = design_of(design)?;
    let mut watch = Watch::new(progress.filter(|p| !p.is_none()), timeout)?;
    let result = py.detach(|| lib_deploy(&design, &request, &mut |n| watch.tick(n)));
    let inner = watch.finish(result)?;
    Ok(PyDeployment::new(inner, settings.contact))
}

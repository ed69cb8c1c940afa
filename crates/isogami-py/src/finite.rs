//! `isogami.finite_sheet` / `isogami.FiniteSheet` and `isogami.deploy_sheet` /
//! `isogami.SheetDeployment`: a finite region of a design, its degrees of freedom with a free
//! boundary, its completion to one DOF, and its deployment with contact among its own tiles
//! (the library's `api::finite_sheet` and `api::deploy_sheet`), as numpy arrays.

use crate::convert::{array, design_of, int_array, to_python};
use crate::deployment::settings_of;
use crate::errors;
use crate::progress::Watch;
use isogami::api::{
    deploy_sheet as lib_deploy_sheet, finite_sheet as lib_finite_sheet, SheetAnalysis,
    SheetDeployRequest, SheetDeployment, SheetRequest,
};
use isogami::finite::{FiniteSheet, Region, SheetMobility};
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A finite sheet of a design: the raw region and, when asked, its completion to a sheet
/// that opens with the design's one motion (the data ``isogami sheet --json`` prints).
///
/// Tiles are rows ``(i, j, tile)``: tile ``tile`` of the design's cell in the cell copy at
/// ``i·u + j·w``. ``tiles``/``joints``/``dof`` describe the sheet a fabrication format writes
/// (the completed one when there is one), ``raw_*`` the region as asked. ``joints`` rows are
/// ``(a, b, joint)``: indices into ``tiles`` and the design's joint. Counts are made at an
/// opened periodic state ``t`` (the closed state, a singular configuration, separately).
#[pyclass(name = "FiniteSheet", module = "isogami", frozen)]
pub struct PyFiniteSheet {
    pub(crate) inner: SheetAnalysis,
}

fn tile_rows<'py>(py: Python<'py>, sheet: &FiniteSheet) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let v = sheet
        .tiles
        .iter()
        .flat_map(|t| [i64::from(t.cell[0]), i64::from(t.cell[1]), t.tile as i64])
        .collect();
    int_array(py, (sheet.len(), 3), v)
}

fn indices<'py>(py: Python<'py>, v: &[usize]) -> PyResult<Bound<'py, PyArray1<i64>>> {
    int_array(py, v.len(), v.iter().map(|&k| k as i64).collect())
}

impl PyFiniteSheet {
    fn mobility(&self) -> &SheetMobility {
        self.inner
            .completion
            .as_ref()
            .map_or(&self.inner.raw_mobility, |c| &c.mobility)
    }
}

#[pymethods]
impl PyFiniteSheet {
    /// The design's spec string.
    #[getter]
    fn design(&self) -> String {
        self.inner.design.clone()
    }
    /// The region asked for, as text (``"6x6"``, ``"rect:120,80"``, ...).
    #[getter]
    fn region(&self) -> String {
        self.inner.region.to_string()
    }
    /// t of the periodic state the counts were made at.
    #[getter]
    fn t(&self) -> f64 {
        self.inner.t
    }
    /// Whether the sheet is the completion (else the raw region).
    #[getter]
    fn completed(&self) -> bool {
        self.inner.completion.is_some()
    }
    /// The sheet's tiles, shape (n, 3): (i, j, tile).
    #[getter]
    fn tiles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        tile_rows(py, self.inner.sheet())
    }
    /// The sheet's pins, shape (m, 3): (a, b, joint) with a, b rows of ``tiles``.
    #[getter]
    fn joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let s = self.inner.sheet();
        let v = s
            .joints
            .iter()
            .flat_map(|j| [j.a as i64, j.b as i64, j.joint as i64])
            .collect();
        int_array(py, (s.joints.len(), 3), v)
    }
    /// Degrees of freedom of the sheet at the opened state (1 for a completed sheet).
    #[getter]
    fn dof(&self) -> usize {
        self.mobility().dof
    }
    /// Degrees of freedom of the sheet in the closed state (a singular configuration).
    #[getter]
    fn closed_dof(&self) -> usize {
        self.inner
            .completed_closed_dof
            .unwrap_or(self.inner.raw_closed_dof)
    }
    /// The raw region's tiles, shape (n_raw, 3).
    #[getter]
    fn raw_tiles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        tile_rows(py, &self.inner.raw)
    }
    /// Degrees of freedom of the raw region at the opened state.
    #[getter]
    fn raw_dof(&self) -> usize {
        self.inner.raw_mobility.dof
    }
    /// Degrees of freedom of the raw region in the closed state.
    #[getter]
    fn raw_closed_dof(&self) -> usize {
        self.inner.raw_closed_dof
    }
    /// The raw region's extra modes: one int array per mode, the rows of ``raw_tiles`` that
    /// move in it.
    #[getter]
    fn floppy_tiles<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyArray1<i64>>>> {
        self.inner
            .raw_mobility
            .floppy
            .iter()
            .map(|m| indices(py, &m.tiles))
            .collect()
    }
    /// Rows of ``raw_tiles`` held by fewer than two pins.
    #[getter]
    fn loose_tiles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        indices(py, &self.inner.raw_mobility.loose_tiles)
    }
    /// Share of the requested tiles' area the sheet keeps (1.0 for a raw sheet).
    #[getter]
    fn covered_fraction(&self) -> f64 {
        self.inner
            .completion
            .as_ref()
            .map_or(1.0, |c| c.report.covered_fraction)
    }
    /// Requested tiles completion left out, shape (k, 3) (empty for a raw sheet).
    #[getter]
    fn removed<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let tiles = self
            .inner
            .completion
            .as_ref()
            .map_or_else(Vec::new, |c| c.report.removed.clone());
        tile_rows(
            py,
            &FiniteSheet {
                tiles,
                joints: Vec::new(),
            },
        )
    }
    /// Tiles from outside the region completion added, shape (k, 3).
    #[getter]
    fn added<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let tiles = self
            .inner
            .completion
            .as_ref()
            .map_or_else(Vec::new, |c| c.report.added.clone());
        tile_rows(
            py,
            &FiniteSheet {
                tiles,
                joints: Vec::new(),
            },
        )
    }
    /// The whole analysis as a dict (what ``isogami sheet --json`` prints).
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
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
            "FiniteSheet({} {}: {} tiles, {} DOF{})",
            self.inner.design,
            self.inner.region,
            self.inner.sheet().len(),
            self.mobility().dof,
            if self.completed() {
                format!(", completed from {} DOF", self.inner.raw_mobility.dof)
            } else {
                String::new()
            }
        )
    }
}

/// A finite sheet deployed with contact among its own tiles to its contact limit, and the
/// periodic sheet's deployment for comparison (``isogami sheet --deploy --json``).
///
/// Per-frame arrays (f frames, the closed state first): ``t`` (f,), ``step`` (f,),
/// ``hull_area_ratio`` (f,), ``stretches`` (f, 2) as (larger, smaller), ``clearance`` (f,),
/// ``poses`` (f, n, 3) as (x, y, θ) per tile of ``sheet.tiles`` (tiling units).
#[pyclass(name = "SheetDeployment", module = "isogami", frozen)]
pub struct PySheetDeployment {
    inner: SheetDeployment,
}

impl PySheetDeployment {
    fn per_frame<'py>(
        &self,
        py: Python<'py>,
        pick: impl Fn(&isogami::api::SheetFrame) -> f64,
    ) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.inner.frames.iter().map(pick).collect())
    }
}

#[pymethods]
impl PySheetDeployment {
    /// The sheet that was deployed (its ``tiles`` order the poses).
    #[getter]
    fn sheet(&self) -> PyResult<PyFiniteSheet> {
        Ok(PyFiniteSheet {
            inner: self.inner.analysis.clone(),
        })
    }
    /// Why the finite deployment ended (``"contact_limit"``, ``"max_steps"``, ...).
    #[getter]
    fn end_reason(&self, py: Python<'_>) -> PyResult<String> {
        to_python(py, &self.inner.end_reason)?
            .get_item("kind")?
            .extract()
    }
    /// Accepted states of the finite deployment.
    #[getter]
    fn steps(&self) -> usize {
        self.inner.steps
    }
    /// Largest area of the tiles' convex hull over the closed sheet's, over every state.
    #[getter]
    fn max_hull_area_ratio(&self) -> f64 {
        self.inner.max_hull_area_ratio
    }
    /// The same sheet's hull area ratio where the periodic deployment ends.
    #[getter]
    fn periodic_hull_area_ratio(&self) -> f64 {
        self.inner.periodic.measures.hull_area_ratio
    }
    /// Largest distance between a tile's centre in the finite and the periodic deployment,
    /// over the states before contact (units of L).
    #[getter]
    fn max_position_deviation(&self) -> f64 {
        self.inner.agreement.max_position_deviation
    }
    /// Largest difference of a tile's angle between them (radians).
    #[getter]
    fn max_angle_deviation(&self) -> f64 {
        self.inner.agreement.max_angle_deviation
    }
    /// Whether the sheet had one DOF with the periodic motion at every state checked.
    #[getter]
    fn one_dof_throughout(&self) -> bool {
        self.inner.one_dof_throughout
    }
    /// t of every frame.
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.t)
    }
    /// Step index of every frame (int).
    #[getter]
    fn step<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let f = &self.inner.frames;
        int_array(py, f.len(), f.iter().map(|r| r.step as i64).collect())
    }
    /// Hull area ratio of every frame.
    #[getter]
    fn hull_area_ratio<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.measures.hull_area_ratio)
    }
    /// Principal stretches of the tile centres per frame, shape (f, 2), larger first.
    #[getter]
    fn stretches<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let f = &self.inner.frames;
        let v = f.iter().flat_map(|r| r.measures.stretches).collect();
        array(py, (f.len(), 2), v)
    }
    /// Smallest clearance between two of the sheet's collision polygons per frame (units
    /// of L).
    #[getter]
    fn clearance<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.min_clearance)
    }
    /// Tile poses per frame, shape (f, n, 3) as (x, y, θ).
    #[getter]
    fn poses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let n = self.inner.analysis.sheet().len();
        poses_array(py, self.inner.frames.iter().map(|f| &f.poses[..]), n)
    }
    /// The whole result as a dict (what ``isogami sheet --deploy --json`` prints).
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
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
            "SheetDeployment({}: {} tiles, {} after {} states, hull area x{:.4})",
            self.inner.analysis.design,
            self.inner.analysis.sheet().len(),
            self.inner.end_reason,
            self.inner.steps,
            self.inner.end.hull_area_ratio
        )
    }
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn sheet_request(
    region: &str,
    edge_mm: f64,
    t: f64,
    complete: bool,
    min_cover: f64,
    settings: Option<&Bound<'_, PyAny>>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<SheetRequest> {
    let region: Region = region
        .parse()
        .map_err(|e: isogami::finite::FiniteError| errors::library(e.into()))?;
    Ok(SheetRequest {
        region,
        edge_mm,
        t,
        complete,
        min_covered: min_cover,
        keep_raw_on_refusal: false,
        settings: settings_of(settings, overrides)?,
    })
}

/// The finite sheet of ``design`` in ``region``: ``"RxC"`` cells (``"6x6"``), or in mm
/// ``"rect:W,H"``, ``"disc:R"``, ``"polygon:x,y;x,y;..."`` centred on cell (0, 0), with mean
/// edge length ``edge_mm``. Its degrees of freedom with a free boundary are counted at the
/// periodic state nearest ``t`` in (0, 1]; with ``complete`` (default) it is completed to a
/// sheet with one DOF that moves like the periodic sheet, keeping at least ``min_cover`` of
/// the region's tile area. ``settings``/``**overrides``/``progress``/``timeout`` as for
/// ``deploy`` (the periodic deployment that finds the opened state).
///
/// Returns a ``FiniteSheet``. Raises ``FiniteError`` for a bad region or request, or when no
/// one-DOF sheet exists in the region (the message says why).
///
/// >>> s = isogami.finite_sheet("rotating-squares", "3x3")
/// >>> (s.dof, s.raw_dof, s.tiles.shape)
/// (1, 1, (36, 3))
#[pyfunction]
#[pyo3(signature = (design, region="6x6", *, edge_mm=20.0, t=0.3, complete=true, min_cover=0.5, settings=None, progress=None, timeout=None, **overrides))]
#[allow(clippy::too_many_arguments)]
pub fn finite_sheet(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    region: &str,
    edge_mm: f64,
    t: f64,
    complete: bool,
    min_cover: f64,
    settings: Option<&Bound<'_, PyAny>>,
    progress: Option<Bound<'_, PyAny>>,
    timeout: Option<f64>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyFiniteSheet> {
    let request = sheet_request(region, edge_mm, t, complete, min_cover, settings, overrides)?;
    let inner = run_detached(py, design, progress, timeout, |design, progress| {
        lib_finite_sheet(design, &request, progress)
    })?;
    Ok(PyFiniteSheet { inner })
}

/// Deploys the finite sheet ``finite_sheet`` would make (same arguments) with contact among
/// its own tiles to its contact limit, beside the periodic sheet, returning ``frames`` frames
/// of tile poses (at least 2). The sheet must have one DOF with the periodic motion: a raw
/// region (``complete=False``) that flops raises ``FiniteError`` naming its count.
///
/// Returns a ``SheetDeployment``.
///
/// >>> run = isogami.deploy_sheet("rotating-squares", "3x3")
/// >>> run.one_dof_throughout, run.poses.shape[1:]
/// (True, (36, 3))
#[pyfunction]
#[pyo3(signature = (design, region="6x6", *, edge_mm=20.0, t=0.3, complete=true, min_cover=0.5, frames=None, settings=None, progress=None, timeout=None, **overrides),
  text_signature = "(design, region='6x6', *, edge_mm=20.0, t=0.3, complete=True, min_cover=0.5, frames=24, settings=None, progress=None, timeout=None, **overrides)")]
#[allow(clippy::too_many_arguments)]
pub fn deploy_sheet(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    region: &str,
    edge_mm: f64,
    t: f64,
    complete: bool,
    min_cover: f64,
    frames: Option<&Bound<'_, PyAny>>,
    settings: Option<&Bound<'_, PyAny>>,
    progress: Option<Bound<'_, PyAny>>,
    timeout: Option<f64>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<PySheetDeployment> {
    let frames = crate::convert::count_or("frames", frames, 0, 24)?;
    let request = SheetDeployRequest {
        sheet: sheet_request(region, edge_mm, t, complete, min_cover, settings, overrides)?,
        frames,
        ..SheetDeployRequest::default()
    };
    let inner = run_detached(py, design, progress, timeout, |design, progress| {
        lib_deploy_sheet(design, &request, progress)
    })?;
    Ok(PySheetDeployment { inner })
}

/// Tile poses of every frame as an (f, n, 3) array of (x, y, θ).
pub(crate) fn poses_array<'py, 'a>(
    py: Python<'py>,
    frames: impl ExactSizeIterator<Item = &'a [isogami::deploy::TilePose]>,
    tiles: usize,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let count = frames.len();
    let v = frames
        .flat_map(|poses| poses.iter().flat_map(|p| [p.x, p.y, p.theta]))
        .collect();
    array(py, (count, tiles, 3), v)
}

/// Runs `f` on the design with the GIL released, its progress reported to the Python
/// callback and bounded by `timeout` (the plumbing every finite-sheet entry point shares).
pub(crate) fn run_detached<T: Send>(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    progress: Option<Bound<'_, PyAny>>,
    timeout: Option<f64>,
    f: impl FnOnce(&isogami::api::Design, isogami::deploy::Progress<'_>) -> isogami::Result<T> + Send,
) -> PyResult<T> {
    let design = design_of(design)?;
    let mut watch = Watch::new(progress.filter(|p| !p.is_none()), timeout)?;
    let result = py.detach(|| f(&design, &mut |n| watch.tick(n)));
    watch.finish(result)
}

crate::pickled_inner!(PyFiniteSheet, "FiniteSheet");
crate::pickled_inner!(PySheetDeployment, "SheetDeployment");

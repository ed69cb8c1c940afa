//! `isogami.pull_sheet` / `isogami.SheetPull`: a finite sheet — raw (floppy) or completed —
//! held by one tile and pulled apart by another, as a tester would, and how far its tiles
//! leave the periodic motion (the library's `api::pull_sheet`), as numpy arrays.

use crate::convert::{int_array, to_python};
use crate::finite::{poses_array, run_detached, sheet_request, PyFiniteSheet};
use isogami::api::{pull_sheet as lib_pull_sheet, PullFrame, SheetPull, SheetPullRequest};
use numpy::{PyArray1, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A finite sheet pulled apart by two of its tiles (``isogami sheet --pull --json``).
///
/// Per-frame arrays (f frames, the first where the pull starts): ``extension`` (f,),
/// ``deviation`` (f,) and ``periodic_t`` (f,) — how far the sheet is from the periodic
/// motion and at which of its states —, ``hull_area_ratio`` (f,), ``poses`` (f, n, 3) as
/// (x, y, θ) per tile of ``sheet.tiles`` (tiling units).
#[pyclass(name = "SheetPull", module = "isogami", frozen)]
pub struct PySheetPull {
    inner: SheetPull,
}

impl PySheetPull {
    fn per_frame<'py>(
        &self,
        py: Python<'py>,
        pick: impl Fn(&PullFrame) -> f64,
    ) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.inner.frames.iter().map(pick).collect())
    }
}

#[pymethods]
impl PySheetPull {
    /// The sheet that was pulled (its ``tiles`` order the poses).
    #[getter]
    fn sheet(&self) -> PyResult<PyFiniteSheet> {
        Ok(PyFiniteSheet {
            inner: self.inner.analysis.clone(),
        })
    }
    /// Degrees of freedom of the pulled sheet.
    #[getter]
    fn dof(&self) -> usize {
        self.inner.dof
    }
    /// The held tile and the pulled one (indices into ``sheet.tiles``).
    #[getter]
    fn grips(&self) -> (usize, usize) {
        (self.inner.grips[0], self.inner.grips[1])
    }
    /// Why the pull ended (``"stalled"``, ``"contact_limit"``, ...).
    #[getter]
    fn end_reason(&self, py: Python<'_>) -> PyResult<String> {
        to_python(py, &self.inner.end_reason)?
            .get_item("kind")?
            .extract()
    }
    /// Accepted states of the pull.
    #[getter]
    fn steps(&self) -> usize {
        self.inner.steps
    }
    /// Distance between the grips at the end over the closed sheet's.
    #[getter]
    fn final_extension(&self) -> f64 {
        self.inner.extension
    }
    /// Largest hull area ratio over the frames.
    #[getter]
    fn max_hull_area_ratio(&self) -> f64 {
        self.inner.max_hull_area_ratio
    }
    /// Largest distance of a tile vertex from the periodic motion over the frames (units
    /// of L).
    #[getter]
    fn max_deviation(&self) -> f64 {
        self.inner.max_deviation
    }
    /// Tiles that leave the periodic motion by more than 0.01 L (int array).
    #[getter]
    fn leaving<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let l = &self.inner.leaving;
        int_array(py, l.len(), l.iter().map(|&t| t as i64).collect())
    }
    /// Where the sheet leaves the periodic motion, or ``None``: a dict with
    /// ``after_periodic_t``, ``before_periodic_t`` and ``dof`` (the sheet's largest DOF count
    /// on the periodic path in between: 2 or more at a branch point).
    #[getter]
    fn leaves<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.leaves)
    }
    /// Grip distance over the closed sheet's, per frame.
    #[getter]
    fn extension<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.extension)
    }
    /// Distance from the periodic motion per frame (units of L).
    #[getter]
    fn deviation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.deviation)
    }
    /// t of the periodic state nearest each frame.
    #[getter]
    fn periodic_t<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.periodic_t)
    }
    /// Hull area ratio per frame.
    #[getter]
    fn hull_area_ratio<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_frame(py, |f| f.measures.hull_area_ratio)
    }
    /// Tile poses per frame, shape (f, n, 3) as (x, y, θ).
    #[getter]
    fn poses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let n = self.inner.analysis.sheet().len();
        poses_array(py, self.inner.frames.iter().map(|f| &f.poses[..]), n)
    }
    /// The whole result as a dict (what ``isogami sheet --pull --json`` prints).
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
            "SheetPull({}: {} tiles, {} DOF, {} after {} states, grips x{:.4} apart, deviation {:.3e} L)",
            self.inner.analysis.design,
            self.inner.analysis.sheet().len(),
            self.inner.dof,
            self.inner.end_reason,
            self.inner.steps,
            self.inner.extension,
            self.inner.max_deviation
        )
    }
}

/// Pulls the finite sheet ``finite_sheet`` would make apart by two of its tiles, as a
/// tester would: ``grips`` = (held, pulled) indices into its tiles, or ``None`` for the
/// ends of the sheet along the direction it opens most. With ``complete=False`` the raw
/// region is pulled, floppy boundary and all: what an uncompleted patch does (its extra
/// modes carry tiles away from the periodic motion); a completed sheet (the default) follows
/// the motion, or leaves it only at a branch point. ``frames`` frames of tile poses (at
/// least 2); other arguments as for ``finite_sheet``.
///
/// Returns a ``SheetPull``. Raises ``FiniteError`` for bad grips or requests.
///
/// >>> run = isogami.pull_sheet("rotating-squares", "2x2", complete=False)
/// >>> run.dof, run.leaves is None
/// (1, True)
#[pyfunction]
#[pyo3(signature = (design, region="6x6", *, edge_mm=20.0, t=0.3, complete=true, min_cover=0.5, grips=None, frames=None, settings=None, progress=None, timeout=None, **overrides),
  text_signature = "(design, region='6x6', *, edge_mm=20.0, t=0.3, complete=True, min_cover=0.5, grips=None, frames=24, settings=None, progress=None, timeout=None, **overrides)")]
#[allow(clippy::too_many_arguments)]
pub fn pull_sheet(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    region: &str,
    edge_mm: f64,
    t: f64,
    complete: bool,
    min_cover: f64,
    grips: Option<&Bound<'_, PyAny>>,
    frames: Option<&Bound<'_, PyAny>>,
    settings: Option<&Bound<'_, PyAny>>,
    progress: Option<Bound<'_, PyAny>>,
    timeout: Option<f64>,
    overrides: Option<&Bound<'_, PyDict>>,
) -> PyResult<PySheetPull> {
    let frames = crate::convert::count_or("frames", frames, 0, 24)?;
    let request = SheetPullRequest {
        sheet: sheet_request(region, edge_mm, t, complete, min_cover, settings, overrides)?,
        grips: grips_of(grips)?,
        frames,
    };
    let inner = run_detached(py, design, progress, timeout, |design, progress| {
        lib_pull_sheet(design, &request, progress)
    })?;
    Ok(PySheetPull { inner })
}

crate::pickled_inner!(PySheetPull, "SheetPull");

/// The grips argument: None, or a pair of tile indices (any pair form, see
/// `convert::int_pair`).
fn grips_of(grips: Option<&Bound<'_, PyAny>>) -> PyResult<Option<[usize; 2]>> {
    match grips {
        None => Ok(None),
        Some(g) if g.is_none() => Ok(None),
        Some(g) => match crate::convert::size_pair(g) {
            Some(Ok((a, b))) => Ok(Some([a, b])),
            Some(Err(shown)) => Err(pyo3::exceptions::PyValueError::new_err(format!(
                "grips {shown}: tile indices must be non-negative ints"
            ))),
            None => Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "grips must be a pair (held, pulled) of tile indices, got {}",
                crate::convert::type_name(g)
            ))),
        },
    }
}

//! `isogami.Database`: a design database (made by `isogami explore`) opened read-only and
//! queried with the browser's filters; rows as records or a pandas DataFrame.

use crate::convert::{to_python, type_name};
use crate::design::PyDesign;
use crate::errors;
use crate::query::PyQuery;
use isogami_store::query::MAX_LIMIT;
use isogami_store::{Check, DesignSummary, Facet, Measure, Store, StoredDesign};
use numpy::PyArray1;
use pyo3::exceptions::{PyImportError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::Mutex;

/// One design of a catalogue: every value the browser lists, filters, sorts, facets or plots
/// by. ``to_dict()`` gives them as a dict; ``design()`` the ``Design``.
#[pyclass(name = "Record", module = "isogami", frozen)]
pub struct PyRecord {
    inner: DesignSummary,
    /// Spec string (unique in a database).
    #[pyo3(get)]
    spec: String,
    /// ``"explored"`` or ``"user"``.
    #[pyo3(get)]
    origin: &'static str,
    /// Tiling family, e.g. ``"IH28"``.
    #[pyo3(get)]
    family: String,
    /// Supercell ``(a, b)``.
    #[pyo3(get)]
    cell: (u8, u8),
    /// Tiles in the cell.
    #[pyo3(get)]
    tile_count: u32,
    /// Joint characters, one per unique edge.
    #[pyo3(get)]
    joints: String,
    /// Spec of the topology at default parameters this design was sampled from.
    #[pyo3(get)]
    topology: String,
    /// Shape parameters.
    #[pyo3(get)]
    params: Vec<f64>,
    /// Behaviour class (None when the sheet does not expand).
    #[pyo3(get)]
    behaviour: Option<String>,
    /// Linkage signature such as "2×4-bar + 1×6-bar" (None without a linkage analysis).
    #[pyo3(get)]
    linkage_signature: Option<String>,
    /// Why the deployment ended, e.g. ``"contact_limit"``.
    #[pyo3(get)]
    end_reason: String,
    /// Deployment method.
    #[pyo3(get)]
    method: String,
    /// Degrees of freedom of the closed state.
    #[pyo3(get)]
    dof: u32,
    /// Kerf relative to the mean edge length.
    #[pyo3(get)]
    kerf: f64,
    /// Largest principal expansion reached.
    #[pyo3(get)]
    max_expansion: f64,
    /// Smallest principal expansion reached.
    #[pyo3(get)]
    min_expansion: f64,
    /// Largest area ratio reached.
    #[pyo3(get)]
    max_area_ratio: f64,
    /// Largest tile rotation reached (radians).
    #[pyo3(get)]
    max_tile_rotation: f64,
    /// Smallest Poisson-like ratio over the open frames (None when it never opens).
    #[pyo3(get)]
    poisson_min: Option<f64>,
    /// Largest Poisson-like ratio over the open frames.
    #[pyo3(get)]
    poisson_max: Option<f64>,
    /// Accepted deployment states.
    #[pyo3(get)]
    steps: u64,
    /// Degrees of freedom of the raw 6×6-cell patch as cut (None for user designs).
    #[pyo3(get)]
    finite_raw_dof: Option<u32>,
    /// Fraction of the 6×6-cell patch its completion to a one-DOF sheet keeps (None when it
    /// has none, and for user designs).
    #[pyo3(get)]
    finite_covered: Option<f64>,
    /// t of the most open state (largest area ratio) along the path (None for user designs).
    #[pyo3(get)]
    open_t: Option<f64>,
    /// Area ratio where the path ends (None for user designs).
    #[pyo3(get)]
    end_area_ratio: Option<f64>,
    /// Shape tolerance: vertex displacement relative to the mean edge length under which the
    /// design keeps 95 % of its largest area ratio; 0 for a special design (None: no shape
    /// parameters, or a user design).
    #[pyo3(get)]
    shape_tolerance: Option<f64>,
    /// Largest area ratio kept at the fabrication tolerance (±0.0025 L), as a fraction.
    #[pyo3(get)]
    fabrication_kept: Option<f64>,
    /// True when the design has a one-DOF finite sheet and keeps its opening at the
    /// fabrication tolerance (a family without shape parameters counts as keeping it).
    #[pyo3(get)]
    buildable: bool,
}

impl PyRecord {
    fn new(s: DesignSummary) -> PyRecord {
        PyRecord {
            spec: s.spec.clone(),
            origin: s.origin.as_str(),
            family: s.family.name(),
            cell: (s.cell.a(), s.cell.b()),
            tile_count: s.tile_count,
            joints: s.joints.clone(),
            topology: s.topology.clone(),
            params: s.params.clone(),
            behaviour: s.behaviour.map(|b| b.to_string()),
            linkage_signature: s.linkage_signature.clone(),
            end_reason: s.end_reason.clone(),
            method: s.method.to_string(),
            dof: s.dof,
            kerf: s.kerf,
            max_expansion: s.max_expansion,
            min_expansion: s.min_expansion,
            max_area_ratio: s.max_area_ratio,
            max_tile_rotation: s.max_tile_rotation,
            poisson_min: s.poisson_min,
            poisson_max: s.poisson_max,
            steps: s.steps,
            finite_raw_dof: s.finite_raw_dof,
            finite_covered: s.finite_covered,
            open_t: s.open_t,
            end_area_ratio: s.end_area_ratio,
            shape_tolerance: s.shape_tolerance,
            fabrication_kept: s.fabrication_kept,
            buildable: s.buildable(),
            inner: s,
        }
    }
}

impl PyRecord {
    /// Its spec string.
    pub(crate) fn spec(&self) -> &str {
        &self.spec
    }
}

impl PyStoredDesign {
    /// Its spec string.
    pub(crate) fn spec(&self) -> &str {
        &self.inner.summary.spec
    }
}

#[pymethods]
impl PyRecord {
    /// The design (read from the spec).
    fn design(&self) -> PyResult<PyDesign> {
        crate::design::design(&self.inner.spec)
    }
    /// Every column as a dict (as the browser's API sends it: ``cell`` is ``[a, b]``).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner)
    }
    /// Pickles as its columns exactly (``Record._from_json``) (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let r = crate::pickle::recipe(
            py,
            "Record._from_json",
            vec![crate::pickle::json(py, &self.inner)?],
            &[],
        )?;
        crate::pickle::reduce(py, &r)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Self>().is_ok_and(|o| {
            let o = o.get();
            o.inner == self.inner
        })
    }

    /// A record from ``to_dict()``'s JSON (for unpickling).
    #[staticmethod]
    fn _from_json(text: &str) -> PyResult<PyRecord> {
        serde_json::from_str(text)
            .map(PyRecord::new)
            .map_err(|e| PyValueError::new_err(format!("text: not a record's JSON: {e}")))
    }

    fn __repr__(&self) -> String {
        format!(
            "isogami.Record({}: {}, area ratio up to {:.4})",
            self.inner.spec,
            self.inner
                .behaviour
                .map_or("no class".to_string(), |b| b.to_string()),
            self.inner.max_area_ratio
        )
    }
}

/// A design read back whole: its record, deployment report and linkage analysis.
#[pyclass(name = "StoredDesign", module = "isogami", frozen)]
pub struct PyStoredDesign {
    inner: StoredDesign,
}

#[pymethods]
impl PyStoredDesign {
    /// The catalogue columns.
    #[getter]
    fn record(&self) -> PyRecord {
        PyRecord::new(self.inner.summary.clone())
    }
    /// The stored deployment report (the dict ``isogami deploy --json`` prints).
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.report)
    }
    /// The stored linkage analysis (as ``isogami linkages --json``), or None.
    fn linkages<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.inner
            .linkages
            .as_ref()
            .map(|l| to_python(py, l))
            .transpose()
    }
    /// The specs of the same design on other cells of its family (same shape and path),
    /// stored with this one: the database keeps one row for them.
    #[getter]
    fn other_cells(&self) -> Vec<String> {
        self.inner.other_cells.clone()
    }
    /// Pickles as its record, report, linkages and other cells exactly
    /// (``StoredDesign._from_json``) (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let r = crate::pickle::recipe(
            py,
            "StoredDesign._from_json",
            vec![
                crate::pickle::json(py, &self.inner.summary)?,
                crate::pickle::json(py, &self.inner.report)?,
                crate::pickle::json(py, &self.inner.linkages)?,
                crate::pickle::json(py, &self.inner.other_cells)?,
            ],
            &[],
        )?;
        crate::pickle::reduce(py, &r)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Self>().is_ok_and(|o| {
            let o = o.get();
            crate::pickle::same(&o.inner.summary, &self.inner.summary)
                && crate::pickle::same(&o.inner.report, &self.inner.report)
                && o.inner.linkages == self.inner.linkages
                && o.inner.other_cells == self.inner.other_cells
        })
    }

    /// A stored design from the JSON of its parts (for unpickling).
    #[staticmethod]
    #[pyo3(signature = (summary, report, linkages, other_cells = "[]"))]
    fn _from_json(
        summary: &str,
        report: &str,
        linkages: &str,
        other_cells: &str,
    ) -> PyResult<PyStoredDesign> {
        let bad = |e: serde_json::Error| {
            PyValueError::new_err(format!("not a stored design's JSON: {e}"))
        };
        Ok(PyStoredDesign {
            inner: StoredDesign {
                summary: serde_json::from_str(summary).map_err(bad)?,
                report: serde_json::from_str(report).map_err(bad)?,
                linkages: serde_json::from_str(linkages).map_err(bad)?,
                other_cells: serde_json::from_str(other_cells).map_err(bad)?,
            },
        })
    }

    fn __repr__(&self) -> String {
        format!("isogami.StoredDesign({})", self.inner.summary.spec)
    }
}

/// A design database opened for reading only (nothing is ever written or created).
///
/// ``check`` is ``"quick"`` (SQLite's quick_check, default) or ``"full"`` (integrity check and
/// every row's checksum and stored JSON). Raises ``StoreError`` for a missing, foreign,
/// damaged or other-version file. Queries take a ``Query`` and/or the browser's filter
/// keywords (see ``Query``). Usable as a context manager; ``close()`` releases the file.
#[pyclass(name = "Database", module = "isogami", frozen)]
pub struct PyDatabase {
    path: PathBuf,
    store: Mutex<Option<Store>>,
}

impl PyDatabase {
    /// The file's path.
    pub(crate) fn file(&self) -> PathBuf {
        self.path.clone()
    }

    /// Runs `f` on the open store with the GIL released (for the other modules' calls).
    pub(crate) fn with_store<T: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&Store) -> isogami_store::StoreResult<T> + Send,
    ) -> PyResult<T> {
        self.with(py, f)
    }

    /// Runs `f` on the open store with the GIL released.
    fn with<T: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&Store) -> isogami_store::StoreResult<T> + Send,
    ) -> PyResult<T> {
        let shown = self.path.display().to_string();
        py.detach(|| {
            let guard = self
                .store
                .lock()
                .map_err(|_| errors::StoreError::new_err("the database handle was poisoned"))?;
            let store = guard
                .as_ref()
                .ok_or_else(|| PyValueError::new_err(format!("{shown}: database is closed")))?;
            f(store).map_err(|e| errors::store(e, &shown))
        })
    }

    /// Every row of a query (all pages when it has no limit).
    fn rows(&self, py: Python<'_>, q: &PyQuery) -> PyResult<Vec<DesignSummary>> {
        let mut query = q.inner.clone();
        self.with(py, move |store| {
            let mut out = Vec::new();
            loop {
                let wanted = q.limit.map(|n| u64::from(n) - out.len() as u64);
                if let Some(w) = wanted {
                    query.limit = u32::try_from(w.min(u64::from(MAX_LIMIT))).unwrap_or(MAX_LIMIT);
                }
                let page = store.page(&query)?;
                let got = page.rows.len();
                out.extend(page.rows);
                let done = got == 0
                    || q.limit.is_some_and(|n| out.len() as u64 >= u64::from(n))
                    || query.offset + got as u64 >= page.total;
                if done {
                    return Ok(out);
                }
                query.offset += got as u64;
            }
        })
    }
}

#[pymethods]
impl PyDatabase {
    #[new]
    #[pyo3(signature = (path, check="quick"))]
    fn new(py: Python<'_>, path: PathBuf, check: &str) -> PyResult<PyDatabase> {
        let check = match check {
            "quick" => Check::Quick,
            "full" => Check::Full,
            other => {
                return Err(PyValueError::new_err(format!(
                    "check must be 'quick' or 'full', got '{}'",
                    other.escape_debug()
                )))
            }
        };
        let shown = path.display().to_string();
        let store = py
            .detach(|| Store::open_read(&path, check))
            .map_err(|e| errors::store(e, &shown))?;
        Ok(PyDatabase {
            path,
            store: Mutex::new(Some(store)),
        })
    }

    /// The file's path.
    #[getter]
    fn path(&self) -> PathBuf {
        self.path.clone()
    }

    /// The designs matching a query, in its order (default: by spec), as ``Record`` objects.
    /// Without a limit every matching design is returned.
    #[pyo3(signature = (query=None, **filters))]
    fn designs(
        &self,
        py: Python<'_>,
        query: Option<&Bound<'_, PyAny>>,
        filters: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Vec<PyRecord>> {
        let q = PyQuery::of(query, filters)?;
        Ok(self.rows(py, &q)?.into_iter().map(PyRecord::new).collect())
    }

    /// The designs matching a query as a pandas DataFrame, one row per design and one column
    /// per record field (``cell`` as ``"AxB"``). Needs pandas (raises ``ImportError``
    /// without it; ``designs()`` gives the same rows as records).
    #[pyo3(signature = (query=None, **filters))]
    fn dataframe<'py>(
        &self,
        py: Python<'py>,
        query: Option<&Bound<'py, PyAny>>,
        filters: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas").map_err(|_| {
            PyImportError::new_err(
                "Database.dataframe needs pandas (pip install pandas); \
                 Database.designs returns the same rows as records",
            )
        })?;
        let q = PyQuery::of(query, filters)?;
        let rows = self.rows(py, &q)?;
        // Shape parameters also as one float column each (param_0, param_1, ...; NaN where
        // a family has fewer), so that they can be filtered and plotted like any column.
        let width = rows.iter().map(|r| r.params.len()).max().unwrap_or(0);
        let records = PyList::empty(py);
        for r in &rows {
            let d = to_python(py, r)?;
            d.set_item("cell", r.cell.to_string())?;
            for k in 0..width {
                d.set_item(
                    format!("param_{k}"),
                    r.params.get(k).copied().unwrap_or(f64::NAN),
                )?;
            }
            records.append(d)?;
        }
        let mut columns: Vec<String> = COLUMNS.iter().map(|c| c.to_string()).collect();
        columns.extend((0..width).map(|k| format!("param_{k}")));
        let kwargs = PyDict::new(py);
        kwargs.set_item("columns", columns)?;
        pandas
            .getattr("DataFrame")?
            .call_method("from_records", (records,), Some(&kwargs))
    }

    /// Number of designs matching a query (limit and offset ignored).
    #[pyo3(signature = (query=None, **filters))]
    fn count(
        &self,
        py: Python<'_>,
        query: Option<&Bound<'_, PyAny>>,
        filters: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<u64> {
        let mut q = PyQuery::of(query, filters)?.inner;
        q.limit = 1;
        q.offset = 0;
        self.with(py, move |s| s.page(&q).map(|p| p.total))
    }

    /// Designs per value of ``facet`` (``"family"``, ``"cell"``, ``"tile_count"``,
    /// ``"behaviour"``, ``"linkage_signature"``, ``"end_reason"``, ``"origin"``) under every
    /// filter except the facet's own selection, most frequent first: a list of
    /// ``(value, count)``. Values as in the browser's API (``cell`` as ``[a, b]``,
    /// ``behaviour`` None for unclassified).
    #[pyo3(signature = (facet, query=None, **filters))]
    fn facet_counts<'py>(
        &self,
        py: Python<'py>,
        facet: &str,
        query: Option<&Bound<'py, PyAny>>,
        filters: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Vec<(Bound<'py, PyAny>, u64)>> {
        let f = Facet::ALL
            .into_iter()
            .find(|f| f.name() == facet)
            .ok_or_else(|| {
                let names: Vec<&str> = Facet::ALL.iter().map(|f| f.name()).collect();
                errors::QueryError::new_err(format!(
                    "unknown facet '{}'; facets are: {}",
                    facet.escape_debug(),
                    names.join(", ")
                ))
            })?;
        let q = PyQuery::of(query, filters)?.inner;
        let counts = self.with(py, move |s| s.facet_counts(&q, f))?;
        counts
            .into_iter()
            .map(|c| Ok((to_python(py, &c.value)?, c.count)))
            .collect()
    }

    /// Measures ``x`` and ``y`` (names as for ``range``) of every design matching a query that
    /// has both, at most ``limit``: a dict with ``spec`` (list), ``x`` and ``y`` (numpy
    /// arrays).
    #[pyo3(signature = (x, y, query=None, limit=100_000, **filters))]
    fn scatter<'py>(
        &self,
        py: Python<'py>,
        x: &str,
        y: &str,
        query: Option<&Bound<'py, PyAny>>,
        limit: u32,
        filters: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mx: Measure = x.parse().map_err(errors::query)?;
        let my: Measure = y.parse().map_err(errors::query)?;
        let q = PyQuery::of(query, filters)?.inner;
        let points = self.with(py, move |s| s.scatter(&q, mx, my, limit))?;
        let d = PyDict::new(py);
        d.set_item(
            "spec",
            points.iter().map(|p| p.spec.clone()).collect::<Vec<_>>(),
        )?;
        d.set_item(
            "x",
            PyArray1::from_vec(py, points.iter().map(|p| p.x).collect()),
        )?;
        d.set_item(
            "y",
            PyArray1::from_vec(py, points.iter().map(|p| p.y).collect()),
        )?;
        Ok(d)
    }

    /// One design read back whole (record, report, linkages), or None when the database does
    /// not hold ``spec``. ``spec`` may be a ``Design``.
    fn design(&self, py: Python<'_>, spec: &Bound<'_, PyAny>) -> PyResult<Option<PyStoredDesign>> {
        let spec = if let Ok(d) = spec.cast::<PyDesign>() {
            d.get().inner.to_string()
        } else {
            spec.extract::<String>().map_err(|_| {
                PyTypeError::new_err(format!(
                    "spec must be a str or an isogami.Design, got {}",
                    type_name(spec)
                ))
            })?
        };
        Ok(self
            .with(py, move |s| s.design(&spec))?
            .map(|inner| PyStoredDesign { inner }))
    }

    /// Work units, designs, per-stage and per-family counts, as ``isogami db stats --json``.
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let stats = self.with(py, |s| s.stats())?;
        to_python(py, &stats)
    }

    /// The exploration settings the database was made with (a dict), or None.
    #[getter]
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let text = self.with(py, |s| s.settings())?;
        text.map(|t| py.import("json")?.call_method1("loads", (t,)))
            .transpose()
    }

    /// The isogami version that made the database, or None.
    #[getter]
    fn tool_version(&self, py: Python<'_>) -> PyResult<Option<String>> {
        self.with(py, |s| s.tool_version())
    }

    /// Closes the file; later queries raise ``ValueError``.
    fn close(&self) -> PyResult<()> {
        if let Ok(mut g) = self.store.lock() {
            g.take();
        }
        Ok(())
    }

    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        let n = self.with(py, |s| s.design_count())?;
        Ok(usize::try_from(n).unwrap_or(usize::MAX))
    }

    fn __enter__(slf: Bound<'_, Self>) -> Bound<'_, Self> {
        slf
    }

    #[pyo3(signature = (*_args))]
    fn __exit__(&self, _args: &Bound<'_, pyo3::types::PyTuple>) -> PyResult<bool> {
        self.close()?;
        Ok(false)
    }

    fn __repr__(&self) -> String {
        format!("isogami.Database({:?})", self.path.display().to_string())
    }
}

/// The DataFrame's columns, in the record's order.
const COLUMNS: &[&str] = &[
    "spec",
    "origin",
    "family",
    "cell",
    "tile_count",
    "joints",
    "topology",
    "params",
    "behaviour",
    "linkage_signature",
    "end_reason",
    "method",
    "dof",
    "kerf",
    "max_expansion",
    "min_expansion",
    "max_area_ratio",
    "max_tile_rotation",
    "poisson_min",
    "poisson_max",
    "steps",
    "finite_raw_dof",
    "finite_covered",
    "open_t",
    "end_area_ratio",
    "shape_tolerance",
    "fabrication_kept",
];

/// Opens a design database for reading (see ``Database``).
#[pyfunction]
#[pyo3(signature = (path, check="quick"))]
pub fn open_database(py: Python<'_>, path: PathBuf, check: &str) -> PyResult<PyDatabase> {
    PyDatabase::new(py, path, check)
}

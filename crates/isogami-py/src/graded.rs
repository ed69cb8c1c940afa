//! `isogami.graded` / `isogami.GradedRun` and `isogami.load_graded`: a design's finite sheet
//! graded so that it opens into a target outline (typed, or an SVG file's) or by a field of
//! area ratio, and the check that it does (the library's `api::graded_sheet`), as numpy
//! arrays, with the JSON `isogami graded --json` prints; `GradedRun.export` writes the sheet in
//! every export format (`export::export_graded`, as `isogami export --sheet`).

use crate::convert::{array, count_or, design_of, int_array, to_python, type_name};
use crate::errors;
use crate::export::{export_error, files_to_python, scale_of, state_of, Given};
use crate::progress::Watch;
use isogami::api::{graded_sheet, GradedRun};
use isogami::export::{export_graded, read_graded, ExportError, Format, GradedPatchRequest};
use isogami::graded::{
    outline_from_svg, parse_target, AreaField, GradedRequest, GradedSheet, Target,
};
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::{PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// A graded sheet, how its optimisation went and whether it opens along one motion (what
/// ``isogami graded --json`` prints, ``to_json()`` word for word).
///
/// The sheet: ``nodes`` (k, 2), the closed positions of the corners tiles share; tiles
/// ``tiles`` (n, 3) as (i, j, tile) — tile ``tile`` of the design's cell in the copy at
/// ``i·u + j·w`` — with their corners ``tile_nodes`` (rows of ``nodes``, counter-clockwise);
/// pins ``joints`` (m, 3) as (a, b, node); the opened state ``poses`` (n, 3) as (x, y, θ) of
/// each tile's first corner and its turn from closed; ``closed`` and ``opened``, one (c, 2)
/// polygon per tile; ``states`` (s, n, 3), the poses part of the way open the pins close in
/// too. Lengths are in units of the design's mean edge length (``length_scale`` in the
/// design's tiling units), the opened sheet centred on the origin. A field target's cells:
/// ``field_targets`` and ``field_ratios`` (c,), the area ratio asked and achieved, and
/// ``field_cells`` (c, 4, 2), each cell's quadrilateral opened; ``max_field_error``.
#[pyclass(name = "GradedRun", module = "isogami", frozen)]
pub struct PyGradedRun {
    sheet: GradedSheet,
    report: Value,
    path: Value,
    /// The verdict and the whole outline's fit (the JSON's `verdict` and `fit`; null in a
    /// file written before they were measured).
    verdict: Value,
    fit: Value,
    /// A field target's cells (the JSON's `field`; empty for an outline).
    field: Vec<Value>,
    /// The JSON, as the CLI prints it (without the final newline).
    text: String,
}

impl PyGradedRun {
    fn new(run: &GradedRun) -> PyResult<PyGradedRun> {
        let json =
            |e: serde_json::Error| errors::IsogamiError::new_err(format!("JSON output: {e}"));
        Ok(PyGradedRun {
            sheet: run.sheet.clone(),
            report: serde_json::to_value(&run.report).map_err(json)?,
            path: serde_json::to_value(&run.path).map_err(json)?,
            verdict: serde_json::to_value(&run.verdict).map_err(json)?,
            fit: serde_json::to_value(run.fit).map_err(json)?,
            field: run
                .field
                .iter()
                .map(serde_json::to_value)
                .collect::<Result<_, _>>()
                .map_err(json)?,
            text: serde_json::to_string_pretty(run).map_err(json)?,
        })
    }

    /// A run from its JSON: `sheet` read and checked by the library, `report` and `path`
    /// kept as they are (objects), the text itself as `to_json()`'s.
    fn from_text(text: &str, source: &str) -> PyResult<PyGradedRun> {
        let bad = |m: String| {
            errors::library(isogami::graded::GradedError::BadSheet(format!("{source}: {m}")).into())
        };
        let mut whole: Value =
            serde_json::from_str(text).map_err(|e| bad(format!("not JSON ({e})")))?;
        let mut part = |key: &str| -> PyResult<Value> {
            match whole.get_mut(key).map(Value::take) {
                Some(v @ Value::Object(_)) => Ok(v),
                _ => Err(bad(format!(
                    "no \"{key}\" object: not the JSON of `isogami graded --out`"
                ))),
            }
        };
        let (sheet, report, path) = (part("sheet")?, part("report")?, part("path")?);
        let mut optional = |key: &str| whole.get_mut(key).map_or(Value::Null, Value::take);
        let (verdict, fit) = (optional("verdict"), optional("fit"));
        let field = match whole.get_mut("field").map(Value::take) {
            None => Vec::new(),
            Some(Value::Array(cells)) => cells,
            Some(_) => return Err(bad("its \"field\" is not a list of cells".into())),
        };
        let sheet: GradedSheet =
            serde_json::from_value(sheet).map_err(|e| bad(format!("its sheet ({e})")))?;
        sheet.validate().map_err(|e| errors::library(e.into()))?;
        Ok(PyGradedRun {
            sheet,
            report,
            path,
            verdict,
            fit,
            field,
            text: text.trim_end().to_string(),
        })
    }

    fn polygons<'py>(
        &self,
        py: Python<'py>,
        polygon: impl Fn(usize) -> Vec<isogami::math::Vec2>,
    ) -> PyResult<Vec<Bound<'py, PyArray2<f64>>>> {
        (0..self.sheet.tiles.len())
            .map(|i| {
                let p = polygon(i);
                array(
                    py,
                    (p.len(), 2),
                    p.iter().flat_map(|v| [v.x, v.y]).collect(),
                )
            })
            .collect()
    }

    /// One number of every field cell (`key`), NaN where missing.
    fn field_numbers(&self, key: &str) -> Vec<f64> {
        self.field
            .iter()
            .map(|c| c.get(key).and_then(Value::as_f64).unwrap_or(f64::NAN))
            .collect()
    }

    fn number(&self, key: &str) -> f64 {
        self.report
            .get(key)
            .and_then(Value::as_f64)
            .unwrap_or(f64::NAN)
    }
}

fn poses_rows(poses: &[isogami::graded::OpenedPose]) -> Vec<f64> {
    poses.iter().flat_map(|p| [p.x, p.y, p.theta]).collect()
}

#[pymethods]
impl PyGradedRun {
    /// The design's spec string.
    #[getter]
    fn design(&self) -> String {
        self.sheet.design.clone()
    }
    /// The design's mean edge length in its tiling units: the unit of every length here.
    #[getter]
    fn length_scale(&self) -> f64 {
        self.sheet.length_scale
    }
    /// Closed positions of the shared corners, shape (k, 2).
    #[getter]
    fn nodes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let n = &self.sheet.nodes;
        array(py, (n.len(), 2), n.iter().flatten().copied().collect())
    }
    /// The tiles, shape (n, 3): (i, j, tile).
    #[getter]
    fn tiles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let t = &self.sheet.tiles;
        let v = t
            .iter()
            .flat_map(|t| [i64::from(t.cell[0]), i64::from(t.cell[1]), t.tile as i64])
            .collect();
        int_array(py, (t.len(), 3), v)
    }
    /// Each tile's corners as rows of ``nodes``, counter-clockwise: one int array per tile.
    #[getter]
    fn tile_nodes<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, numpy::PyArray1<i64>>>> {
        self.sheet
            .tiles
            .iter()
            .map(|t| {
                int_array(
                    py,
                    t.nodes.len(),
                    t.nodes.iter().map(|&n| n as i64).collect(),
                )
            })
            .collect()
    }
    /// The pins, shape (m, 3): (a, b, node), a and b rows of ``tiles``.
    #[getter]
    fn joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let j = &self.sheet.joints;
        let v = j
            .iter()
            .flat_map(|j| [j.a as i64, j.b as i64, j.node as i64])
            .collect();
        int_array(py, (j.len(), 3), v)
    }
    /// The opened state: each tile's (x, y, θ), shape (n, 3) — where its first corner is and
    /// how far it turned from closed (radians, counter-clockwise).
    #[getter]
    fn poses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        array(
            py,
            (self.sheet.opened.len(), 3),
            poses_rows(&self.sheet.opened),
        )
    }
    /// The states part of the way open the pins close in too, least open first, shape
    /// (s, n, 3) as ``poses``.
    #[getter]
    fn states<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let s = &self.sheet.path;
        let v = s.iter().flat_map(|p| poses_rows(p)).collect();
        array(py, (s.len(), self.sheet.tiles.len(), 3), v)
    }
    /// Each tile's closed polygon: one (c, 2) array per tile.
    #[getter]
    fn closed<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyArray2<f64>>>> {
        self.polygons(py, |i| self.sheet.closed_polygon(i))
    }
    /// Each tile's opened polygon: one (c, 2) array per tile.
    #[getter]
    fn opened<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyArray2<f64>>>> {
        self.polygons(py, |i| self.sheet.opened_polygon(i))
    }
    /// The target outline at the scale it was fitted at, shape (k, 2), counter-clockwise.
    #[getter]
    fn target<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let points: Vec<f64> = self
            .report
            .get("target")
            .and_then(Value::as_array)
            .map(|a| {
                a.iter()
                    .flat_map(|p| [&p[0], &p[1]])
                    .filter_map(Value::as_f64)
                    .collect()
            })
            .unwrap_or_default();
        array(py, (points.len() / 2, 2), points)
    }
    /// A field target: the area ratio each measured cell is asked for, shape (c,) (empty for
    /// an outline target).
    #[getter]
    fn field_targets<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.field_numbers("target"))
    }
    /// A field target: each measured cell's opened area over its closed area, shape (c,), in
    /// the order of ``field_targets``.
    #[getter]
    fn field_ratios<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.field_numbers("ratio"))
    }
    /// A field target: each measured cell's quadrilateral (four neighbouring cells' reference
    /// corners) in the opened state, shape (c, 4, 2).
    #[getter]
    fn field_cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let v: Vec<f64> = self
            .field
            .iter()
            .flat_map(|c| {
                (0..4).flat_map(move |k| {
                    (0..2).map(move |d| c["opened"][k][d].as_f64().unwrap_or(f64::NAN))
                })
            })
            .collect();
        array(py, (self.field.len(), 4, 2), v)
    }
    /// A field target: the largest difference between a cell's achieved and asked area ratio
    /// (the report's ``max_field_error``); None for an outline target.
    #[getter]
    fn max_field_error(&self) -> Option<f64> {
        self.report.get("max_field_error").and_then(Value::as_f64)
    }
    /// Whether the graded sheet opens along one motion from closed to the opened state
    /// (closed pins, one DOF, no overlap at every state of the path check).
    #[getter]
    fn reached(&self) -> bool {
        self.path
            .get("reached")
            .and_then(Value::as_bool)
            .unwrap_or(false)
    }
    /// Largest relative distance of the opened outline from the target.
    #[getter]
    fn max_outline_error(&self) -> f64 {
        self.number("max_outline_error")
    }
    /// Largest distance between the two opened positions of a pinned corner (length scales).
    #[getter]
    fn joint_gap(&self) -> f64 {
        self.number("joint_gap")
    }
    /// The optimisation and the fit as a dict (the JSON's ``report``).
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.report)
    }
    /// Whether the sheet opens along one motion and meets its target, with the sizes, as a
    /// dict (the JSON's ``verdict``: ``opens``, ``meets_target``, ``target_fraction``,
    /// ``error``, ``tolerance``, ``deepest_overlap``, ``widest_pin_gap``, ``sheet_opening``,
    /// ``periodic_opening``, ``text`` — the line ``isogami graded`` prints — and more); None
    /// for a file written before verdicts.
    fn verdict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.verdict)
    }
    /// The whole opened outline against the target as a dict (the JSON's ``fit``:
    /// ``hausdorff``, ``mean``, ``inside``, ``outside`` relative to the target's equivalent
    /// ``radius``, and the ``worst`` point); None for a field target or an older file.
    fn fit<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.fit)
    }
    /// The sheet opens along one motion and meets its target (the verdict's ``opens`` and
    /// ``meets_target``); False for a file written before verdicts.
    #[getter]
    fn passed(&self) -> bool {
        let flag = |k: &str| self.verdict.get(k).and_then(Value::as_bool) == Some(true);
        flag("opens") && flag("meets_target")
    }
    /// The check of the path from the opened state back to the closed tiling as a dict (the
    /// JSON's ``path``: ``states``, ``closed_spread``, ``reached``, and the measures the
    /// states were judged by, ``pin_tolerance`` and ``dof_from_opening``).
    fn path_check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.path)
    }
    /// The whole run as JSON: what ``isogami graded --json`` prints (without its final
    /// newline); a loaded run's is its file's.
    fn to_json(&self) -> String {
        self.text.clone()
    }
    /// Writes the run to ``path`` as ``isogami graded --out`` does (``to_json()`` and a
    /// newline), replacing the file whole or leaving it as it was.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let contents = self.text.clone() + "\n";
        py.detach(|| write_whole(&path, contents.as_bytes()))
            .map_err(|e| PyOSError::new_err(format!("cannot write {}: {e}", path.display())))
    }
    /// Writes the graded sheet in millimetres in ``format`` (``export_formats()`` lists them)
    /// and returns the file contents: ``bytes`` for one file, a dict ``{file name: bytes}`` for
    /// a folder (``"kirigami-sim"``) — what ``isogami export --sheet FILE`` writes from this
    /// run's file, byte for byte (the sheet is read back from ``to_json()`` as the CLI reads
    /// the file).
    ///
    /// The scale is ``edge_mm`` (the closed sheet's mean tile edge, default 20 mm) or
    /// ``width_mm`` (its width at the state); ``t`` the opening (a number in [0, 1], the path
    /// check's state of nearest opening; 0 closed, the default, what a laser cuts) or
    /// ``"open"`` (the optimised state); ``frames`` the states animated formats keep (2..100,
    /// default 11). The laser and 3D-print settings, ``creator`` and the errors are
    /// ``isogami.export``'s; ``timeout`` seconds and Ctrl-C stop a print's solid. The GIL is
    /// released while it runs.
    #[pyo3(signature = (
        format, *, edge_mm=None, width_mm=None, t=None, frames=None, material=None,
        hinge_mm=None, kerf_mm=None, thickness_mm=None, margin_mm=None, stroke_mm=None,
        cut_colour=None, score_colour=None, engrave_colour=None, labels=false, gap_mm=None,
        lamella_mm=None, nozzle_mm=None, creator=None, timeout=None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn export<'py>(
        &self,
        py: Python<'py>,
        format: &str,
        edge_mm: Option<f64>,
        width_mm: Option<f64>,
        t: Option<&Bound<'py, PyAny>>,
        frames: Option<&Bound<'py, PyAny>>,
        material: Option<&str>,
        hinge_mm: Option<f64>,
        kerf_mm: Option<f64>,
        thickness_mm: Option<f64>,
        margin_mm: Option<f64>,
        stroke_mm: Option<f64>,
        cut_colour: Option<String>,
        score_colour: Option<String>,
        engrave_colour: Option<String>,
        labels: bool,
        gap_mm: Option<f64>,
        lamella_mm: Option<f64>,
        nozzle_mm: Option<f64>,
        creator: Option<String>,
        timeout: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let format: Format = format
            .parse()
            .map_err(|e: ExportError| errors::ExportError::new_err(e.to_string()))?;
        let defaults = GradedPatchRequest::default();
        let request = GradedPatchRequest {
            scale: scale_of(edge_mm, width_mm, defaults.scale)?,
            state: match t {
                Some(t) if !t.is_none() => state_of(t)?,
                _ => defaults.state,
            },
            frames: count_or("frames", frames, 0, defaults.frames)?,
        };
        let options = Given::new(
            material,
            hinge_mm,
            kerf_mm,
            thickness_mm,
            margin_mm,
            stroke_mm,
            cut_colour,
            score_colour,
            engrave_colour,
            labels,
            gap_mm,
            lamella_mm,
            nozzle_mm,
            creator,
        )
        .options(format)?;
        let text = self.text.clone();
        let watch = Mutex::new(Watch::new(None, timeout)?);
        let result = py.detach(|| {
            let lock = || watch.lock().unwrap_or_else(|e| e.into_inner());
            let input = read_graded(&text)?;
            isogami::stop::watched(&mut |_| lock().poll(), 0, |keep_going| {
                export_graded(
                    &input.sheet,
                    input.path.as_ref(),
                    &request,
                    format,
                    &options,
                    keep_going,
                )
            })
        });
        let watch = watch.into_inner().unwrap_or_else(|e| e.into_inner());
        match result {
            Ok((_, files)) => files_to_python(py, files),
            Err(e) => Err(export_error(e, watch)),
        }
    }
    /// A run from ``to_json()``'s text (for unpickling).
    #[staticmethod]
    fn _from_json(text: &str) -> PyResult<PyGradedRun> {
        PyGradedRun::from_text(text, "text")
    }
    /// Pickles as its JSON exactly (``GradedRun._from_json``) (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let r = crate::pickle::recipe(
            py,
            "GradedRun._from_json",
            vec![self.text.clone().into_pyobject(py)?.into_any()],
            &[],
        )?;
        crate::pickle::reduce(py, &r)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Self>()
            .is_ok_and(|o| o.get().text == self.text)
    }

    fn __repr__(&self) -> String {
        let fit = match self.max_field_error() {
            Some(e) => format!("field within {e:.4}"),
            None => format!(
                "outline within {:.2} %",
                100.0 * self.number("max_outline_error")
            ),
        };
        format!(
            "GradedRun({}: {} tiles, {fit}, {})",
            self.sheet.design,
            self.sheet.tiles.len(),
            if self.reached() {
                "opens along one motion"
            } else {
                "does not open along one motion"
            }
        )
    }
}

/// Writes `contents` beside `path` and renames it into place.
fn write_whole(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("not a file name"))?;
    let mut staged = name.to_os_string();
    staged.push(format!(".{}.partial", std::process::id()));
    let staged = path.with_file_name(staged);
    let written = std::fs::write(&staged, contents).and_then(|()| std::fs::rename(&staged, path));
    if written.is_err() {
        let _ = std::fs::remove_file(&staged);
    }
    written
}

/// A target's text as ``isogami graded --target`` reads it: ``disc``, ``ellipse:A,B``,
/// ``polygon:x,y;...``, ``field:FROM,TO[,DEGREES]`` or ``@PATH`` of an SVG file.
fn target_of(target: &str) -> PyResult<Target> {
    let read = match target.strip_prefix('@') {
        None => parse_target(target),
        Some(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| {
                errors::library(
                    isogami::graded::GradedError::BadTarget(format!("cannot read {path}: {e}"))
                        .into(),
                )
            })?;
            outline_from_svg(&text).map(Target::Outline)
        }
    };
    read.map_err(|e| errors::library(e.into()))
}

/// The ``field`` keyword: ``(from, to)`` or ``(from, to, degrees)``, checked by the library.
fn field_of(field: &Bound<'_, PyAny>) -> PyResult<Target> {
    let numbers: Vec<f64> = field.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "field must be (from, to) or (from, to, degrees), got {}",
            type_name(field)
        ))
    })?;
    let (from, to, direction_degrees) = match numbers[..] {
        [from, to] => (from, to, 0.0),
        [from, to, degrees] => (from, to, degrees),
        _ => {
            return Err(PyTypeError::new_err(format!(
                "field must be (from, to) or (from, to, degrees), got {} numbers",
                numbers.len()
            )))
        }
    };
    AreaField {
        from,
        to,
        direction_degrees,
    }
    .validated()
    .map(Target::Field)
    .map_err(|e| errors::library(e.into()))
}

/// The region: (rows, cols) or ``"RxC"``.
fn region_of(region: &Bound<'_, PyAny>) -> PyResult<(usize, usize)> {
    if let Ok(text) = region.extract::<String>() {
        let cells = text.split_once(['x', 'X']).and_then(|(r, c)| {
            Some((
                r.trim().parse::<usize>().ok()?,
                c.trim().parse::<usize>().ok()?,
            ))
        });
        return cells.ok_or_else(|| {
            PyValueError::new_err(format!(
                "region {text:?} is not RxC (e.g. \"3x3\") or (rows, cols)"
            ))
        });
    }
    match crate::convert::size_pair(region) {
        Some(Ok(pair)) => Ok(pair),
        Some(Err(shown)) => Err(PyValueError::new_err(format!(
            "region {shown}: rows and columns must be non-negative ints"
        ))),
        None => Err(PyTypeError::new_err(format!(
            "region must be (rows, cols) or \"RxC\", got {}",
            type_name(region)
        ))),
    }
}

/// Grades ``design``'s finite sheet of ``region`` cells — (rows, cols) or ``"RxC"`` — so that
/// it opens into ``target``: ``"disc"``, ``"ellipse:A,B"``, ``"polygon:x,y;x,y;..."`` (star-
/// shaped about its centroid) or ``"@outline.svg"``, the one closed shape of an SVG file
/// (as ``isogami graded --target``); scaled to the area the design's own sheet covers open.
/// Or by a field of area ratio instead of an outline: ``target="field:FROM,TO[,DEGREES]"``
/// or ``field=(from, to)`` / ``(from, to, degrees)`` — a linear ramp from ``from`` at one end of
/// the sheet to ``to`` at the other along ``degrees`` (counter-clockwise from +x, default 0),
/// met cell by cell (``field_targets``, ``field_ratios``, ``max_field_error``; at least 2×2
/// cells).
/// ``t``: the opened state as the periodic deployment's t in (0, 1] (None: the state of
/// largest area); ``states``: opened states the pins must close in (1 to 16); ``iterations``
/// of the optimisation (the defaults are the library's, as the CLI's). Then checks that the
/// graded closed tiling opens along one motion.
///
/// ``progress(iteration, cost)`` is called after every accepted step of the optimisation;
/// returning False (or raising) stops the run, as do ``timeout`` seconds and Ctrl-C
/// (``CancelledError``, or the callback's own exception, or KeyboardInterrupt). The GIL is
/// released while it runs.
///
/// Returns a ``GradedRun``. Raises ``FiniteError`` for a bad target, field, SVG file, region or
/// sheet (the library's one-line message), ``SettingsError`` for a setting out of range,
/// ``TypeError`` for ``field`` with a target other than the default.
///
/// >>> run = isogami.graded("rotating-squares", (2, 2), "ellipse:1.3,1", iterations=60)
/// >>> run.poses.shape, len(run.opened)
/// ((16, 3), 16)
#[pyfunction]
#[pyo3(signature = (design, region=None, target="disc", t=None, states=None, iterations=None, *, field=None, tolerance=None, fall_back=true, progress=None, timeout=None),
  text_signature = "(design, region=(3, 3), target='disc', t=None, states=8, iterations=200, *, field=None, tolerance=None, fall_back=True, progress=None, timeout=None)")]
#[allow(clippy::too_many_arguments)]
pub fn graded(
    py: Python<'_>,
    design: &Bound<'_, PyAny>,
    region: Option<&Bound<'_, PyAny>>,
    target: &str,
    t: Option<f64>,
    states: Option<&Bound<'_, PyAny>>,
    iterations: Option<&Bound<'_, PyAny>>,
    field: Option<&Bound<'_, PyAny>>,
    tolerance: Option<f64>,
    fall_back: bool,
    progress: Option<Bound<'_, PyAny>>,
    timeout: Option<f64>,
) -> PyResult<PyGradedRun> {
    let target = match field.filter(|f| !f.is_none()) {
        Some(_) if target.trim() != "disc" => {
            return Err(PyTypeError::new_err(format!(
                "give target or field, not both (target {target:?})"
            )))
        }
        Some(f) => field_of(f)?,
        None => target_of(target)?,
    };
    let (rows, cols) = match region {
        Some(r) if !r.is_none() => region_of(r)?,
        _ => (3, 3),
    };
    let defaults = GradedRequest::default();
    let mut request = GradedRequest {
        design: design_of(design)?.to_string(),
        rows,
        cols,
        t,
        states: count_or("states", states, 0, defaults.states)?,
        tolerance,
        fall_back,
        ..defaults
    }
    .with_target(target);
    request.solve.max_iterations =
        count_or("iterations", iterations, 1, request.solve.max_iterations)?;
    let progress = progress.filter(|p| !p.is_none());
    if let Some(cb) = &progress {
        if !cb.is_callable() {
            return Err(PyTypeError::new_err(format!(
                "progress must be callable (iteration, cost) -> bool | None, got {}",
                type_name(cb)
            )));
        }
    }
    // The optimisation calls back on the work's thread; the caller's thread polls for the
    // timeout and Ctrl-C meanwhile (`stop::watched`), so the setup and the path check stop too.
    let watch = Mutex::new(Watch::new(progress, timeout)?);
    let result = py.detach(|| {
        let lock = || watch.lock().unwrap_or_else(|e| e.into_inner());
        isogami::stop::watched(&mut |_| lock().poll(), 0, |keep_going| {
            graded_sheet(
                &request,
                &mut |p| {
                    let (iteration, cost) = (p.iteration, p.cost);
                    lock().tick_args(|py| (iteration, cost).into_pyobject(py))
                },
                keep_going,
            )
        })
    });
    let watch = watch.into_inner().unwrap_or_else(|e| e.into_inner());
    PyGradedRun::new(&watch.finish(result)?)
}

/// The run ``GradedRun.save`` or ``isogami graded --out`` wrote to ``path``: its sheet read
/// and checked, its report and path check as written, ``to_json()`` the file's text.
///
/// Raises ``FiniteError`` for a file that cannot be read or is not a graded run.
#[pyfunction]
pub fn load_graded(py: Python<'_>, path: PathBuf) -> PyResult<PyGradedRun> {
    let shown = path.display().to_string();
    let text = py.detach(|| std::fs::read_to_string(&path)).map_err(|e| {
        errors::library(
            isogami::graded::GradedError::BadSheet(format!("cannot read {shown}: {e}")).into(),
        )
    })?;
    PyGradedRun::from_text(&text, &shown)
}

//! `isogami.inverse`: from a target behaviour to designs that have it, through the library's
//! one entry point (`isogami::inverse::inverse_design`) on a database's candidates
//! (`Store::inverse_candidates`), saving through the store
//! (`StoreWriter::save_inverse_results`) as `isogami inverse --save` does. Same options as the CLI; the result's ``to_dict()`` is the
//! JSON `isogami inverse --json` prints.

use crate::convert::{count_or, index_of, to_python, type_name};
use crate::database::PyDatabase;
use crate::design::PyDesign;
use crate::errors;
use crate::progress::Watch;
use isogami::api::Design;
use isogami::inverse::{inverse_design, Candidate, InverseRequest, InverseResult, Target};
use isogami_store::{Check, SavedDesign, Store, StoreWriter};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use serde::Serialize;
use std::path::PathBuf;

/// The result of an inverse-design run: per topology the best screened design and its
/// refinement, in rank order. ``designs`` are the refined designs, ``best`` the first;
/// ``to_dict()`` gives everything (targets, counts, before/after objectives, measures and
/// reports) as `isogami inverse --json` prints it.
#[pyclass(name = "InverseResult", module = "isogami", frozen)]
pub struct PyInverseResult {
    /// The target in canonical text form.
    target: String,
    /// The refined designs, best first.
    designs: Vec<Design>,
    /// Their refined objectives.
    objectives: Vec<f64>,
    /// Wall time, seconds.
    seconds: f64,
    /// `isogami inverse --json`'s text: the library's result (which serialises only) and
    /// what was saved. Kept as text, so that a result pickles exactly.
    json: String,
}

/// The JSON form: the library's result and, after ``save=True``, what was saved.
#[derive(Serialize)]
struct Output<'a> {
    #[serde(flatten)]
    result: &'a InverseResult,
    #[serde(skip_serializing_if = "<[SavedDesign]>::is_empty")]
    saved: &'a [SavedDesign],
}

impl PyInverseResult {
    fn new(result: &InverseResult, saved: &[SavedDesign]) -> PyResult<PyInverseResult> {
        let json = serde_json::to_string(&Output { result, saved })
            .map_err(|e| errors::IsogamiError::new_err(format!("JSON output: {e}")))?;
        Ok(PyInverseResult {
            target: result.target.clone(),
            designs: result
                .results
                .iter()
                .map(|r| r.after.design.clone())
                .collect(),
            objectives: result.results.iter().map(|r| r.after.objective).collect(),
            seconds: result.seconds,
            json,
        })
    }
}

impl PyInverseResult {
    /// The JSON form, read back.
    fn parsed(&self) -> PyResult<serde_json::Value> {
        serde_json::from_str(&self.json)
            .map_err(|e| errors::IsogamiError::new_err(format!("JSON output: {e}")))
    }
}

#[pymethods]
impl PyInverseResult {
    /// The target in canonical text form.
    #[getter]
    fn target(&self) -> String {
        self.target.clone()
    }

    /// The refined designs, best first.
    #[getter]
    fn designs(&self) -> Vec<PyDesign> {
        self.designs
            .iter()
            .map(|d| PyDesign { inner: d.clone() })
            .collect()
    }

    /// The best refined design.
    #[getter]
    fn best(&self) -> Option<PyDesign> {
        self.designs.first().map(|d| PyDesign { inner: d.clone() })
    }

    /// The refined objectives (smaller is better), best first.
    #[getter]
    fn objectives(&self) -> Vec<f64> {
        self.objectives.clone()
    }

    /// Wall time of the run in seconds.
    #[getter]
    fn seconds(&self) -> f64 {
        self.seconds
    }

    /// Whether the best design meets the target: every goal that names a value
    /// (``area(1.6)``, ``lock(0.1,0.3)``, ``isotropic``…) within its tolerance; ``None`` when
    /// every goal asks for the most (``area``, ``uniform``). Per goal: ``to_dict()``'s
    /// ``results[i]["verdict"]``.
    #[getter]
    fn met(&self) -> PyResult<Option<bool>> {
        Ok(self.parsed()?["met"].as_bool())
    }

    /// The best design's verdict in one line ("target NOT met: lock(6.07,6.07) is 7.08 away
    /// (tolerance 0.01)"); empty when there is no design.
    #[getter]
    fn verdict(&self) -> PyResult<String> {
        let v = self.parsed()?;
        Ok(v["results"][0]["verdict"]["summary"]
            .as_str()
            .unwrap_or_default()
            .to_string())
    }

    /// Everything, as the dict `json.loads` makes of `isogami inverse --json`'s output.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        py.import("json")?
            .call_method1("loads", (self.json.as_str(),))
    }

    fn __len__(&self) -> usize {
        self.designs.len()
    }

    /// Pickles exactly, as its parts (``InverseResult._from_state``), not as a second run.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let specs: Vec<String> = self.designs.iter().map(|d| d.to_string()).collect();
        let r = crate::pickle::recipe(
            py,
            "InverseResult._from_state",
            vec![
                self.target.clone().into_pyobject(py)?.into_any(),
                specs.into_pyobject(py)?.into_any(),
                self.objectives.clone().into_pyobject(py)?.into_any(),
                self.seconds.into_pyobject(py)?.into_any(),
                self.json.clone().into_pyobject(py)?.into_any(),
            ],
            &[],
        )?;
        crate::pickle::reduce(py, &r)
    }

    /// A result from its parts (for unpickling).
    #[staticmethod]
    fn _from_state(
        target: String,
        designs: Vec<String>,
        objectives: Vec<f64>,
        seconds: f64,
        json: String,
    ) -> PyResult<PyInverseResult> {
        let designs = designs
            .iter()
            .map(|s| isogami::api::resolve_design(s).map_err(errors::library))
            .collect::<PyResult<_>>()?;
        Ok(PyInverseResult {
            target,
            designs,
            objectives,
            seconds,
            json,
        })
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Self>().is_ok_and(|o| {
            let o = o.get();
            o.json == self.json && o.designs == self.designs && o.target == self.target
        })
    }

    fn __repr__(&self) -> String {
        match (self.designs.first(), self.objectives.first()) {
            (Some(best), Some(objective)) => format!(
                "isogami.InverseResult(target={:?}, designs={}, best={:?}, objective={:.6})",
                self.target,
                self.designs.len(),
                best.to_string(),
                objective
            ),
            _ => format!("isogami.InverseResult(target={:?}, designs=0)", self.target),
        }
    }
}

/// The target of a Python argument: compact text, JSON text, or a dict of the JSON form.
fn target_of(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<Target> {
    let text = if let Ok(text) = obj.extract::<String>() {
        text
    } else if obj.cast::<pyo3::types::PyDict>().is_ok() {
        py.import("json")?
            .call_method1("dumps", (obj,))?
            .extract::<String>()?
    } else {
        return Err(PyTypeError::new_err(format!(
            "target must be a str (compact text or JSON) or a dict (the JSON form), got {}",
            type_name(obj)
        )));
    };
    Target::resolve(&text).map_err(|e| errors::InverseError::new_err(e.to_string()))
}

/// The database argument: an open ``Database`` or a path.
enum Source<'a> {
    Open(&'a PyDatabase),
    Path(PathBuf),
}

impl Source<'_> {
    fn path(&self) -> PathBuf {
        match self {
            Source::Open(db) => db.file(),
            Source::Path(p) => p.clone(),
        }
    }

    /// The designs passing the target's family, cell and tile constraints (every design when
    /// none does, so that the library can say which constraint removed them).
    fn candidates(&self, py: Python<'_>, target: &Target) -> PyResult<Vec<Candidate>> {
        let constraints = &target.constraints;
        match self {
            Source::Open(db) => {
                db.with_store(py, move |store| store.inverse_candidates(constraints))
            }
            Source::Path(path) => {
                let shown = path.display().to_string();
                py.detach(|| {
                    Store::open_read(path, Check::Quick)
                        .and_then(|s| s.inverse_candidates(constraints))
                })
                .map_err(|e| errors::store(e, &shown))
            }
        }
    }
}

/// Finds designs with a target behaviour in a design database and refines their tile shapes
/// (the library's inverse design; see `isogami inverse --help` and docs/INVERSE.md).
///
/// ``target``: compact text such as ``"2*area + isotropic; families=IH28; tiles<=4"``, JSON
/// text, or a dict of the JSON form. ``database``: a ``Database`` or a path. ``top``: how
/// many designs of different topologies to keep and refine; ``budget``: evaluations
/// (deployments) per refined design, 0 screens only; ``confirm`` / ``triage``: how many
/// pre-screened designs to re-deploy / to refine briefly (default 16 × top); ``samples``:
/// fresh shape samples per best topology; ``kerf``: the kerf designs are deployed with (mean
/// edge lengths); ``refine_kerf``: optimise the kerf too; ``save``: store the refined
/// designs in the database as user designs (``to_dict()["saved"]`` says which).
///
/// ``progress(p)`` is called after every evaluation with a dict (``stage``, ``done``,
/// ``total``, ``best``, ``leaders``: each leading topology's best valid design so far) and
/// stops the run when it returns False; ``timeout`` in seconds;
/// Ctrl-C stops it (``CancelledError`` / ``KeyboardInterrupt``). The GIL is released while
/// it runs. Bad targets and options raise ``InverseError`` or ``SettingsError`` before
/// anything runs.
#[pyfunction]
#[pyo3(signature = (
    target, database, *, top=None, budget=None, confirm=None, triage=None, samples=None,
    kerf=None, refine_kerf=false, save=false, progress=None, timeout=None
), text_signature = "(target, database, *, top=3, budget=80, confirm=None, triage=None, samples=0, kerf=None, refine_kerf=False, save=False, progress=None, timeout=None)")]
#[allow(clippy::too_many_arguments)]
pub fn inverse(
    py: Python<'_>,
    target: &Bound<'_, PyAny>,
    database: &Bound<'_, PyAny>,
    top: Option<&Bound<'_, PyAny>>,
    budget: Option<&Bound<'_, PyAny>>,
    confirm: Option<&Bound<'_, PyAny>>,
    triage: Option<&Bound<'_, PyAny>>,
    samples: Option<&Bound<'_, PyAny>>,
    kerf: Option<f64>,
    refine_kerf: bool,
    save: bool,
    progress: Option<Bound<'_, PyAny>>,
    timeout: Option<f64>,
) -> PyResult<PyInverseResult> {
    // Counts checked here, so that -1 or 2**64 is refused naming the argument (not wrapped,
    // not a bare OverflowError); the library checks the ranges it allows.
    let top = count_or("top", top, 0, 3)?;
    let budget = count_or("budget", budget, 0, 80)?;
    let samples = count_or("samples", samples, 0, 0)?;
    let mut request = InverseRequest::new(target_of(py, target)?);
    request.top = top;
    request.budget = budget;
    for (name, given) in [("confirm", confirm), ("triage", triage)] {
        if given.is_some_and(|g| {
            !g.is_none() && index_of(g).is_some_and(|i| i.extract::<i64>().ok() == Some(0))
        }) {
            return Err(errors::InverseError::new_err(format!(
                "inverse design: {name} must be at least 1 (None for the default, 16 × top)"
            )));
        }
    }
    request.confirm = count_or("confirm", confirm, 1, 0)?;
    request.triage = count_or("triage", triage, 1, 0)?;
    request.samples = samples;
    if let Some(k) = kerf {
        request.kerf = k;
    }
    request.refine_kerf = refine_kerf;
    request.validate().map_err(|e| errors::library(e.into()))?;
    let source = if let Ok(db) = database.cast::<PyDatabase>() {
        Source::Open(db.get())
    } else if let Ok(path) = database.extract::<PathBuf>() {
        Source::Path(path)
    } else {
        return Err(PyTypeError::new_err(format!(
            "database must be an isogami.Database or a path, got {}",
            type_name(database)
        )));
    };
    let candidates = source.candidates(py, &request.target)?;
    let mut watch = Watch::new(progress.filter(|p| !p.is_none()), timeout)?;
    let result = py.detach(|| {
        inverse_design(&candidates, &request, &mut |p| {
            watch.tick_with(|py| to_python(py, p))
        })
    });
    let result = watch.finish(result)?;
    let saved = if save {
        let path = source.path();
        let shown = path.display().to_string();
        py.detach(|| {
            StoreWriter::open(&path, None, Check::Quick)
                .and_then(|mut w| w.save_inverse_results(&result))
        })
        .map_err(|e| errors::store(e, &shown))?
    } else {
        Vec::new()
    };
    PyInverseResult::new(&result, &saved)
}

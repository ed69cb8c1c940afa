//! `isogami.Design`: a complete design (family, shape parameters, supercell, one joint choice
//! per unique edge) read from a name, a spec string, design JSON or keyword arguments, always
//! checked by the library to build.

use crate::cell::PyCell;
use crate::convert::{index_of, to_python, type_name};
use crate::errors;
use isogami::api::{resolve_design, sheet_geometry, Design};
use isogami::cell::CellDims;
use isogami::render::cell_svg;
use isogami::tiling::Family;
use isogami::topology::JointChoice;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// A kirigami design: a tiling family with shape parameters, a supercell a×b and a joint
/// choice on every unique edge of the cell.
///
/// Make one with ``isogami.design(text)`` (a name such as ``"rotating-squares"``, a spec
/// string ``FAMILY:PARAMS:CELL:JOINTS`` or design JSON), with ``Design.from_spec``,
/// ``Design.from_json`` or ``Design.named``, or from keyword arguments::
///
///     Design(family="IH76", cell="2x2", joints="abab...")
///
/// ``params`` defaults to the family's (Kaplan's) defaults; ``cell`` is ``"AxB"`` or a
/// pair ``(a, b)`` with 1 <= a, b <= 4; ``joints`` is a str with one character per unique edge
/// (``-`` none, ``a``/``b`` a pin at that end, ``x`` both) or a sequence of such characters
/// (``"none"`` and ``"both"`` are accepted too). Every form is checked: the parameters must
/// give a valid tile and the joints must match the cell's edge count, else ``TilingError``,
/// ``CellError`` or ``DesignError``.
///
/// A design is immutable, hashable and picklable; ``str(design)`` is its spec string, which
/// round-trips exactly.
#[pyclass(name = "Design", module = "isogami", frozen)]
#[derive(Clone)]
pub struct PyDesign {
    pub inner: Design,
}

/// A joint choice from one Python item.
fn joint_choice(index: usize, text: &str) -> PyResult<JointChoice> {
    let c = match text.trim() {
        "none" => Some(JointChoice::None),
        "both" => Some(JointChoice::Both),
        t if t.chars().count() == 1 => t.chars().next().and_then(JointChoice::from_char),
        _ => None,
    };
    c.ok_or_else(|| {
        errors::DesignError::new_err(format!(
            "bad design spec: joint {index} is '{}'; use '-', 'a', 'b' or 'x' (or 'none', 'both')",
            text.escape_debug()
        ))
    })
}

/// Joint choices from a str of joint characters or a sequence of choices.
fn joints_of(obj: &Bound<'_, PyAny>) -> PyResult<Vec<JointChoice>> {
    if let Ok(text) = obj.extract::<String>() {
        return text
            .chars()
            .enumerate()
            .map(|(i, c)| joint_choice(i, &c.to_string()))
            .collect();
    }
    let items: Vec<String> = obj.extract().map_err(|_| {
        PyTypeError::new_err(format!(
            "joints must be a str of joint characters or a sequence of str, got {}",
            type_name(obj)
        ))
    })?;
    items
        .iter()
        .enumerate()
        .map(|(i, t)| joint_choice(i, t))
        .collect()
}

/// Cell dimensions from "AxB" or a pair (a, b).
pub fn dims_of(obj: &Bound<'_, PyAny>) -> PyResult<CellDims> {
    if let Ok(text) = obj.extract::<String>() {
        return text
            .parse()
            .map_err(|e: isogami::cell::CellError| errors::library(e.into()));
    }
    if let Some([a, b]) = crate::convert::int_pair(obj) {
        // Sizes as given (-1 stays -1), not wrapped into a byte.
        let small = |v: &Bound<'_, pyo3::types::PyInt>| {
            v.extract::<i64>().ok().and_then(|v| u8::try_from(v).ok())
        };
        return match (small(&a), small(&b)) {
            (Some(a), Some(b)) => CellDims::new(a, b).map_err(|e| errors::library(e.into())),
            _ => Err(errors::library(
                isogami::cell::CellError::BadCell {
                    input: format!("{a}x{b}"),
                }
                .into(),
            )),
        };
    }
    Err(PyTypeError::new_err(format!(
        "cell must be a str 'AxB' or a pair (a, b) of ints, got {}",
        type_name(obj)
    )))
}

/// A family from its name ("IH28", "28") or number.
pub fn family_of(obj: &Bound<'_, PyAny>) -> PyResult<Family> {
    if let Ok(f) = obj.cast::<crate::family::PyFamily>() {
        return Ok(f.get().inner);
    }
    if let Ok(text) = obj.extract::<String>() {
        return text
            .parse()
            .map_err(|e: isogami::tiling::TilingError| errors::library(e.into()));
    }
    if let Some(i) = index_of(obj) {
        // An int or a numpy integer; numbers beyond u32 (or negative) are no family either,
        // and the message shows them as given.
        return match i.extract::<i64>().ok().and_then(|n| u32::try_from(n).ok()) {
            Some(n) => Family::from_number(n).map_err(|e| errors::library(e.into())),
            None => Err(errors::library(
                isogami::tiling::TilingError::UnknownFamily {
                    input: i.to_string(),
                }
                .into(),
            )),
        };
    }
    Err(PyTypeError::new_err(format!(
        "family must be a str such as 'IH28', an int or an isogami.Family, got {}",
        type_name(obj)
    )))
}

/// Checks that a design builds (valid shape, supported cell, joints fitting the cell).
fn checked(design: Design) -> PyResult<PyDesign> {
    design.cell().map_err(|e| errors::library(e.into()))?;
    Ok(PyDesign { inner: design })
}

#[pymethods]
impl PyDesign {
    #[new]
    #[pyo3(signature = (family, params=None, cell=None, joints=None))]
    fn new(
        family: &Bound<'_, PyAny>,
        params: Option<Vec<f64>>,
        cell: Option<&Bound<'_, PyAny>>,
        joints: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyDesign> {
        let family = family_of(family)?;
        let dims = match cell {
            Some(c) => dims_of(c)?,
            None => CellDims::MINIMAL,
        };
        let joints =
            match joints {
                Some(j) => joints_of(j)?,
                None => return Err(PyTypeError::new_err(
                    "Design() needs joints: a str with one character per unique edge of the cell \
                     (see isogami.cell(family, params, cell).edge_count)",
                )),
            };
        checked(Design::new(
            family,
            &params.unwrap_or_else(|| family.default_params()),
            dims,
            joints,
        ))
    }

    /// Reads a spec string ``FAMILY:PARAMS:CELL:JOINTS`` (e.g. ``"IH90::1x1:aaa"``).
    #[staticmethod]
    fn from_spec(spec: &str) -> PyResult<PyDesign> {
        let design: Design = spec
            .parse()
            .map_err(|e: isogami::topology::DesignError| errors::library(e.into()))?;
        checked(design)
    }

    /// Reads design JSON, given as text or as a dict: ``{"family": "IH76", "params": [],
    /// "cell": [2, 2], "joints": [{"edge": 0, "at": "b"}, ...]}`` (edges not listed carry no
    /// joint; ``params`` may be left out for the family's defaults).
    #[staticmethod]
    fn from_json(json: &Bound<'_, PyAny>) -> PyResult<PyDesign> {
        let text: String = if json.is_instance_of::<PyDict>() {
            json.py()
                .import("json")?
                .call_method1("dumps", (json,))?
                .extract()?
        } else {
            json.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "design JSON must be a str or a dict, got {}",
                    type_name(json)
                ))
            })?
        };
        let design = Design::from_json(&text).map_err(|e| errors::library(e.into()))?;
        checked(design)
    }

    /// A named classic design (see ``isogami.NAMED_DESIGNS``), e.g. ``"rotating-squares"``.
    #[staticmethod]
    fn named(name: &str) -> PyResult<PyDesign> {
        isogami::topology::named_design(name.trim())
            .map(|inner| PyDesign { inner })
            .ok_or_else(|| {
                errors::DesignError::new_err(format!(
                    "no design is named '{}'; names: {}",
                    name.escape_debug(),
                    isogami::topology::NAMED_DESIGNS.join(", ")
                ))
            })
    }

    /// The tiling family, e.g. ``"IH76"``.
    #[getter]
    fn family(&self) -> String {
        self.inner.family.name()
    }

    /// The shape parameters v0, v1, ... (the family's count).
    #[getter]
    fn params(&self) -> Vec<f64> {
        self.inner.params.clone()
    }

    /// The supercell size as a pair ``(a, b)``.
    #[getter]
    fn cell(&self) -> (u8, u8) {
        (self.inner.dims.a(), self.inner.dims.b())
    }

    /// One joint character per unique edge: ``-`` none, ``a``/``b`` a pin at that end, ``x``
    /// both.
    #[getter]
    fn joints(&self) -> String {
        self.inner.joints.iter().map(|j| j.to_char()).collect()
    }

    /// The spec string ``FAMILY:PARAMS:CELL:JOINTS`` (round-trips exactly).
    #[getter]
    fn spec(&self) -> String {
        self.inner.to_string()
    }

    /// Number of pin joints (an ``x`` edge counts two).
    #[getter]
    fn joint_count(&self) -> usize {
        self.inner.joint_count()
    }

    /// Number of unique edges of the cell (the length of ``joints``).
    #[getter]
    fn edge_count(&self) -> usize {
        self.inner.joints.len()
    }

    /// The design JSON (only jointed edges listed), as text.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.inner.to_json())
            .map_err(|e| errors::IsogamiError::new_err(e.to_string()))
    }

    /// The design JSON as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.to_json())
    }

    /// The same design with other shape parameters (checked).
    fn with_params(&self, params: Vec<f64>) -> PyResult<PyDesign> {
        checked(self.inner.at_params(&params))
    }

    /// The same design with other joints (checked), given as for the constructor.
    fn with_joints(&self, joints: &Bound<'_, PyAny>) -> PyResult<PyDesign> {
        checked(Design {
            joints: joints_of(joints)?,
            ..self.inner.clone()
        })
    }

    /// The closed unit cell of this design (tiles, edges, tiling vectors).
    fn unit_cell(&self) -> PyResult<PyCell> {
        let cell = self.inner.cell().map_err(|e| errors::library(e.into()))?;
        Ok(PyCell { inner: cell })
    }

    /// Drawable geometry as the browser gets it: tile polygons (tiling units, centred as the
    /// mechanism places them), the cell's edges with endpoints, offsets and joint characters,
    /// u, w and the mean edge length.
    fn geometry<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let g = sheet_geometry(&self.inner).map_err(errors::library)?;
        to_python(py, &g)
    }

    /// An SVG drawing of the closed sheet (3×3 cells) with the joints marked.
    fn svg(&self) -> PyResult<String> {
        let cell = self.inner.cell().map_err(|e| errors::library(e.into()))?;
        Ok(cell_svg(&cell, Some(&self.inner.joints)))
    }

    fn _repr_svg_(&self) -> PyResult<String> {
        self.svg()
    }

    fn __str__(&self) -> String {
        self.inner.to_string()
    }

    fn __repr__(&self) -> String {
        // A spec holds no quotes or backslashes: this is Python's repr of the str.
        format!("isogami.Design('{}')", self.inner)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyDesign>()
            .is_ok_and(|o| o.get().inner == self.inner)
    }

    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        self.inner.to_string().hash(&mut h);
        h.finish()
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let from_spec = py.get_type::<PyDesign>().getattr("from_spec")?;
        let args = PyTuple::new(py, [slf.get().inner.to_string()])?;
        Ok((from_spec, args))
    }
}

/// Reads a design given as a name (``"rotating-squares"``), a spec string
/// ``FAMILY:PARAMS:CELL:JOINTS`` or design JSON, and checks that it builds (valid shape
/// parameters, a supported cell, one joint choice per unique edge).
///
/// Raises ``TilingError`` (unknown family, bad parameters), ``CellError`` (cell size) or
/// ``DesignError`` (unreadable spec or JSON, joints that do not fit).
#[pyfunction]
pub fn design(text: &str) -> PyResult<PyDesign> {
    resolve_design(text)
        .map(|inner| PyDesign { inner })
        .map_err(errors::library)
}

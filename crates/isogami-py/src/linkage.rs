//! `isogami.linkages`: the planar linkages a design's joints form (paper §5.1), their
//! signature and the tile degrees.

use crate::convert::{design_of, to_python};
use crate::errors;
use isogami::api::{linkages as lib_linkages, tile_linkages, Design};
use isogami::linkage::LinkageAnalysis;
use isogami::render::linkage_svg;
use pyo3::prelude::*;

/// The linkage analysis of a design: every linkage (a chordless loop of tiles round a hole,
/// one per translation class), the signature such as ``"2×4-bar + 1×6-bar"``, tile degrees
/// and the faces that are not linkages.
#[pyclass(name = "Linkages", module = "isogami", frozen)]
pub struct PyLinkages {
    design: Design,
    inner: LinkageAnalysis,
}

#[pymethods]
impl PyLinkages {
    /// The linkage signature, e.g. ``"2×4-bar + 1×6-bar"`` (``"none"`` without linkages).
    #[getter]
    fn signature(&self) -> String {
        self.inner.signature.clone()
    }

    /// The bar count of every linkage.
    #[getter]
    fn bars(&self) -> Vec<usize> {
        self.inner.linkages.iter().map(|l| l.bars).collect()
    }

    /// Every linkage as a dict: ``bars``, ``nodes`` (tiles round the hole as
    /// ``[tile, [k_u, k_w]]``) and ``joints`` (``edge``, ``end``, ``cell`` of each pin).
    #[getter]
    fn linkages<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.linkages)
    }

    /// Tile degree (distinct pinned neighbours) → number of tiles of the cell with it.
    #[getter]
    fn degree_histogram(&self) -> std::collections::BTreeMap<usize, usize> {
        self.inner.degree_histogram.clone()
    }

    /// The faces that are not linkages, with the reason (``issue``).
    #[getter]
    fn other_faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.other_faces)
    }

    /// For each tile of the cell, the indices (into ``linkages``) of every linkage through
    /// one of its copies, ascending (empty for none): a tile is often in several.
    fn tile_linkages(&self) -> Vec<Vec<usize>> {
        tile_linkages(&self.inner, self.tile_count())
    }

    /// The analysis as ``isogami linkages --json`` prints it.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner)
    }

    /// An SVG of the 3×3 patch with the linkages coloured by bar count.
    fn svg(&self) -> PyResult<String> {
        let cell = self.design.cell().map_err(|e| errors::library(e.into()))?;
        Ok(linkage_svg(&cell, &self.design.joints, &self.inner))
    }

    fn _repr_svg_(&self) -> PyResult<String> {
        self.svg()
    }

    fn __len__(&self) -> usize {
        self.inner.linkages.len()
    }

    /// Pickles as its data (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        crate::pickle::reduce_state(py, self)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Self>().is_ok_and(|o| {
            let o = o.get();
            o.design == self.design && o.inner == self.inner
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "isogami.Linkages({}: {})",
            self.design, self.inner.signature
        )
    }
}

impl crate::pickle::Pickled for PyLinkages {
    const CLASS: &'static str = "Linkages";
    /// The design's spec and the analysis.
    fn save(&self) -> PyResult<(Vec<u8>, Vec<Vec<f64>>)> {
        let state = (self.design.to_string(), &self.inner);
        Ok((crate::pickle::to_json(&state)?, Vec::new()))
    }
    fn load(json: &[u8], _arrays: Vec<Vec<f64>>) -> PyResult<Self> {
        let (spec, inner): (String, LinkageAnalysis) =
            Python::attach(|py| crate::pickle::from_json(py, Self::CLASS, json))?;
        let design = isogami::api::Design::resolve(&spec).map_err(|e| errors::library(e.into()))?;
        Ok(PyLinkages { design, inner })
    }
}

impl PyLinkages {
    fn tile_count(&self) -> usize {
        self.design.cell().map(|c| c.tiles.len()).unwrap_or(0)
    }
}

/// The linkage analysis of ``design`` (an ``isogami.Design``, a name, a spec string or design
/// JSON).
#[pyfunction]
pub fn linkages(py: Python<'_>, design: &Bound<'_, PyAny>) -> PyResult<PyLinkages> {
    let design = design_of(design)?;
    crate::pickle::computing();
    let inner = py
        .detach(|| lib_linkages(&design))
        .map_err(errors::library)?;
    Ok(PyLinkages { design, inner })
}

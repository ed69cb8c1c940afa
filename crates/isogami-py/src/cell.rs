//! `isogami.Cell`: the closed unit cell (or a×b supercell) of a tiling: tiles, unique edges
//! with neighbour offsets, tiling vectors.

use crate::convert::{array, int_array, point, to_python};
use crate::design::{dims_of, family_of};
use crate::errors;
use isogami::cell::{CellDims, End, UnitCell};
use isogami::render::cell_svg;
use isogami::tiling::Tiling;
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The closed-state unit cell of a tiling: CCW tile polygons, every unique edge once with the
/// cell offset of the neighbouring tile, and the tiling vectors u and w (tiling units).
///
/// Make one with ``isogami.cell(family, params, cell)`` or ``Design.unit_cell()``.
#[pyclass(name = "Cell", module = "isogami", frozen)]
pub struct PyCell {
    pub inner: UnitCell,
}

#[pymethods]
impl PyCell {
    /// The tiling family, e.g. ``"IH28"``.
    #[getter]
    fn family(&self) -> String {
        self.inner.family.name()
    }

    /// The shape parameters.
    #[getter]
    fn params(&self) -> Vec<f64> {
        self.inner.params.clone()
    }

    /// The supercell size ``(a, b)``.
    #[getter]
    fn cell(&self) -> (u8, u8) {
        (self.inner.dims.a(), self.inner.dims.b())
    }

    /// First tiling vector u = a·t1, shape (2,).
    #[getter]
    fn u<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        point(py, [self.inner.u.x, self.inner.u.y])
    }

    /// Second tiling vector w = b·t2, shape (2,).
    #[getter]
    fn w<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        point(py, [self.inner.w.x, self.inner.w.y])
    }

    /// Number of tiles in the cell.
    #[getter]
    fn tile_count(&self) -> usize {
        self.inner.tiles.len()
    }

    /// Number of unique edges (the length of a design's joint string).
    #[getter]
    fn edge_count(&self) -> usize {
        self.inner.edges.len()
    }

    /// Mean edge length L (tiling units): the unit of every non-dimensional length.
    #[getter]
    fn mean_edge_length(&self) -> f64 {
        self.inner.mean_edge_length()
    }

    /// The tile polygons, one array of shape (vertices, 2) per tile, counter-clockwise.
    #[getter]
    fn polygons<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyArray2<f64>>>> {
        self.inner
            .tiles
            .iter()
            .map(|t| {
                array(
                    py,
                    (t.polygon.len(), 2),
                    t.polygon.iter().flat_map(|p| [p.x, p.y]).collect(),
                )
            })
            .collect()
    }

    /// Area centroid of every tile, shape (tiles, 2).
    #[getter]
    fn centroids<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = &self.inner.tiles;
        array(
            py,
            (t.len(), 2),
            t.iter()
                .flat_map(|t| [t.centroid.x, t.centroid.y])
                .collect(),
        )
    }

    /// Which aspect of the minimal cell each tile is.
    #[getter]
    fn aspects(&self) -> Vec<usize> {
        self.inner.tiles.iter().map(|t| t.aspect).collect()
    }

    /// Unique edges as an int array of shape (edges, 4): tile_a, edge_a, tile_b, edge_b (edge k
    /// of a tile runs from its vertex k to k + 1).
    #[getter]
    fn edges<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let e = &self.inner.edges;
        int_array(
            py,
            (e.len(), 4),
            e.iter()
                .flat_map(|e| [e.tile_a, e.edge_a, e.tile_b, e.edge_b].map(|v| v as i64))
                .collect(),
        )
    }

    /// Cell offset (k_u, k_w) of each edge's neighbour tile, int array of shape (edges, 2).
    #[getter]
    fn offsets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let e = &self.inner.edges;
        int_array(
            py,
            (e.len(), 2),
            e.iter().flat_map(|e| e.offset.map(i64::from)).collect(),
        )
    }

    /// The two endpoints A and B (the joint candidates) of each edge, shape (edges, 2, 2).
    #[getter]
    fn endpoints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let n = self.inner.edges.len();
        let values = (0..n)
            .flat_map(|k| {
                let a = self.inner.endpoint(k, End::A);
                let b = self.inner.endpoint(k, End::B);
                [a.x, a.y, b.x, b.y]
            })
            .collect();
        array(py, (n, 2, 2), values)
    }

    /// The cell as ``isogami cell --json`` prints it.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let c = &self.inner;
        let d = PyDict::new(py);
        d.set_item("family", c.family.name())?;
        d.set_item("params", c.params.clone())?;
        d.set_item("cell", c.dims.to_string())?;
        d.set_item("u", [c.u.x, c.u.y])?;
        d.set_item("w", [c.w.x, c.w.y])?;
        d.set_item("tiles", to_python(py, &c.tiles)?)?;
        let edges = pyo3::types::PyList::empty(py);
        for (k, e) in c.edges.iter().enumerate() {
            let a = c.endpoint(k, End::A);
            let b = c.endpoint(k, End::B);
            let row = PyDict::new(py);
            row.set_item("index", k)?;
            row.set_item("tile_a", e.tile_a)?;
            row.set_item("edge_a", e.edge_a)?;
            row.set_item("tile_b", e.tile_b)?;
            row.set_item("edge_b", e.edge_b)?;
            row.set_item("offset", e.offset)?;
            row.set_item("a", [a.x, a.y])?;
            row.set_item("b", [b.x, b.y])?;
            edges.append(row)?;
        }
        d.set_item("edges", edges)?;
        d.set_item("mean_edge_length", c.mean_edge_length())?;
        Ok(d)
    }

    /// An SVG drawing of the closed sheet over 3×3 cells; with ``joints`` (a design's joint
    /// string) the joints are marked.
    #[pyo3(signature = (joints=None))]
    fn svg(&self, joints: Option<&str>) -> PyResult<String> {
        let joints = match joints {
            None => None,
            Some(text) => {
                let d = isogami::topology::Design {
                    family: self.inner.family,
                    params: self.inner.params.clone(),
                    dims: self.inner.dims,
                    joints: text
                        .chars()
                        .enumerate()
                        .map(|(i, c)| {
                            isogami::topology::JointChoice::from_char(c).ok_or_else(|| {
                                errors::DesignError::new_err(format!(
                                    "bad design spec: joint character {i} is '{}'; use '-', 'a', 'b' or 'x'",
                                    c.escape_debug()
                                ))
                            })
                        })
                        .collect::<PyResult<_>>()?,
                };
                d.cell().map_err(|e| errors::library(e.into()))?;
                Some(d.joints)
            }
        };
        Ok(cell_svg(&self.inner, joints.as_deref()))
    }

    fn _repr_svg_(&self) -> String {
        cell_svg(&self.inner, None)
    }

    /// Pickles as ``isogami.cell(family, params, cell)`` (see the `pickle` module).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let r = crate::pickle::recipe(
            py,
            "cell",
            vec![
                self.inner.family.name().into_pyobject(py)?.into_any(),
                self.inner.params.clone().into_pyobject(py)?.into_any(),
                self.cell().into_pyobject(py)?.into_any(),
            ],
            &[],
        )?;
        crate::pickle::reduce(py, &r)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Self>().is_ok_and(|o| {
            let o = o.get();
            crate::pickle::same(&o.inner, &self.inner)
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "isogami.Cell({} {} with {} tiles, {} unique edges)",
            self.inner.family,
            self.inner.dims,
            self.inner.tiles.len(),
            self.inner.edges.len()
        )
    }
}

/// The closed unit cell of ``family`` (a name such as ``"IH28"`` or a number) at shape
/// ``params`` (default: Kaplan's defaults), repeated into a supercell ``cell`` (``"AxB"`` or
/// ``(a, b)``, 1..4 each).
///
/// Raises ``TilingError`` for an unknown family or bad parameters, ``CellError`` for a bad
/// cell size.
#[pyfunction]
#[pyo3(signature = (family, params=None, cell=None))]
pub fn cell(
    family: &Bound<'_, PyAny>,
    params: Option<Vec<f64>>,
    cell: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyCell> {
    let family = family_of(family)?;
    let dims = match cell {
        Some(c) => dims_of(c)?,
        None => CellDims::MINIMAL,
    };
    let params = params.unwrap_or_else(|| family.default_params());
    let tiling = Tiling::new(family, &params).map_err(|e| errors::library(e.into()))?;
    let inner = UnitCell::new(&tiling, dims).map_err(|e| errors::library(e.into()))?;
    Ok(PyCell { inner })
}

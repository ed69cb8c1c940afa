//! `isogami.Query`: the browser's catalogue filters as the store's own query type
//! (`isogami_store::DesignQuery`). Keys are those of the browser's URLs (family, cell, tiles,
//! behaviour, linkage, end, origin, range, sort, limit, offset); values are read by the
//! store's vocabulary (`Facet::value`, `Measure`, `SortKey`), so a value means in Python what
//! it means in the browser.

use crate::convert::type_name;
use crate::errors;
use isogami_store::query::MAX_LIMIT;
use isogami_store::{DesignQuery, Facet, Measure, SortKey};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

/// The filter keys, each with the facet it selects (None for the non-facet keys).
pub const KEYS: &[(&str, Option<Facet>)] = &[
    ("family", Some(Facet::Family)),
    ("cell", Some(Facet::Cell)),
    ("tiles", Some(Facet::TileCount)),
    ("behaviour", Some(Facet::Behaviour)),
    ("linkage", Some(Facet::LinkageSignature)),
    ("end", Some(Facet::EndReason)),
    ("origin", Some(Facet::Origin)),
    ("range", None),
    ("sort", None),
    ("lead", None),
    ("limit", None),
    ("offset", None),
];

/// A catalogue query: facet selections (any of the listed values; all facets at once),
/// numeric ranges, an order and a page.
///
/// Keywords, as in the browser's URLs:
///
/// - ``family`` (``"IH28"`` or a list), ``cell`` (``"2x1"``, ``(2, 1)`` or a list),
///   ``tiles`` (tile counts), ``behaviour`` (``"isotropic_auxetic"``,
///   ``"anisotropic_auxetic"``, ``"orthotropic_positive_poisson"``, ``"none"``),
///   ``linkage`` (signatures), ``end`` (end reasons such as ``"contact_limit"``), ``origin``
///   (``"explored"``, ``"user"``);
/// - ``range``: bounds on measures, a dict ``{"max_area_ratio": (1.5, None)}`` or a list
///   of ``(measure, min, max)`` or ``"measure:min:max"`` (None or empty: open). Measures:
///   max_expansion, min_expansion, max_area_ratio, max_tile_rotation, poisson_min,
///   poisson_max, steps, tile_count, kerf, finite_raw_dof, finite_covered, open_t,
///   end_area_ratio, shape_tolerance, fabrication_kept, v0…v5;
/// - ``sort``: a measure or ``spec``, ``family``, ``cell``, ``behaviour``,
///   ``linkage_signature``, ``end_reason``, ``origin``; ``"-key"`` for descending;
/// - ``lead``: ``"buildable"`` puts buildable designs first (a one-DOF finite sheet and the
///   fabrication tolerance met; ``Record.buildable``), each part in the sort's order; ``"all"``
///   (the default) does not;
/// - ``limit`` (None: every matching design) and ``offset``.
///
/// Bad values raise ``QueryError`` naming the key.
#[pyclass(name = "Query", module = "isogami", frozen)]
#[derive(Clone)]
pub struct PyQuery {
    pub inner: DesignQuery,
    /// None: every row (pages of the store's largest size).
    pub limit: Option<u32>,
}

/// The items of a value that may be one item or a collection of them: a list, a tuple, a
/// set, a numpy array, a pandas Series or Index (anything iterable but a str, bytes, a Family
/// or a pair of ints, which is one cell).
fn items<'py>(value: &Bound<'py, PyAny>) -> Vec<Bound<'py, PyAny>> {
    if let Ok(l) = value.cast::<PyList>() {
        return l.iter().collect();
    }
    if let Ok(t) = value.cast::<PyTuple>() {
        // (2, 1) is one cell, not two values.
        if !t.iter().all(|v| v.extract::<i64>().is_ok()) || t.len() != 2 {
            return t.iter().collect();
        }
        return vec![value.clone()];
    }
    let single = value.extract::<String>().is_ok()
        || value.is_instance_of::<pyo3::types::PyBytes>()
        || value.cast::<crate::family::PyFamily>().is_ok()
        || value.is_instance_of::<pyo3::types::PyDict>()
        || crate::convert::index_of(value).is_some();
    if !single {
        if let Ok(it) = value.try_iter() {
            if let Ok(v) = it.collect::<PyResult<Vec<_>>>() {
                return v;
            }
        }
    }
    vec![value.clone()]
}

/// One facet value as the browser's text form.
fn facet_text(key: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    if value.is_none() {
        return Ok("none".into());
    }
    if let Ok(s) = value.extract::<String>() {
        return Ok(s);
    }
    if let Ok((a, b)) = value.extract::<(i64, i64)>() {
        return Ok(format!("{a}x{b}"));
    }
    if !value.is_instance_of::<pyo3::types::PyBool>() {
        if let Ok(n) = value.extract::<i64>() {
            return Ok(n.to_string());
        }
    }
    if let Ok(f) = value.cast::<crate::family::PyFamily>() {
        return Ok(f.get().inner.name());
    }
    Err(PyTypeError::new_err(format!(
        "{key}: expected a str (or a list of them), got {}",
        type_name(value)
    )))
}

/// A range bound written as text: empty is open.
fn text_bound(key: &str, text: &str) -> PyResult<Option<f64>> {
    if text.trim().is_empty() {
        return Ok(None);
    }
    text.trim().parse().map(Some).map_err(|_| {
        errors::QueryError::new_err(format!(
            "range bound '{}' on {key} is not a number",
            text.escape_debug()
        ))
    })
}

/// A range bound: None (open), a number, or text.
fn bound(key: &str, value: Bound<'_, PyAny>) -> PyResult<Option<f64>> {
    if value.is_none() {
        return Ok(None);
    }
    if let Ok(s) = value.extract::<String>() {
        return text_bound(key, &s);
    }
    value.extract::<f64>().map(Some).map_err(|_| {
        PyTypeError::new_err(format!(
            "range bound on {key} must be a number or None, got {}",
            type_name(&value)
        ))
    })
}

fn measure(text: &str) -> PyResult<Measure> {
    text.trim().parse().map_err(errors::query)
}

/// Adds the ranges of a `range` value.
fn ranges(q: &mut DesignQuery, value: &Bound<'_, PyAny>) -> PyResult<()> {
    if let Ok(d) = value.cast::<PyDict>() {
        for (k, v) in d.iter() {
            let name: String = k.extract()?;
            let m = measure(&name)?;
            let (lo, hi): (Bound<'_, PyAny>, Bound<'_, PyAny>) = v.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "range {name}: expected a pair (min, max), got {}",
                    type_name(&v)
                ))
            })?;
            q.range(m, bound(&name, lo)?, bound(&name, hi)?);
        }
        return Ok(());
    }
    let list: Vec<Bound<'_, PyAny>> = match value.cast::<PyList>() {
        Ok(l) => l.iter().collect(),
        Err(_) => vec![value.clone()],
    };
    for item in list {
        if let Ok(text) = item.extract::<String>() {
            let parts: Vec<&str> = text.split(':').collect();
            let [m, lo, hi] = parts[..] else {
                return Err(errors::QueryError::new_err(format!(
                    "range must be measure:min:max, got '{}'",
                    text.escape_debug()
                )));
            };
            let m = measure(m)?;
            let key = m.to_string();
            q.range(m, text_bound(&key, lo)?, text_bound(&key, hi)?);
            continue;
        }
        let (name, lo, hi): (String, Bound<'_, PyAny>, Bound<'_, PyAny>) =
            item.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "range: expected (measure, min, max) or 'measure:min:max', got {}",
                    type_name(&item)
                ))
            })?;
        let m = measure(&name)?;
        q.range(m, bound(&name, lo)?, bound(&name, hi)?);
    }
    Ok(())
}

impl PyQuery {
    /// A query from the browser's keys.
    pub fn from_pairs(pairs: &[(String, Bound<'_, PyAny>)]) -> PyResult<PyQuery> {
        let mut q = DesignQuery::default();
        let mut limit = None;
        for (key, value) in pairs {
            let facet = KEYS.iter().find(|(k, _)| k == key).map(|(_, f)| *f);
            match (key.as_str(), facet) {
                (_, Some(Some(facet))) => {
                    if value.is_none() && facet != Facet::Behaviour {
                        continue;
                    }
                    for item in items(value) {
                        let text = facet_text(key, &item)?;
                        let v = facet
                            .value(&text)
                            .map_err(|e| errors::QueryError::new_err(format!("{key}: {e}")))?;
                        q.select(v);
                    }
                }
                ("range", _) => ranges(&mut q, value)?,
                ("sort", _) => {
                    if value.is_none() {
                        continue;
                    }
                    let text: String = value.extract().map_err(|_| {
                        PyTypeError::new_err(format!(
                            "sort must be a str, got {}",
                            type_name(value)
                        ))
                    })?;
                    let (name, descending) = match text.strip_prefix('-') {
                        Some(rest) => (rest, true),
                        None => (text.as_str(), false),
                    };
                    let key: SortKey = name
                        .parse()
                        .map_err(|e| errors::QueryError::new_err(format!("sort: {e}")))?;
                    q.sort_by(key, descending);
                }
                ("lead", _) => {
                    if value.is_none() {
                        continue;
                    }
                    let text: String = value.extract().map_err(|_| {
                        PyTypeError::new_err(format!(
                            "lead must be a str, got {}",
                            type_name(value)
                        ))
                    })?;
                    q.lead(&text)
                        .map_err(|e| errors::QueryError::new_err(e.to_string()))?;
                }
                ("limit", _) => {
                    if value.is_none() {
                        limit = None;
                        continue;
                    }
                    let n: i64 = value.extract().map_err(|_| {
                        PyTypeError::new_err(format!(
                            "limit must be an int or None, got {}",
                            type_name(value)
                        ))
                    })?;
                    if n < 1 {
                        return Err(errors::QueryError::new_err(format!(
                            "limit {n} must be at least 1 (None: every design)"
                        )));
                    }
                    limit = Some(u32::try_from(n).unwrap_or(u32::MAX));
                }
                ("offset", _) => {
                    let n: i64 = value.extract().map_err(|_| {
                        PyTypeError::new_err(format!(
                            "offset must be an int, got {}",
                            type_name(value)
                        ))
                    })?;
                    q.offset = u64::try_from(n).map_err(|_| {
                        errors::QueryError::new_err(format!("offset {n} must not be negative"))
                    })?;
                }
                (other, _) => {
                    let keys: Vec<&str> = KEYS.iter().map(|(k, _)| *k).collect();
                    return Err(PyTypeError::new_err(format!(
                        "unknown filter '{}'; filters are: {}",
                        other.escape_debug(),
                        keys.join(", ")
                    )));
                }
            }
        }
        q.limit = limit.map_or(MAX_LIMIT, |n| n.min(MAX_LIMIT));
        Ok(PyQuery { inner: q, limit })
    }

    /// A query from an optional `Query` and keyword filters added to it.
    pub fn of(
        query: Option<&Bound<'_, PyAny>>,
        filters: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyQuery> {
        let extra = PyQuery::from_pairs(&crate::settings::pairs(filters)?)?;
        let Some(query) = query.filter(|q| !q.is_none()) else {
            return Ok(extra);
        };
        let base = query
            .cast::<PyQuery>()
            .map_err(|_| {
                PyTypeError::new_err(format!(
                    "query must be an isogami.Query, got {}",
                    type_name(query)
                ))
            })?
            .get()
            .clone();
        if filters.is_none_or(|f| f.is_empty()) {
            return Ok(base);
        }
        Ok(base.merged(&extra, filters))
    }

    /// `self` with the selections and ranges of `extra` added; sort and page of `extra`
    /// where given.
    fn merged(mut self, extra: &PyQuery, given: Option<&Bound<'_, PyDict>>) -> PyQuery {
        let has = |k: &str| given.is_some_and(|d| d.contains(k).unwrap_or(false));
        let q = &mut self.inner;
        let e = &extra.inner;
        q.families.extend(e.families.iter().copied());
        q.cells.extend(e.cells.iter().copied());
        q.tile_counts.extend(e.tile_counts.iter().copied());
        q.behaviours.extend(e.behaviours.iter().copied());
        q.linkage_signatures
            .extend(e.linkage_signatures.iter().cloned());
        q.end_reasons.extend(e.end_reasons.iter().cloned());
        q.origins.extend(e.origins.iter().copied());
        q.ranges.extend(e.ranges.iter().copied());
        if has("sort") {
            q.sort = e.sort;
        }
        if has("lead") {
            q.buildable_first = e.buildable_first;
        }
        if has("offset") {
            q.offset = e.offset;
        }
        if has("limit") {
            q.limit = e.limit;
            self.limit = extra.limit;
        }
        self
    }
}

#[pymethods]
impl PyQuery {
    #[new]
    #[pyo3(signature = (**filters))]
    fn new(filters: Option<&Bound<'_, PyDict>>) -> PyResult<PyQuery> {
        PyQuery::from_pairs(&crate::settings::pairs(filters)?)
    }

    /// A copy with more filters (selections and ranges add up; sort, limit and offset
    /// replace).
    #[pyo3(name = "where", signature = (**filters))]
    fn where_(slf: &Bound<'_, Self>, filters: Option<&Bound<'_, PyDict>>) -> PyResult<PyQuery> {
        PyQuery::of(Some(slf.as_any()), filters)
    }

    /// The query as the store's JSON form (families, cells, tile_counts, behaviours,
    /// linkage_signatures, end_reasons, origins, ranges, sort, limit, offset).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let d = crate::convert::to_python(py, &self.inner)?;
        d.set_item("limit", self.limit)?;
        Ok(d)
    }

    /// Pickles as its data (see the `pickle` module), so a query can go to pool workers.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        crate::pickle::reduce_state(py, self)
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<Self>()
            .is_ok_and(|o| o.get().inner == self.inner && o.get().limit == self.limit)
    }

    fn __repr__(&self) -> String {
        let json = serde_json::to_string(&self.inner).unwrap_or_default();
        format!("isogami.Query({json})")
    }
}

impl crate::pickle::Pickled for PyQuery {
    const CLASS: &'static str = "Query";
    fn save(&self) -> PyResult<(Vec<u8>, Vec<Vec<f64>>)> {
        Ok((
            crate::pickle::to_json(&(&self.inner, self.limit))?,
            Vec::new(),
        ))
    }
    fn load(json: &[u8], _arrays: Vec<Vec<f64>>) -> PyResult<Self> {
        let (inner, limit) = Python::attach(|py| crate::pickle::from_json(py, Self::CLASS, json))?;
        Ok(PyQuery { inner, limit })
    }
}

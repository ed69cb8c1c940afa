//! A query's filters as an SQL WHERE clause with bound values. Column names come only from
//! the query enums; every value is a parameter.

use super::types::{DesignQuery, Facet, Measure, QueryError, Sort, SortKey, MAX_LIMIT};
use rusqlite::types::Value;

/// A WHERE clause and its parameters.
#[derive(Debug, Default)]
pub(crate) struct Where {
    clauses: Vec<String>,
    pub(crate) params: Vec<Value>,
}

impl Where {
    /// True when nothing is filtered.
    pub(crate) fn is_empty(&self) -> bool {
        self.clauses.is_empty()
    }

    /// `WHERE …` or nothing.
    pub(crate) fn sql(&self) -> String {
        if self.clauses.is_empty() {
            String::new()
        } else {
            format!("WHERE {}", self.clauses.join(" AND "))
        }
    }

    /// Adds a condition with its parameters.
    pub(crate) fn push(&mut self, clause: String, params: impl IntoIterator<Item = Value>) {
        self.clauses.push(clause);
        self.params.extend(params);
    }

    /// `column` is one of `values` (or NULL when `or_null`).
    fn any_of(&mut self, column: &'static str, values: Vec<Value>, or_null: bool) {
        let list = || vec!["?"; values.len()].join(", ");
        let clause = match (values.is_empty(), or_null) {
            (true, false) => return,
            (true, true) => format!("{column} IS NULL"),
            (false, false) => format!("{column} IN ({})", list()),
            (false, true) => format!("({column} IN ({}) OR {column} IS NULL)", list()),
        };
        self.push(clause, values);
    }
}

/// Text value.
fn text(s: impl Into<String>) -> Value {
    Value::Text(s.into())
}

/// The column a facet is stored in: the schema names each facet column after its facet.
pub(crate) fn facet_column(facet: Facet) -> &'static str {
    facet.name()
}

/// The filters of `q`, leaving out the selection of `skip` (for disjunctive facet counts).
pub(crate) fn filters(q: &DesignQuery, skip: Option<Facet>) -> Result<Where, QueryError> {
    let mut w = Where::default();
    let keep = |f: Facet| skip != Some(f);
    if keep(Facet::Family) {
        let v = q
            .families
            .iter()
            .map(|f| Value::Integer(i64::from(f.number())))
            .collect();
        w.any_of(facet_column(Facet::Family), v, false);
    }
    if keep(Facet::Cell) {
        let v = q.cells.iter().map(|c| text(c.to_string())).collect();
        w.any_of(facet_column(Facet::Cell), v, false);
    }
    if keep(Facet::TileCount) {
        let v = q
            .tile_counts
            .iter()
            .map(|&n| Value::Integer(i64::from(n)))
            .collect();
        w.any_of(facet_column(Facet::TileCount), v, false);
    }
    if keep(Facet::Behaviour) {
        let v = q
            .behaviours
            .iter()
            .flatten()
            .map(|b| text(b.as_str()))
            .collect();
        let or_null = q.behaviours.iter().any(Option::is_none);
        w.any_of(facet_column(Facet::Behaviour), v, or_null);
    }
    if keep(Facet::LinkageSignature) {
        let v = q
            .linkage_signatures
            .iter()
            .flatten()
            .map(|s| text(s.as_str()))
            .collect();
        let or_null = q.linkage_signatures.iter().any(Option::is_none);
        w.any_of(facet_column(Facet::LinkageSignature), v, or_null);
    }
    if keep(Facet::EndReason) {
        let v = q.end_reasons.iter().map(|s| text(s.as_str())).collect();
        w.any_of(facet_column(Facet::EndReason), v, false);
    }
    if keep(Facet::Origin) {
        let v = q.origins.iter().map(|o| text(o.as_str())).collect();
        w.any_of(facet_column(Facet::Origin), v, false);
    }
    for r in &q.ranges {
        let column = r.measure.column()?;
        for bound in [r.min, r.max].into_iter().flatten() {
            if !bound.is_finite() {
                return Err(QueryError::NotFinite {
                    measure: r.measure,
                    value: bound,
                });
            }
        }
        if let (Some(min), Some(max)) = (r.min, r.max) {
            if min > max {
                return Err(QueryError::EmptyRange {
                    measure: r.measure,
                    min,
                    max,
                });
            }
        }
        // `+column`: a range never drives an index search. Without statistics SQLite takes
        // ranges for selective, and fetching most rows through an index costs several times a
        // scan of the compact summary table.
        if let Some(min) = r.min {
            w.push(format!("+{column} >= ?"), [Value::Real(min)]);
        }
        if let Some(max) = r.max {
            w.push(format!("+{column} <= ?"), [Value::Real(max)]);
        }
    }
    Ok(w)
}

/// The sort, spec ascending by default.
pub(crate) fn sort_or_default(sort: Option<Sort>) -> Sort {
    sort.unwrap_or(Sort {
        key: SortKey::Spec,
        descending: false,
    })
}

/// The sort's key columns and whether they may be missing.
fn key_columns(key: SortKey) -> Result<(Vec<&'static str>, bool), QueryError> {
    Ok(match key {
        SortKey::Spec => (vec!["spec"], false),
        SortKey::Family => (vec!["family"], false),
        SortKey::Cell => (vec!["cell_a", "cell_b"], false),
        SortKey::Behaviour => (vec!["behaviour"], true),
        SortKey::LinkageSignature => (vec!["linkage_signature"], true),
        SortKey::EndReason => (vec!["end_reason"], false),
        SortKey::Origin => (vec!["origin"], false),
        SortKey::Measure(m) => (vec![m.column()?], m.nullable()),
    })
}

/// An index whose order is the sort's order (key with missing values last, then id), and the
/// ORDER BY that SQLite matches against it.
pub(crate) fn index_order(sort: Sort) -> Result<Option<(&'static str, String)>, QueryError> {
    let (plain, nulls_last) = match sort.key {
        SortKey::Spec => ("designs_spec", None),
        SortKey::Family => ("designs_family", None),
        SortKey::EndReason => ("designs_end_reason", None),
        SortKey::Origin => ("designs_origin", None),
        SortKey::Behaviour => ("designs_behaviour", Some("designs_behaviour_nulls_last")),
        SortKey::LinkageSignature => ("designs_linkage", Some("designs_linkage_nulls_last")),
        SortKey::Measure(m) => match m {
            Measure::MaxExpansion => ("designs_max_expansion", None),
            Measure::MinExpansion => ("designs_min_expansion", None),
            Measure::MaxAreaRatio => ("designs_area_ratio", None),
            Measure::MaxTileRotation => ("designs_tile_rotation", None),
            Measure::Steps => ("designs_steps", None),
            Measure::TileCount => ("designs_tile_count", None),
            Measure::PoissonMin => (
                "designs_poisson_min",
                Some("designs_poisson_min_nulls_last"),
            ),
            Measure::PoissonMax => (
                "designs_poisson_max",
                Some("designs_poisson_max_nulls_last"),
            ),
            Measure::FiniteRawDof => (
                "designs_finite_raw_dof",
                Some("designs_finite_raw_dof_nulls_last"),
            ),
            Measure::FiniteCovered => (
                "designs_finite_covered",
                Some("designs_finite_covered_nulls_last"),
            ),
            Measure::OpenT => ("designs_open_t", Some("designs_open_t_nulls_last")),
            Measure::EndAreaRatio => (
                "designs_end_area_ratio",
                Some("designs_end_area_ratio_nulls_last"),
            ),
            Measure::ShapeTolerance => (
                "designs_shape_tolerance",
                Some("designs_shape_tolerance_nulls_last"),
            ),
            Measure::FabricationKept => (
                "designs_fabrication_kept",
                Some("designs_fabrication_kept_nulls_last"),
            ),
            Measure::Kerf | Measure::Param(_) => return Ok(None),
        },
        SortKey::Cell => return Ok(None),
    };
    let (columns, _) = key_columns(sort.key)?;
    let c = columns[0];
    Ok(Some(match (sort.descending, nulls_last) {
        // SQLite orders NULL first, so walking an index backwards puts missing values last.
        (true, _) => (plain, format!("ORDER BY {c} DESC, id DESC")),
        (false, None) => (plain, format!("ORDER BY {c} ASC, id ASC")),
        (false, Some(index)) => (index, format!("ORDER BY {c} IS NULL, {c} ASC, id ASC")),
    }))
}

/// `ORDER BY …` for sorting the filtered rows (keys written `+key` so that no index is walked):
/// missing values last, ties by insertion order in the same direction; buildable designs
/// first when the query asks for it.
pub(crate) fn sorted_order(query: &DesignQuery) -> Result<String, QueryError> {
    let sort = sort_or_default(query.sort);
    let dir = if sort.descending { "DESC" } else { "ASC" };
    let (columns, nullable) = key_columns(sort.key)?;
    let nulls = if nullable { " NULLS LAST" } else { "" };
    let mut keys: Vec<String> = columns
        .iter()
        .map(|c| format!("+{c} {dir}{nulls}"))
        .collect();
    if query.buildable_first {
        keys.insert(0, format!("{} DESC", buildable_sql()));
    }
    Ok(format!("ORDER BY {}, +id {dir}", keys.join(", ")))
}

/// SQL that is 1 for a buildable design, 0 otherwise (the rule of
/// [`DesignSummary::buildable`](crate::DesignSummary::buildable)).
pub(crate) fn buildable_sql() -> String {
    format!("(finite_covered IS NOT NULL AND {})", tolerance_met_sql())
}

/// SQL that is 1 for a design with margins whose shape tolerance reaches the fabrication
/// tolerance (or whose family has no shape parameters), 0 otherwise.
pub(crate) fn tolerance_met_sql() -> String {
    format!(
        "(open_t IS NOT NULL AND (shape_tolerance IS NULL OR shape_tolerance >= {:e}))",
        isogami::catalog::FABRICATION_TOLERANCE
    )
}

/// Checks limit and offset.
pub(crate) fn check_page(q: &DesignQuery) -> Result<(), QueryError> {
    if q.limit == 0 || q.limit > MAX_LIMIT {
        return Err(QueryError::Limit(q.limit));
    }
    if i64::try_from(q.offset).is_err() {
        return Err(QueryError::Offset(q.offset));
    }
    Ok(())
}

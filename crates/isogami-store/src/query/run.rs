//! Running queries against the store.

use super::filter::{
    check_page, facet_column, filters, index_order, sort_or_default, sorted_order,
};
use super::types::{DesignQuery, Facet, FacetCount, FacetValue, Measure, Page, ScatterPoint};
use crate::error::{StoreError, StoreResult};
use crate::open::Store;
use crate::records::Origin;
use crate::rows::{read_design, DESIGN_COLUMNS};
use rusqlite::params_from_iter;
use rusqlite::types::Value;

/// A page walks the sort index when the filtered set has at least this many times the rows
/// the page needs (offset + limit): the walk then visits at most 1/WALK_FACTOR of the table.
const WALK_FACTOR: u64 = 10;

/// A stored facet value as the typed value, or damage.
fn facet_value(facet: Facet, v: Value) -> StoreResult<FacetValue> {
    let damaged = |v: &Value| StoreError::Damaged(format!("{facet} value {v:?} cannot be read"));
    Ok(match (facet, &v) {
        (Facet::Family, Value::Integer(n)) => FacetValue::Family(
            u32::try_from(*n)
                .ok()
                .and_then(|n| isogami::tiling::Family::from_number(n).ok())
                .ok_or_else(|| damaged(&v))?,
        ),
        (Facet::Cell, Value::Text(t)) => FacetValue::Cell(t.parse().map_err(|_| damaged(&v))?),
        (Facet::TileCount, Value::Integer(n)) => {
            FacetValue::TileCount(u32::try_from(*n).map_err(|_| damaged(&v))?)
        }
        (Facet::Behaviour, Value::Null) => FacetValue::Behaviour(None),
        (Facet::LinkageSignature, Value::Null) => FacetValue::LinkageSignature(None),
        (Facet::LinkageSignature, Value::Text(t)) => FacetValue::LinkageSignature(Some(t.clone())),
        (Facet::EndReason, Value::Text(t)) => FacetValue::EndReason(t.clone()),
        (Facet::Origin, Value::Text(t)) => {
            FacetValue::Origin(Origin::from_name(t).ok_or_else(|| damaged(&v))?)
        }
        (Facet::Behaviour, Value::Text(t)) => facet.value(t).map_err(|_| damaged(&v))?,
        _ => return Err(damaged(&v)),
    })
}

impl Store {
    /// One page of the designs matching `query`, in its order, with the size of the whole
    /// filtered set. Every row returned is checked against its checksum.
    pub fn page(&self, query: &DesignQuery) -> StoreResult<Page> {
        check_page(query)?;
        let sort = sort_or_default(query.sort);
        let w = filters(query, None)?;
        let total: i64 = self.conn.query_row(
            &format!("SELECT count(*) FROM designs {}", w.sql()),
            params_from_iter(w.params.iter()),
            |r| r.get(0),
        )?;
        let total = total as u64;
        let mut out = Vec::with_capacity(query.limit as usize);
        if query.offset < total {
            let mut params = w.params.clone();
            params.push(Value::Integer(i64::from(query.limit)));
            params.push(Value::Integer(query.offset as i64));
            // Walking the sort key's index and stopping after offset + limit matches is fast
            // unless the filter is selective (most rows walked are then rejected): the count
            // just taken tells which. Otherwise the matches are sorted, as (key, id) pairs
            // only, and the page's rows fetched by id.
            let wanted = query.offset + u64::from(query.limit);
            let walk = !query.buildable_first && total >= WALK_FACTOR * wanted;
            let sql = match index_order(sort)?.filter(|_| walk) {
                Some((index, order)) => format!(
                    "SELECT {DESIGN_COLUMNS}, checksum FROM designs INDEXED BY {index} {} {order} \
                     LIMIT ? OFFSET ?",
                    w.sql()
                ),
                None => {
                    let order = sorted_order(query)?;
                    format!(
                        "SELECT {DESIGN_COLUMNS}, checksum FROM designs WHERE id IN \
                         (SELECT id FROM designs {} {order} LIMIT ? OFFSET ?) {order}",
                        w.sql()
                    )
                }
            };
            let mut stmt = self.conn.prepare_cached(&sql)?;
            let mut rows = stmt.query(params_from_iter(params.iter()))?;
            while let Some(row) = rows.next()? {
                out.push(read_design(row, 0)?.0);
            }
        }
        Ok(Page {
            total,
            offset: query.offset,
            rows: out,
        })
    }

    /// Designs per value of `facet` under every filter of `query` except the facet's own
    /// selection; most frequent first, then by value. Limit, offset and sort are ignored.
    pub fn facet_counts(&self, query: &DesignQuery, facet: Facet) -> StoreResult<Vec<FacetCount>> {
        let w = filters(query, Some(facet))?;
        let column = facet_column(facet);
        // Unfiltered, the facet's own index holds every value (a covering scan); filtered,
        // `+column` keeps SQLite from walking that index and fetching every row through it.
        let group = if w.is_empty() { "" } else { "+" };
        let sql = format!(
            "SELECT {column}, count(*) FROM designs {} GROUP BY {group}{column} \
             ORDER BY count(*) DESC, {column}",
            w.sql()
        );
        let mut stmt = self.conn.prepare_cached(&sql)?;
        let rows: Vec<(Value, i64)> = stmt
            .query_map(params_from_iter(w.params.iter()), |r| {
                Ok((r.get(0)?, r.get(1)?))
            })?
            .collect::<Result<_, _>>()?;
        rows.into_iter()
            .map(|(v, n)| {
                Ok(FacetCount {
                    value: facet_value(facet, v)?,
                    count: n as u64,
                })
            })
            .collect()
    }

    /// Counts of every facet under `query` (see [`Store::facet_counts`]).
    pub fn all_facet_counts(
        &self,
        query: &DesignQuery,
    ) -> StoreResult<Vec<(Facet, Vec<FacetCount>)>> {
        Facet::ALL
            .iter()
            .map(|&f| Ok((f, self.facet_counts(query, f)?)))
            .collect()
    }

    /// `x` and `y` of every design matching `query`'s filters that has both, in insertion
    /// order, at most `limit` points. Sort, limit and offset of the query are ignored.
    pub fn scatter(
        &self,
        query: &DesignQuery,
        x: Measure,
        y: Measure,
        limit: u32,
    ) -> StoreResult<Vec<ScatterPoint>> {
        let mut w = filters(query, None)?;
        let (cx, cy) = (x.column()?, y.column()?);
        w.push(format!("{cx} IS NOT NULL AND {cy} IS NOT NULL"), []);
        let sql = format!(
            "SELECT spec, {cx}, {cy}, family, behaviour FROM designs {} ORDER BY id LIMIT ?",
            w.sql()
        );
        let mut params = w.params.clone();
        params.push(Value::Integer(i64::from(limit)));
        let mut stmt = self.conn.prepare_cached(&sql)?;
        let rows = stmt
            .query_map(params_from_iter(params.iter()), |r| {
                Ok((
                    r.get::<_, String>(0)?,
                    r.get::<_, f64>(1)?,
                    r.get::<_, f64>(2)?,
                    r.get::<_, Value>(3)?,
                    r.get::<_, Value>(4)?,
                ))
            })?
            .collect::<Result<Vec<_>, _>>()?;
        rows.into_iter()
            .map(|(spec, x, y, family, behaviour)| {
                let unread = || StoreError::Damaged(format!("{spec}: family or behaviour unread"));
                let family = match facet_value(Facet::Family, family)? {
                    FacetValue::Family(f) => f,
                    _ => return Err(unread()),
                };
                let behaviour = match facet_value(Facet::Behaviour, behaviour)? {
                    FacetValue::Behaviour(b) => b,
                    _ => return Err(unread()),
                };
                Ok(ScatterPoint {
                    spec,
                    x,
                    y,
                    family,
                    behaviour,
                })
            })
            .collect()
    }
}

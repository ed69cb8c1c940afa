//! Candidates for inverse design: every design matching the target's family, cell and tile
//! constraints, with its stored deployment report, as the library's plain
//! [`Candidate`](isogami::inverse::Candidate) values. The library does the screening; this
//! module only selects and reads. When the constraints select nothing, every design is
//! read instead, so that the library can say which constraint removed them and what the
//! database holds ([`Store::inverse_candidates`]).

use crate::error::{StoreError, StoreResult};
use crate::open::Store;
use crate::query::filter::filters;
use crate::query::{DesignQuery, Measure, RangeFilter};
use crate::read::{record_from_row, typed};
use crate::rows::DESIGN_COLUMNS;
use isogami::inverse::{Candidate, Constraints};
use isogami::topology::Design;
use rusqlite::params_from_iter;

impl DesignQuery {
    /// The query selecting what `constraints` allow by family, cell and tile count (the
    /// constraints a database row can answer without deploying).
    pub fn for_constraints(constraints: &Constraints) -> DesignQuery {
        let mut q = DesignQuery {
            families: constraints.families.clone(),
            cells: constraints.cells.clone(),
            ..DesignQuery::default()
        };
        if constraints.min_tiles.is_some() || constraints.max_tiles.is_some() {
            q.ranges.push(RangeFilter {
                measure: Measure::TileCount,
                min: constraints.min_tiles.map(f64::from),
                max: constraints.max_tiles.map(f64::from),
            });
        }
        q
    }
}

impl Store {
    /// Every design matching `query`'s filters (its sort, limit and offset are ignored), in
    /// insertion order, each with its stored report; rows are checked against their
    /// checksums and reports parsed into the library's types.
    pub fn candidates(&self, query: &DesignQuery) -> StoreResult<Vec<Candidate>> {
        let w = filters(query, None)?;
        let sql = format!(
            "SELECT {DESIGN_COLUMNS}, d.checksum, x.report, x.linkages, x.checksum
             FROM designs d JOIN design_data x ON x.design = d.id {} ORDER BY d.id",
            w.sql()
        );
        let mut stmt = self.conn.prepare(&sql)?;
        let mut rows = stmt.query(params_from_iter(w.params.iter()))?;
        let mut out = Vec::new();
        while let Some(row) = rows.next()? {
            let stored = typed(record_from_row(row)?)?;
            let design: Design = stored.summary.spec.parse().map_err(|e| {
                StoreError::Damaged(format!(
                    "stored spec {} does not read: {e}",
                    stored.summary.spec
                ))
            })?;
            out.push(Candidate {
                design,
                topology: stored.summary.topology,
                report: Some(stored.report),
            });
        }
        Ok(out)
    }

    /// The candidates for a target with `constraints`: the designs they admit by family,
    /// cell and tile count; when they admit none, every design of the database (inverse
    /// design then refuses the run naming the constraint that removed them and how many).
    pub fn inverse_candidates(&self, constraints: &Constraints) -> StoreResult<Vec<Candidate>> {
        let admitted = self.candidates(&DesignQuery::for_constraints(constraints))?;
        if admitted.is_empty() {
            self.candidates(&DesignQuery::default())
        } else {
            Ok(admitted)
        }
    }
}

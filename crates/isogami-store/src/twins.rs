//! Cell twins stored once: an explored design found again on another cell of its family
//! (same shape, same path; `isogami::explore::dedup::twins`) keeps one row in `designs`, and
//! each other cell's spec is a row of the optional `cell_twins` table naming the design it is
//! stored with (checksum over both). Catalogue totals, pages and facets therefore count the
//! design once; [`Store::design`] lists its other cells and finds it by any of its specs.
//!
//! Like the motion classes, the twins depend only on the set of explored designs in the file:
//! writers recompute them in one transaction after `explore` commits units and after a merge
//! (which also copies the input's twin rows), so any job count, unit order or set of merged
//! shards stores the same designs. User designs are never merged away.

use crate::checksum;
use crate::error::StoreResult;
use crate::open::{Store, StoreWriter};
use crate::rows::{cell_twin_values, verify};
use isogami::explore::{cell_twins, TwinCandidate};
use isogami::mobility::MobilitySettings;
use isogami::topology::Design;
use rusqlite::params;

impl StoreWriter {
    /// Finds the cell twins among the explored designs and stores each once (see the module
    /// docs), in one transaction; returns how many designs it folded into a twin.
    pub fn refresh_cell_twins(&mut self) -> StoreResult<u64> {
        let candidates: Vec<TwinCandidate> = {
            let mut stmt = self.conn.prepare(
                "SELECT spec, max_area_ratio, end_area_ratio, max_expansion, min_expansion,
                        finite_covered IS NOT NULL
                 FROM designs WHERE origin = 'explored' ORDER BY spec",
            )?;
            let rows = stmt.query_map([], |r| {
                Ok((
                    r.get::<_, String>(0)?,
                    [
                        r.get::<_, f64>(1)?,
                        r.get::<_, Option<f64>>(2)?.unwrap_or(f64::NAN),
                        r.get::<_, f64>(3)?,
                        r.get::<_, f64>(4)?,
                    ],
                    r.get::<_, bool>(5)?,
                ))
            })?;
            let mut out = Vec::new();
            for row in rows {
                let (spec, path, one_dof_sheet) = row?;
                // A text that is no spec (a record made by hand) has no twin.
                if let Ok(design) = spec.parse::<Design>() {
                    out.push(TwinCandidate {
                        design,
                        spec,
                        path,
                        one_dof_sheet,
                    });
                }
            }
            out
        };
        let kept_by = cell_twins(&candidates, MobilitySettings::default());
        let tx = self.store.conn.transaction()?;
        // A twin row whose spec is a design again (a merge brought its unit back) is stale.
        tx.execute(
            "DELETE FROM cell_twins WHERE spec IN (SELECT spec FROM designs)",
            [],
        )?;
        let mut folded = 0;
        {
            let mut pointing = tx.prepare("SELECT spec FROM cell_twins WHERE kept = ?1")?;
            let mut put = tx.prepare(
                "INSERT OR REPLACE INTO cell_twins(spec, kept, checksum) VALUES (?1, ?2, ?3)",
            )?;
            let mut drop_data = tx.prepare(
                "DELETE FROM design_data WHERE design = (SELECT id FROM designs WHERE spec = ?1)",
            )?;
            let mut drop_design = tx.prepare("DELETE FROM designs WHERE spec = ?1")?;
            for (c, kept) in candidates.iter().zip(&kept_by) {
                let Some(k) = kept else { continue };
                let kept = &candidates[*k].spec;
                let earlier: Vec<String> = pointing
                    .query_map([&c.spec], |r| r.get(0))?
                    .collect::<Result<_, _>>()?;
                for spec in earlier.iter().chain(std::iter::once(&c.spec)) {
                    let sum = checksum::of_values(&cell_twin_values(spec, kept));
                    put.execute(params![spec, kept, sum])?;
                }
                drop_data.execute([&c.spec])?;
                drop_design.execute([&c.spec])?;
                folded += 1;
            }
        }
        tx.commit()?;
        Ok(folded)
    }
}

impl Store {
    /// Whether the file has the twins table (made or opened by a writer since it existed).
    fn has_cell_twins(&self) -> StoreResult<bool> {
        crate::open::has_table(&self.conn, "cell_twins")
    }

    /// The specs of the same design on other cells of its family, stored with `spec` (spec
    /// order; empty for a design without twins or a file without the table).
    pub fn other_cells(&self, spec: &str) -> StoreResult<Vec<String>> {
        Ok(self
            .twin_rows("WHERE kept = ?1 ORDER BY spec", spec)?
            .into_iter()
            .map(|(s, _)| s)
            .collect())
    }

    /// The spec of the design that `spec` is stored with, when `spec` is a cell twin.
    pub fn stored_as(&self, spec: &str) -> StoreResult<Option<String>> {
        Ok(self
            .twin_rows("WHERE spec = ?1", spec)?
            .into_iter()
            .next()
            .map(|(_, kept)| kept))
    }

    /// Every twin row as (twin spec, spec it is stored with), in spec order (checksums
    /// verified).
    pub fn cell_twins(&self) -> StoreResult<Vec<(String, String)>> {
        self.twin_rows("WHERE ?1 = ?1 ORDER BY spec", "")
    }

    fn twin_rows(&self, filter: &str, arg: &str) -> StoreResult<Vec<(String, String)>> {
        if !self.has_cell_twins()? {
            return Ok(Vec::new());
        }
        let mut stmt = self.conn.prepare_cached(&format!(
            "SELECT spec, kept, checksum FROM cell_twins {filter}"
        ))?;
        let rows = stmt.query_map([arg], |r| {
            Ok((
                r.get::<_, String>(0)?,
                r.get::<_, String>(1)?,
                r.get::<_, i64>(2)?,
            ))
        })?;
        let mut out = Vec::new();
        for row in rows {
            let (spec, kept, stored) = row?;
            verify(&cell_twin_values(&spec, &kept), stored, || {
                format!("cell twin row of {spec}")
            })?;
            out.push((spec, kept));
        }
        Ok(out)
    }

    /// Number of cell twins stored with another design.
    pub fn cell_twin_count(&self) -> StoreResult<u64> {
        if !self.has_cell_twins()? {
            return Ok(0);
        }
        let n: i64 = self
            .conn
            .query_row("SELECT count(*) FROM cell_twins", [], |r| r.get(0))?;
        Ok(n as u64)
    }
}

//! `isogami db migrate` of a schema-3 file: the same rows with the finite-sheet columns
//! (issue 22) added and filled.
//!
//! Nothing about a version-3 row is wrong, it only lacks two figures, so the file is copied
//! (the old one is only read) rather than explored again: the copy gets the two columns and
//! their indexes, every explored design's figures are computed from its spec with the run's
//! settings (`isogami::catalog::finite_figures`: deployed again, then the finite 6×6 patch —
//! the values a new exploration stores, tested), and every row's checksum is made anew over
//! its new values, after its old checksum was verified. User designs keep the columns empty,
//! as a user design saved today does. Parts of split units still waiting for their siblings
//! keep their entries as they are: their designs get empty columns when the unit is joined.
//! The copy is written beside the new file and renamed into place only when complete, then
//! opened with the full check.

use crate::checksum;
use crate::error::{StoreError, StoreResult};
use crate::open::{put_meta, reader_connection, Check, StoreWriter};
use crate::records::Origin;
use crate::rows::{design_from_values, design_values, DESIGN_COLUMNS, DESIGN_COLUMN_COUNT_V3};
use crate::schema::{FINITE_INDEXES, SCHEMA_VERSION};
use isogami::catalog::{finite_figures, CatalogSettings, FiniteFigures};
use isogami::topology::Design;
use rayon::prelude::*;
use rusqlite::types::Value;
use rusqlite::{params_from_iter, Connection};
use serde::Serialize;
use std::path::Path;

/// What the upgrade of a schema-3 file did.
#[derive(Debug, Clone, Default, Serialize)]
pub struct FiniteFill {
    /// Designs in the file.
    pub designs: usize,
    /// Explored designs whose figures were computed.
    pub computed: usize,
    /// Of these, designs whose 6×6 patch has no one-DOF sheet (covered fraction empty).
    pub no_one_dof_sheet: usize,
    /// User designs (columns left empty).
    pub user_designs: usize,
    /// Explored designs whose figures could not be computed (columns left empty): (spec,
    /// reason).
    pub failed: Vec<(String, String)>,
}

/// One `designs` row of the old file: id, values (schema-3 columns) and origin.
struct OldRow {
    id: i64,
    values: Vec<Value>,
    spec: String,
    explored: bool,
}

/// Copies the schema-3 database `from` into `into` (a new path) with the finite-sheet
/// columns filled, computing them on `jobs` threads.
pub(crate) fn fill_finite_columns(
    from: &Path,
    into: &Path,
    settings: Option<CatalogSettings>,
    jobs: usize,
) -> StoreResult<FiniteFill> {
    if into.exists() {
        return Err(StoreError::Damaged(format!(
            "{} already exists: an upgrade writes a new file",
            into.display()
        )));
    }
    let partial = into.with_extension("migrating");
    // Left behind by an interrupted upgrade: ours to replace.
    let _ = std::fs::remove_file(&partial);
    std::fs::copy(from, &partial)?;
    let result = fill(&partial, settings, jobs);
    match result {
        Ok(fill) => {
            std::fs::rename(&partial, into)?;
            // The new file as every writer opens it, fully checked.
            StoreWriter::open(into, None, Check::Full)?;
            Ok(fill)
        }
        Err(e) => {
            let _ = std::fs::remove_file(&partial);
            Err(e)
        }
    }
}

/// Adds and fills the columns in the copy at `path`, in one transaction.
fn fill(path: &Path, settings: Option<CatalogSettings>, jobs: usize) -> StoreResult<FiniteFill> {
    let rows = old_rows(path)?;
    let mut out = FiniteFill {
        designs: rows.len(),
        ..FiniteFill::default()
    };
    if rows.iter().any(|r| r.explored) && settings.is_none() {
        return Err(StoreError::Damaged(
            "explored designs but no readable settings".into(),
        ));
    }
    let settings = settings.unwrap_or_default();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.max(1))
        .build()
        .map_err(|e| StoreError::Io(std::io::Error::other(e.to_string())))?;
    let figures: Vec<Option<Result<FiniteFigures, String>>> = pool.install(|| {
        rows.par_iter()
            .map(|r| {
                r.explored.then(|| {
                    let design: Design = r.spec.parse().map_err(|e| format!("{e}"))?;
                    finite_figures(&design, &settings).map_err(|e| e.to_string())
                })
            })
            .collect()
    });
    let mut conn = Connection::open(path)?;
    let tx = conn.transaction()?;
    tx.execute_batch(
        "ALTER TABLE designs ADD COLUMN finite_raw_dof INTEGER;
         ALTER TABLE designs ADD COLUMN finite_covered REAL;",
    )?;
    tx.execute_batch(FINITE_INDEXES)?;
    {
        let mut update = tx.prepare(
            "UPDATE designs SET finite_raw_dof = ?1, finite_covered = ?2, checksum = ?3 \
             WHERE id = ?4",
        )?;
        for (row, figures) in rows.iter().zip(figures) {
            let (mut summary, work_unit) = design_from_values(&row.values)
                .map_err(|e| StoreError::Damaged(format!("design row {}: {e}", row.spec)))?;
            match figures {
                None => out.user_designs += 1,
                Some(Ok(f)) => {
                    out.computed += 1;
                    out.no_one_dof_sheet += usize::from(f.covered.is_none());
                    summary.finite_raw_dof = u32::try_from(f.raw_dof).ok();
                    summary.finite_covered = f.covered;
                }
                Some(Err(reason)) => out.failed.push((row.spec.clone(), reason)),
            }
            let values = design_values(&summary, work_unit.as_deref());
            let n = values.len();
            update.execute(params_from_iter([
                values[n - 2].clone(),
                values[n - 1].clone(),
                Value::Integer(checksum::of_values(&values)),
                Value::Integer(row.id),
            ]))?;
        }
    }
    put_meta(&tx, "schema_version", &SCHEMA_VERSION.to_string())?;
    tx.commit()?;
    Ok(out)
}

/// Every `designs` row of the schema-3 file at `path`, its checksum verified.
fn old_rows(path: &Path) -> StoreResult<Vec<OldRow>> {
    let conn = reader_connection(path, false)?;
    let old_columns: Vec<&str> = DESIGN_COLUMNS
        .split(',')
        .map(str::trim)
        .take(DESIGN_COLUMN_COUNT_V3)
        .collect();
    let mut stmt = conn.prepare(&format!(
        "SELECT id, {}, checksum FROM designs ORDER BY id",
        old_columns.join(", ")
    ))?;
    let mut rows = stmt.query([])?;
    let mut out = Vec::new();
    while let Some(r) = rows.next()? {
        let id: i64 = r.get(0)?;
        let values = crate::rows::raw_values(r, 1, DESIGN_COLUMN_COUNT_V3)?;
        let stored: i64 = r.get(1 + DESIGN_COLUMN_COUNT_V3)?;
        let spec = match values.first() {
            Some(Value::Text(s)) => s.clone(),
            _ => "?".into(),
        };
        crate::rows::verify(&values, stored, || format!("design row {spec}"))?;
        let origin = match values.get(1) {
            Some(Value::Text(o)) => Origin::from_name(o),
            _ => None,
        };
        out.push(OldRow {
            id,
            values,
            explored: origin == Some(Origin::Explored),
            spec,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exploration::{explore_into, ExploreRequest};
    use crate::migrate::migrate;
    use crate::open::{meta, Store};
    use crate::records::DesignRecord;
    use crate::rows::raw_values;
    use isogami::tiling::Family;
    use std::sync::atomic::AtomicBool;

    /// Turns a current file into the schema-3 file old isogami wrote: no finite-sheet columns
    /// or indexes, checksums over the old columns, version 3.
    fn downgrade(path: &Path) {
        let conn = Connection::open(path).unwrap();
        conn.execute_batch(
            "DROP INDEX designs_finite_raw_dof; DROP INDEX designs_finite_covered;
             DROP INDEX designs_finite_raw_dof_nulls_last;
             DROP INDEX designs_finite_covered_nulls_last;
             ALTER TABLE designs DROP COLUMN finite_raw_dof;
             ALTER TABLE designs DROP COLUMN finite_covered;",
        )
        .unwrap();
        let old: Vec<&str> = DESIGN_COLUMNS
            .split(',')
            .map(str::trim)
            .take(DESIGN_COLUMN_COUNT_V3)
            .collect();
        let rows: Vec<(i64, i64)> = conn
            .prepare(&format!("SELECT id, {} FROM designs", old.join(", ")))
            .unwrap()
            .query_map([], |r| {
                let values = raw_values(r, 1, DESIGN_COLUMN_COUNT_V3)?;
                Ok((r.get(0)?, checksum::of_values(&values)))
            })
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        for (id, sum) in rows {
            conn.execute("UPDATE designs SET checksum = ?1 WHERE id = ?2", [sum, id])
                .unwrap();
        }
        put_meta(&conn, "schema_version", "3").unwrap();
    }

    #[test]
    fn a_schema_3_file_is_refused_then_upgraded_to_what_exploring_stores() {
        let dir = tempfile::Builder::new()
            .prefix("isogami-store-migrate-finite-")
            .tempdir()
            .unwrap();
        let fresh = dir.path().join("fresh.db");
        let request = ExploreRequest {
            settings: CatalogSettings::default().quick(),
            families: vec![
                // Triangles (no shape parameters) and a hexagon with some.
                Family::from_number(83).unwrap(),
                Family::from_number(28).unwrap(),
            ],
            cells: None,
            shard: None,
            jobs: 2,
            parts: 1,
        };
        let outcome = explore_into(&fresh, &request, &mut |_| {}, &AtomicBool::new(false)).unwrap();
        assert!(outcome.failures.is_empty(), "{:?}", outcome.failures);
        let user = {
            let s = Store::open_read(&fresh, Check::Quick).unwrap();
            let e = s
                .summaries()
                .unwrap()
                .into_iter()
                .find(|e| !e.spec.parse::<Design>().unwrap().params.is_empty())
                .unwrap();
            let design: Design = e.spec.parse().unwrap();
            let mut params = design.params.clone();
            params[0] *= 1.01;
            let design = design.at_params(&params);
            let report = s.design(&e.spec).unwrap().unwrap().report;
            DesignRecord::from_parts(&design, "user", Origin::User, &report, None).unwrap()
        };
        StoreWriter::open(&fresh, None, Check::Quick)
            .unwrap()
            .save_user_design(&user)
            .unwrap();
        let want = Store::open_read(&fresh, Check::Full)
            .unwrap()
            .summaries()
            .unwrap();
        assert!(want.iter().any(|s| s.finite_raw_dof.is_some()));

        let old = dir.path().join("old.db");
        std::fs::copy(&fresh, &old).unwrap();
        downgrade(&old);
        let before = std::fs::read(&old).unwrap();
        let e = Store::open_read(&old, Check::Quick).unwrap_err();
        assert!(matches!(e, StoreError::NoFiniteColumns), "{e:?}");
        assert!(e.to_string().contains("isogami db migrate"), "{e}");

        let new = dir.path().join("new.db");
        let outcome = migrate(&old, &new, 2, &mut |_| {}, &AtomicBool::new(false)).unwrap();
        assert_eq!(
            std::fs::read(&old).unwrap(),
            before,
            "the old file is only read"
        );
        assert_eq!(outcome.from_version, 3);
        let fill = outcome.finite.unwrap();
        assert_eq!((fill.designs, fill.user_designs), (want.len(), 1));
        assert_eq!(fill.computed, want.len() - 1);
        assert!(fill.failed.is_empty(), "{:?}", fill.failed);

        let got = Store::open_read(&new, Check::Full).unwrap();
        assert_eq!(
            got.summaries().unwrap(),
            want,
            "the values exploring stores"
        );
        assert_eq!(
            meta(&got.conn, "schema_version").unwrap().as_deref(),
            Some("4")
        );
        // Its queries use the new columns' indexes like a new file's.
        let mut q = crate::DesignQuery::default();
        q.sort_by(
            crate::SortKey::Measure(crate::Measure::FiniteCovered),
            false,
        );
        assert_eq!(got.page(&q).unwrap().total, want.len() as u64);
        // A second upgrade into the same file is refused; the file stays.
        assert!(migrate(&old, &new, 1, &mut |_| {}, &AtomicBool::new(false)).is_err());
        Store::open_read(&new, Check::Full).unwrap();
    }
}

//! `isogami db migrate` of a schema-3 or schema-4 file: the same rows with the columns the
//! file lacks added and filled: the finite-sheet ones (issue 22, missing in version 3) and
//! the margins (issue 40, missing in versions 3 and 4).
//!
//! Nothing about such a row is wrong, it only lacks figures, so the file is copied (the old
//! one is only read) rather than explored again: the copy gets the columns and their indexes,
//! every explored design's figures are computed from its spec with the run's settings
//! (`isogami::catalog::finite_figures` and `isogami::catalog::margins`: deployed again — the
//! values a new exploration stores, tested), and every row's checksum is made anew over its
//! new values, after its old checksum was verified. User designs keep the columns empty, as
//! a user design saved today does. Parts of split units still waiting for their siblings
//! keep their entries as they are: their designs get empty columns when the unit is joined.
//! The copy is written beside the new file and renamed into place only when complete, then
//! opened with the full check.

use crate::checksum;
use crate::error::{StoreError, StoreResult};
use crate::open::{put_meta, reader_connection, Check, StoreWriter};
use crate::records::{DesignSummary, Origin};
use crate::rows::{
    design_from_values, design_values, DESIGN_COLUMNS, DESIGN_COLUMN_COUNT, DESIGN_COLUMN_COUNT_V3,
    DESIGN_COLUMN_COUNT_V4,
};
use crate::schema::{
    BEFORE_FINITE_COLUMNS, BEFORE_MARGIN_COLUMNS, FINITE_INDEXES, MARGIN_INDEXES, SCHEMA_VERSION,
};
use isogami::catalog::{finite_figures, margins, CatalogSettings, FiniteFigures, Margins};
use isogami::topology::Design;
use rayon::prelude::*;
use rusqlite::types::Value;
use rusqlite::{params_from_iter, Connection};
use serde::Serialize;
use std::path::Path;

/// What the upgrade of a schema-3 or schema-4 file did.
#[derive(Debug, Clone, Default, Serialize)]
pub struct ColumnFill {
    /// Designs in the file.
    pub designs: usize,
    /// Explored designs whose figures were computed.
    pub computed: usize,
    /// Of these, designs whose 6×6 patch has no one-DOF sheet (covered fraction empty);
    /// counted only when the finite-sheet figures were computed (a schema-3 file).
    pub no_one_dof_sheet: usize,
    /// Of these, special designs (shape tolerance 0).
    pub special: usize,
    /// User designs (columns left empty).
    pub user_designs: usize,
    /// Explored designs whose figures could not be computed (columns left empty): (spec,
    /// reason).
    pub failed: Vec<(String, String)>,
}

/// The columns a file of `version` lacks, in the order of [`DESIGN_COLUMNS`] (the missing
/// ones are always its last), with their SQL types, and the indexes to make.
fn missing_columns(version: i64) -> StoreResult<(usize, &'static [&'static str], String)> {
    const FINITE: [&str; 2] = ["finite_raw_dof INTEGER", "finite_covered REAL"];
    const BOTH: [&str; 6] = [
        FINITE[0],
        FINITE[1],
        "open_t REAL",
        "end_area_ratio REAL",
        "shape_tolerance REAL",
        "fabrication_kept REAL",
    ];
    match version {
        BEFORE_FINITE_COLUMNS => Ok((
            DESIGN_COLUMN_COUNT_V3,
            &BOTH,
            format!("{FINITE_INDEXES}{MARGIN_INDEXES}"),
        )),
        BEFORE_MARGIN_COLUMNS => Ok((DESIGN_COLUMN_COUNT_V4, &BOTH[2..], MARGIN_INDEXES.into())),
        _ => Err(StoreError::Damaged(format!(
            "schema version {version} has no column upgrade"
        ))),
    }
}

/// One `designs` row of the old file: id, values (the old version's columns) and origin.
struct OldRow {
    id: i64,
    values: Vec<Value>,
    spec: String,
    explored: bool,
}

/// The figures computed for one explored design.
struct Figures {
    finite: Option<FiniteFigures>,
    margins: Margins,
}

/// Copies the schema-`version` database `from` (3 or 4) into `into` (a new path) with the
/// columns it lacks filled, computing them on `jobs` threads.
pub(crate) fn fill_columns(
    from: &Path,
    into: &Path,
    version: i64,
    settings: Option<CatalogSettings>,
    jobs: usize,
) -> StoreResult<ColumnFill> {
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
    let result = fill(&partial, version, settings, jobs);
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
fn fill(
    path: &Path,
    version: i64,
    settings: Option<CatalogSettings>,
    jobs: usize,
) -> StoreResult<ColumnFill> {
    let (old_count, added, indexes) = missing_columns(version)?;
    let rows = old_rows(path, old_count)?;
    let mut out = ColumnFill {
        designs: rows.len(),
        ..ColumnFill::default()
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
    let with_finite = version == BEFORE_FINITE_COLUMNS;
    let figures: Vec<Option<Result<Figures, String>>> = pool.install(|| {
        rows.par_iter()
            .map(|r| {
                r.explored.then(|| {
                    let design: Design = r.spec.parse().map_err(|e| format!("{e}"))?;
                    let finite = with_finite
                        .then(|| finite_figures(&design, &settings))
                        .transpose()
                        .map_err(|e| e.to_string())?;
                    let margins = margins(&design, &settings).map_err(|e| e.to_string())?;
                    Ok(Figures { finite, margins })
                })
            })
            .collect()
    });
    let mut conn = Connection::open(path)?;
    let tx = conn.transaction()?;
    for column in added {
        tx.execute_batch(&format!("ALTER TABLE designs ADD COLUMN {column};"))?;
    }
    tx.execute_batch(&indexes)?;
    {
        let names: Vec<&str> = DESIGN_COLUMNS.split(',').map(str::trim).collect();
        let sets: Vec<String> = (old_count..DESIGN_COLUMN_COUNT)
            .enumerate()
            .map(|(k, c)| format!("{} = ?{}", names[c], k + 1))
            .collect();
        let n = DESIGN_COLUMN_COUNT - old_count;
        let mut update = tx.prepare(&format!(
            "UPDATE designs SET {}, checksum = ?{} WHERE id = ?{}",
            sets.join(", "),
            n + 1,
            n + 2
        ))?;
        for (row, figures) in rows.iter().zip(figures) {
            let mut padded = row.values.clone();
            padded.resize(DESIGN_COLUMN_COUNT, Value::Null);
            let (mut summary, work_unit) = design_from_values(&padded)
                .map_err(|e| StoreError::Damaged(format!("design row {}: {e}", row.spec)))?;
            match figures {
                None => out.user_designs += 1,
                Some(Ok(f)) => {
                    out.computed += 1;
                    if let Some(finite) = f.finite {
                        out.no_one_dof_sheet += usize::from(finite.covered.is_none());
                        summary.finite_raw_dof = u32::try_from(finite.raw_dof).ok();
                        summary.finite_covered = finite.covered;
                    }
                    out.special += usize::from(f.margins.is_special());
                    set_margins(&mut summary, &f.margins);
                }
                Some(Err(reason)) => out.failed.push((row.spec.clone(), reason)),
            }
            let values = design_values(&summary, work_unit.as_deref());
            let mut bound: Vec<Value> = values[old_count..].to_vec();
            bound.push(Value::Integer(checksum::of_values(&values)));
            bound.push(Value::Integer(row.id));
            update.execute(params_from_iter(bound))?;
        }
    }
    put_meta(&tx, "schema_version", &SCHEMA_VERSION.to_string())?;
    tx.commit()?;
    Ok(out)
}

/// Writes `m` into a summary's margin fields (as `DesignRecord::with_margins` does).
fn set_margins(summary: &mut DesignSummary, m: &Margins) {
    summary.open_t = Some(m.open_t);
    summary.end_area_ratio = Some(m.end_area_ratio);
    summary.shape_tolerance = m.shape_tolerance;
    summary.fabrication_kept = m.fabrication_kept;
}

/// Every `designs` row of the old file at `path` with its first `count` columns, its
/// checksum verified.
fn old_rows(path: &Path, count: usize) -> StoreResult<Vec<OldRow>> {
    let conn = reader_connection(path, false)?;
    let old_columns: Vec<&str> = DESIGN_COLUMNS
        .split(',')
        .map(str::trim)
        .take(count)
        .collect();
    let mut stmt = conn.prepare(&format!(
        "SELECT id, {}, checksum FROM designs ORDER BY id",
        old_columns.join(", ")
    ))?;
    let mut rows = stmt.query([])?;
    let mut out = Vec::new();
    while let Some(r) = rows.next()? {
        let id: i64 = r.get(0)?;
        let values = crate::rows::raw_values(r, 1, count)?;
        let stored: i64 = r.get(1 + count)?;
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

    /// Turns a current file into the schema-`version` file (3 or 4) old isogami wrote: without
    /// the columns and indexes that version lacked, checksums over its columns, its version.
    fn downgrade(path: &Path, version: i64) {
        let conn = Connection::open(path).unwrap();
        let margins = [
            "open_t",
            "end_area_ratio",
            "shape_tolerance",
            "fabrication_kept",
        ];
        let finite = ["finite_raw_dof", "finite_covered"];
        let mut dropped: Vec<&str> = margins.to_vec();
        if version == 3 {
            dropped.extend(finite);
        }
        for column in &dropped {
            conn.execute_batch(&format!(
                "DROP INDEX designs_{column}; DROP INDEX designs_{column}_nulls_last;
                 ALTER TABLE designs DROP COLUMN {column};"
            ))
            .unwrap();
        }
        let count = DESIGN_COLUMN_COUNT - dropped.len();
        let old: Vec<&str> = DESIGN_COLUMNS
            .split(',')
            .map(str::trim)
            .take(count)
            .collect();
        let rows: Vec<(i64, i64)> = conn
            .prepare(&format!("SELECT id, {} FROM designs", old.join(", ")))
            .unwrap()
            .query_map([], |r| {
                let values = raw_values(r, 1, count)?;
                Ok((r.get(0)?, checksum::of_values(&values)))
            })
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        for (id, sum) in rows {
            conn.execute("UPDATE designs SET checksum = ?1 WHERE id = ?2", [sum, id])
                .unwrap();
        }
        put_meta(&conn, "schema_version", &version.to_string()).unwrap();
    }

    #[test]
    fn schema_3_and_4_files_are_refused_then_upgraded_to_what_exploring_stores() {
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
        assert!(want
            .iter()
            .any(|s| s.shape_tolerance.is_some() && s.open_t.is_some()));
        for version in [3, 4] {
            upgraded_is_fresh(dir.path(), &fresh, &want, version);
        }
    }

    /// Downgrades a copy of `fresh` to `version`, checks that it is refused naming the
    /// migration, migrates it and compares the result with `want`.
    fn upgraded_is_fresh(dir: &Path, fresh: &Path, want: &[DesignSummary], version: i64) {
        let old = dir.join(format!("old{version}.db"));
        std::fs::copy(fresh, &old).unwrap();
        downgrade(&old, version);
        let before = std::fs::read(&old).unwrap();
        let e = Store::open_read(&old, Check::Quick).unwrap_err();
        match version {
            3 => assert!(matches!(e, StoreError::NoFiniteColumns), "{e:?}"),
            _ => assert!(matches!(e, StoreError::NoMarginColumns), "{e:?}"),
        }
        assert!(e.to_string().contains("isogami db migrate"), "{e}");

        let new = dir.join(format!("new{version}.db"));
        let outcome = migrate(&old, &new, 2, &mut |_| {}, &AtomicBool::new(false)).unwrap();
        assert_eq!(
            std::fs::read(&old).unwrap(),
            before,
            "the old file is only read"
        );
        assert_eq!(outcome.from_version, version);
        let fill = outcome.columns.unwrap();
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
            Some(SCHEMA_VERSION.to_string().as_str())
        );
        // Its queries use the new columns' indexes like a new file's.
        let mut q = crate::DesignQuery::default();
        q.sort_by(
            crate::SortKey::Measure(if version == 3 {
                crate::Measure::FiniteCovered
            } else {
                crate::Measure::ShapeTolerance
            }),
            false,
        );
        assert_eq!(got.page(&q).unwrap().total, want.len() as u64);
        // A second upgrade into the same file is refused; the file stays.
        assert!(migrate(&old, &new, 1, &mut |_| {}, &AtomicBool::new(false)).is_err());
        Store::open_read(&new, Check::Full).unwrap();
    }
}

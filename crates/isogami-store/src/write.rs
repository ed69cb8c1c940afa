//! Writing: a work unit with its stages and designs in one transaction, and user designs.

use crate::checksum;
use crate::error::{StoreError, StoreResult};
use crate::open::StoreWriter;
use crate::records::{DesignRecord, Origin, StageCount, UnitRecords, WorkUnitRecord};
use crate::rows::{
    data_values, design_values, unit_memory_values, unit_values, DESIGN_COLUMNS,
    DESIGN_COLUMN_COUNT,
};
use rusqlite::types::Value;
use rusqlite::{params, params_from_iter, Connection};

/// Inserts a work unit and its stage rows, and drops any parts of it still waiting (left by a
/// run that split the unit, when the unit then came whole).
pub(crate) fn insert_unit(
    conn: &Connection,
    unit: &WorkUnitRecord,
    stages: &[StageCount],
) -> StoreResult<()> {
    conn.execute(
        "INSERT INTO work_units(id, family, cell, kind, seconds, finished_at, checksum)
         VALUES (?1, ?2, ?3, ?4, ?5, datetime('now'), ?6)",
        params![
            unit.id,
            unit.family,
            unit.cell,
            unit.kind,
            unit.seconds,
            checksum::of_values(&unit_values(unit, stages))
        ],
    )?;
    if let Some(bytes) = unit.peak_rss_bytes {
        let bytes = i64::try_from(bytes).unwrap_or(i64::MAX);
        conn.execute(
            "INSERT OR REPLACE INTO unit_memory(work_unit, peak_rss_bytes, checksum) VALUES (?1, ?2, ?3)",
            params![
                unit.id,
                bytes,
                checksum::of_values(&unit_memory_values(&unit.id, bytes))
            ],
        )?;
    }
    conn.execute("DELETE FROM unit_parts WHERE work_unit = ?1", [&unit.id])?;
    let mut st = conn.prepare_cached(
        "INSERT INTO stage_counts(work_unit, position, stage, count_in, count_out, seconds)
         VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
    )?;
    for (k, s) in stages.iter().enumerate() {
        st.execute(params![
            unit.id,
            k as i64,
            s.stage,
            s.count_in as i64,
            s.count_out as i64,
            s.seconds
        ])?;
    }
    Ok(())
}

/// Inserts a finished unit: its row, stage rows and designs (inside the caller's transaction).
pub(crate) fn insert_records(conn: &Connection, records: &UnitRecords) -> StoreResult<()> {
    insert_unit(conn, &records.unit, &records.stages)?;
    for d in &records.designs {
        insert_design(conn, d, Some(&records.unit.id))?;
    }
    Ok(())
}

/// Inserts a design's summary row and its data row.
pub(crate) fn insert_design(
    conn: &Connection,
    record: &DesignRecord,
    work_unit: Option<&str>,
) -> StoreResult<()> {
    let mut values = design_values(&record.summary, work_unit);
    let sum = checksum::of_values(&values);
    values.push(Value::Integer(sum));
    let placeholders = vec!["?"; DESIGN_COLUMN_COUNT + 1].join(", ");
    let mut stmt = conn.prepare_cached(&format!(
        "INSERT INTO designs({DESIGN_COLUMNS}, checksum) VALUES ({placeholders})"
    ))?;
    let inserted = stmt.execute(params_from_iter(values.iter()));
    if let Err(rusqlite::Error::SqliteFailure(f, _)) = &inserted {
        if f.extended_code == rusqlite::ffi::SQLITE_CONSTRAINT_UNIQUE {
            return Err(StoreError::DuplicateSpec(record.summary.spec.clone()));
        }
    }
    inserted?;
    let id = conn.last_insert_rowid();
    let data = data_values(
        &record.summary.spec,
        &record.report,
        record.linkages.as_deref(),
    );
    conn.prepare_cached(
        "INSERT INTO design_data(design, report, linkages, checksum) VALUES (?1, ?2, ?3, ?4)",
    )?
    .execute(params![
        id,
        record.report,
        record.linkages,
        checksum::of_values(&data)
    ])?;
    Ok(())
}

impl StoreWriter {
    /// Writes a finished work unit, its stage counts and its designs in one transaction:
    /// either all of it is in the file afterwards or none of it. Its designs must have origin
    /// `explored`.
    pub fn commit_unit(&mut self, records: &UnitRecords) -> StoreResult<()> {
        if let Some(d) = records
            .designs
            .iter()
            .find(|d| d.summary.origin != Origin::Explored)
        {
            return Err(StoreError::InvalidRecord {
                spec: d.summary.spec.clone(),
                problem: "a work unit's designs must have origin 'explored'".into(),
            });
        }
        let tx = self.store.conn.transaction()?;
        insert_records(&tx, records)?;
        tx.commit()?;
        Ok(())
    }

    /// Saves a design a user made (origin `user`), e.g. from live editing. A spec already in
    /// the database is refused with [`StoreError::DuplicateSpec`].
    pub fn save_user_design(&mut self, record: &DesignRecord) -> StoreResult<()> {
        if record.summary.origin != Origin::User {
            return Err(StoreError::InvalidRecord {
                spec: record.summary.spec.clone(),
                problem: "a saved user design must have origin 'user'".into(),
            });
        }
        let tx = self.store.conn.transaction()?;
        insert_design(&tx, record, None)?;
        tx.commit()?;
        Ok(())
    }
}

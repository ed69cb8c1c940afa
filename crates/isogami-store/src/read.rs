//! Typed reads of what the store holds; every row is checked against its checksum.

use crate::error::{StoreError, StoreResult};
use crate::open::Store;
use crate::records::{DesignRecord, DesignSummary, StageCount, StoredDesign, WorkUnitRecord};
use crate::rows::{
    data_values, read_design, unit_memory_values, unit_values, verify, DESIGN_COLUMNS,
};
use isogami::deploy::DeploymentReport;
use isogami::linkage::LinkageAnalysis;
use rusqlite::OptionalExtension;
use std::collections::{HashMap, HashSet};

/// `designs` columns, checksum, then the `design_data` columns (report, linkages, checksum).
fn record_select(filter: &str) -> String {
    format!(
        "SELECT {DESIGN_COLUMNS}, d.checksum, x.report, x.linkages, x.checksum
         FROM designs d JOIN design_data x ON x.design = d.id {filter}"
    )
}

/// Reads one joined row as a verified record.
pub(crate) fn record_from_row(row: &rusqlite::Row<'_>) -> StoreResult<DesignRecord> {
    let (summary, _) = read_design(row, 0)?;
    let base = crate::rows::DESIGN_COLUMN_COUNT + 1;
    let report: String = row.get(base)?;
    let linkages: Option<String> = row.get(base + 1)?;
    let stored: i64 = row.get(base + 2)?;
    verify(
        &data_values(&summary.spec, &report, linkages.as_deref()),
        stored,
        || format!("stored results of {}", summary.spec),
    )?;
    Ok(DesignRecord {
        summary,
        report,
        linkages,
    })
}

/// Parses a verified record into the library's types.
pub(crate) fn typed(record: DesignRecord) -> StoreResult<StoredDesign> {
    let spec = record.summary.spec.clone();
    let stored_json = |what: &'static str, e: serde_json::Error| StoreError::StoredJson {
        spec: spec.clone(),
        what,
        message: e.to_string(),
    };
    let report: DeploymentReport =
        serde_json::from_str(&record.report).map_err(|e| stored_json("deployment report", e))?;
    let linkages: Option<LinkageAnalysis> = record
        .linkages
        .as_deref()
        .map(serde_json::from_str)
        .transpose()
        .map_err(|e| stored_json("linkage analysis", e))?;
    Ok(StoredDesign {
        summary: record.summary,
        report,
        linkages,
        other_cells: Vec::new(),
    })
}

impl Store {
    /// Ids of every committed work unit.
    pub fn done_units(&self) -> StoreResult<HashSet<String>> {
        let mut stmt = self.conn.prepare("SELECT id FROM work_units")?;
        let ids = stmt
            .query_map([], |r| r.get(0))?
            .collect::<Result<_, _>>()?;
        Ok(ids)
    }

    /// Every work unit with its stage counts, ordered by id.
    pub fn work_units(&self) -> StoreResult<Vec<(WorkUnitRecord, Vec<StageCount>)>> {
        let mut stmt = self.conn.prepare(
            "SELECT id, family, cell, kind, seconds, checksum FROM work_units ORDER BY id",
        )?;
        let units: Vec<(WorkUnitRecord, i64)> = stmt
            .query_map([], |r| {
                Ok((
                    WorkUnitRecord {
                        id: r.get(0)?,
                        family: r.get(1)?,
                        cell: r.get(2)?,
                        kind: r.get(3)?,
                        seconds: r.get(4)?,
                        peak_rss_bytes: None,
                    },
                    r.get(5)?,
                ))
            })?
            .collect::<Result<_, _>>()?;
        let memory = self.unit_memory()?;
        let mut st = self.conn.prepare(
            "SELECT stage, count_in, count_out, seconds FROM stage_counts
             WHERE work_unit = ?1 ORDER BY position",
        )?;
        units
            .into_iter()
            .map(|(mut u, stored)| {
                u.peak_rss_bytes = memory.get(&u.id).copied();
                let stages: Vec<StageCount> = st
                    .query_map([&u.id], |r| {
                        Ok(StageCount {
                            stage: r.get(0)?,
                            count_in: r.get::<_, i64>(1)? as u64,
                            count_out: r.get::<_, i64>(2)? as u64,
                            seconds: r.get(3)?,
                        })
                    })?
                    .collect::<Result<_, _>>()?;
                verify(&unit_values(&u, &stages), stored, || {
                    format!("work unit {}", u.id)
                })?;
                Ok((u, stages))
            })
            .collect()
    }

    /// Peak memory per work unit id, checksum-verified; empty when the database has no
    /// `unit_memory` table (made before it existed).
    fn unit_memory(&self) -> StoreResult<HashMap<String, u64>> {
        if !crate::open::has_table(&self.conn, "unit_memory")? {
            return Ok(HashMap::new());
        }
        let mut stmt = self
            .conn
            .prepare("SELECT work_unit, peak_rss_bytes, checksum FROM unit_memory")?;
        let rows: Vec<(String, i64, i64)> = stmt
            .query_map([], |r| Ok((r.get(0)?, r.get(1)?, r.get(2)?)))?
            .collect::<Result<_, _>>()?;
        rows.into_iter()
            .map(|(unit, bytes, stored)| {
                verify(&unit_memory_values(&unit, bytes), stored, || {
                    format!("memory row of work unit {unit}")
                })?;
                let bytes = u64::try_from(bytes).map_err(|_| {
                    StoreError::Damaged(format!("work unit {unit}: negative peak memory"))
                })?;
                Ok((unit, bytes))
            })
            .collect()
    }

    /// Number of designs.
    pub fn design_count(&self) -> StoreResult<u64> {
        let n: i64 = self
            .conn
            .query_row("SELECT count(*) FROM designs", [], |r| r.get(0))?;
        Ok(n as u64)
    }

    /// One design by its spec, with its report and linkage analysis as the library's types
    /// and the specs of its cell twins. The spec is matched exactly, then in the canonical
    /// form the library writes (so `IH28:0.5:1x1:…` finds `IH28:0.50:1x1:…` if that is how it
    /// was stored); the spec of a cell twin finds the design it is stored with (whose
    /// summary names its own spec).
    pub fn design(&self, spec: &str) -> StoreResult<Option<StoredDesign>> {
        let Some(mut stored) = self.design_record(spec)?.map(typed).transpose()? else {
            return Ok(None);
        };
        stored.other_cells = self.other_cells(&stored.summary.spec)?;
        Ok(Some(stored))
    }

    /// One design by its spec as stored (JSON documents verified but not parsed); matched as
    /// [`design`](Self::design) matches it.
    pub fn design_record(&self, spec: &str) -> StoreResult<Option<DesignRecord>> {
        let sql = record_select("WHERE d.spec = ?1");
        let mut stmt = self.conn.prepare(&sql)?;
        let mut candidates = vec![spec.to_string()];
        if let Ok(d) = spec.parse::<isogami::topology::Design>() {
            candidates.push(d.to_string());
        }
        for s in &candidates {
            let found = stmt.query_row([s], |r| Ok(record_from_row(r))).optional()?;
            if let Some(record) = found {
                return record.map(Some);
            }
        }
        for s in &candidates {
            if let Some(kept) = self.stored_as(s)? {
                let found = stmt
                    .query_row([&kept], |r| Ok(record_from_row(r)))
                    .optional()?;
                return found.transpose();
            }
        }
        Ok(None)
    }

    /// The designs of one work unit, ordered by spec.
    pub fn designs_of_unit(&self, unit: &str) -> StoreResult<Vec<DesignRecord>> {
        self.records_where("WHERE d.work_unit = ?1 ORDER BY d.spec", Some(unit))
    }

    /// Designs saved by users, ordered by when they were saved.
    pub fn user_designs(&self) -> StoreResult<Vec<DesignRecord>> {
        self.records_where("WHERE d.origin = 'user' ORDER BY d.id", None)
    }

    fn records_where(&self, filter: &str, arg: Option<&str>) -> StoreResult<Vec<DesignRecord>> {
        let mut stmt = self.conn.prepare(&record_select(filter))?;
        let mut rows = match arg {
            Some(a) => stmt.query([a])?,
            None => stmt.query([])?,
        };
        let mut out = Vec::new();
        while let Some(row) = rows.next()? {
            out.push(record_from_row(row)?);
        }
        Ok(out)
    }

    /// Every design summary in insertion order, the order queries break ties in (checksums
    /// verified).
    pub fn summaries(&self) -> StoreResult<Vec<DesignSummary>> {
        let mut stmt = self.conn.prepare(&format!(
            "SELECT {DESIGN_COLUMNS}, checksum FROM designs ORDER BY id"
        ))?;
        let mut rows = stmt.query([])?;
        let mut out = Vec::new();
        while let Some(row) = rows.next()? {
            out.push(read_design(row, 0)?.0);
        }
        Ok(out)
    }
}

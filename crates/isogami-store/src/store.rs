//! Opening, checking and writing the database.

use crate::error::{StoreError, StoreResult};
use crate::records::{DesignRecord, StageCount, WorkUnitRecord};
use crate::schema::{CREATE, SCHEMA_VERSION};
use rusqlite::{params, Connection, OptionalExtension};
use std::collections::HashSet;
use std::path::Path;

/// An open design database.
#[derive(Debug)]
pub struct Store {
    pub(crate) conn: Connection,
}

fn meta(conn: &Connection, key: &str) -> StoreResult<Option<String>> {
    Ok(conn
        .query_row("SELECT value FROM meta WHERE key = ?1", [key], |r| r.get(0))
        .optional()?)
}

impl Store {
    /// Opens (or creates) the database for a run with these settings. A file with another
    /// schema version, or made with other settings, is refused.
    pub fn open(path: &Path, tool_version: &str, settings_json: &str) -> StoreResult<Store> {
        let store = Store::open_any(path)?;
        match meta(&store.conn, "settings")? {
            None => {
                store.conn.execute(
                    "INSERT INTO meta(key, value) VALUES ('settings', ?1), ('tool_version', ?2)",
                    params![settings_json, tool_version],
                )?;
            }
            Some(s) if s == settings_json => {}
            Some(s) => return Err(StoreError::SettingsMismatch(s)),
        }
        Ok(store)
    }

    /// Opens an existing or new database without a settings check (statistics, merging).
    pub fn open_any(path: &Path) -> StoreResult<Store> {
        let conn = Connection::open(path)?;
        // WAL: a killed writer never corrupts the file, readers never block the writer.
        conn.pragma_update(None, "journal_mode", "WAL")?;
        conn.pragma_update(None, "synchronous", "NORMAL")?;
        conn.pragma_update(None, "foreign_keys", "ON")?;
        conn.busy_timeout(std::time::Duration::from_secs(10))?;
        let version: Option<String> = {
            let has_meta: bool = conn.query_row(
                "SELECT count(*) > 0 FROM sqlite_master WHERE type = 'table' AND name = 'meta'",
                [],
                |r| r.get(0),
            )?;
            if has_meta {
                meta(&conn, "schema_version")?
            } else {
                None
            }
        };
        match version {
            Some(v) => {
                let found: i64 = v.parse().unwrap_or(-1);
                if found != SCHEMA_VERSION {
                    return Err(StoreError::SchemaVersion {
                        found,
                        expected: SCHEMA_VERSION,
                    });
                }
            }
            None => {
                conn.execute_batch(CREATE)?;
                conn.execute(
                    "INSERT OR REPLACE INTO meta(key, value) VALUES ('schema_version', ?1)",
                    [SCHEMA_VERSION.to_string()],
                )?;
            }
        }
        Ok(Store { conn })
    }

    /// Settings JSON the database was made with.
    pub fn settings(&self) -> StoreResult<Option<String>> {
        meta(&self.conn, "settings")
    }

    /// Tool version that made the database.
    pub fn tool_version(&self) -> StoreResult<Option<String>> {
        meta(&self.conn, "tool_version")
    }

    /// Ids of every committed work unit.
    pub fn done_units(&self) -> StoreResult<HashSet<String>> {
        let mut stmt = self.conn.prepare("SELECT id FROM work_units")?;
        let ids = stmt
            .query_map([], |r| r.get(0))?
            .collect::<Result<_, _>>()?;
        Ok(ids)
    }

    /// Writes a finished work unit, its stage counts and its designs in one transaction:
    /// either all of it is in the file afterwards or none of it.
    pub fn commit_unit(
        &mut self,
        unit: &WorkUnitRecord,
        stages: &[StageCount],
        designs: &[DesignRecord],
    ) -> StoreResult<()> {
        let tx = self.conn.transaction()?;
        tx.execute(
            "INSERT INTO work_units(id, family, cell, kind, seconds, finished_at)
             VALUES (?1, ?2, ?3, ?4, ?5, datetime('now'))",
            params![unit.id, unit.family, unit.cell, unit.kind, unit.seconds],
        )?;
        {
            let mut st = tx.prepare(
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
            let mut dt = tx.prepare(
                "INSERT INTO designs(spec, work_unit, family, params, cell, joints, topology,
                    behaviour, end_reason, max_expansion, min_expansion, max_area_ratio,
                    max_tile_rotation, steps, linkage_signature, report, linkages)
                 VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17)",
            )?;
            for d in designs {
                dt.execute(params![
                    d.spec,
                    unit.id,
                    d.family,
                    d.params,
                    d.cell,
                    d.joints,
                    d.topology,
                    d.behaviour,
                    d.end_reason,
                    d.max_expansion,
                    d.min_expansion,
                    d.max_area_ratio,
                    d.max_tile_rotation,
                    d.steps as i64,
                    d.linkage_signature,
                    d.report,
                    d.linkages
                ])?;
            }
        }
        tx.commit()?;
        Ok(())
    }

    /// Every design, ordered by spec.
    pub fn designs(&self) -> StoreResult<Vec<DesignRecord>> {
        let mut stmt = self.conn.prepare(
            "SELECT spec, family, params, cell, joints, topology, behaviour, end_reason,
                    max_expansion, min_expansion, max_area_ratio, max_tile_rotation, steps,
                    linkage_signature, report, linkages
             FROM designs ORDER BY spec",
        )?;
        let rows = stmt.query_map([], |r| {
            Ok(DesignRecord {
                spec: r.get(0)?,
                family: r.get(1)?,
                params: r.get(2)?,
                cell: r.get(3)?,
                joints: r.get(4)?,
                topology: r.get(5)?,
                behaviour: r.get(6)?,
                end_reason: r.get(7)?,
                max_expansion: r.get(8)?,
                min_expansion: r.get(9)?,
                max_area_ratio: r.get(10)?,
                max_tile_rotation: r.get(11)?,
                steps: r.get::<_, i64>(12)? as u64,
                linkage_signature: r.get(13)?,
                report: r.get(14)?,
                linkages: r.get(15)?,
            })
        })?;
        Ok(rows.collect::<Result<_, _>>()?)
    }

    /// Every work unit with its stage counts, ordered by id.
    pub fn work_units(&self) -> StoreResult<Vec<(WorkUnitRecord, Vec<StageCount>)>> {
        let mut stmt = self
            .conn
            .prepare("SELECT id, family, cell, kind, seconds FROM work_units ORDER BY id")?;
        let units: Vec<WorkUnitRecord> = stmt
            .query_map([], |r| {
                Ok(WorkUnitRecord {
                    id: r.get(0)?,
                    family: r.get(1)?,
                    cell: r.get(2)?,
                    kind: r.get(3)?,
                    seconds: r.get(4)?,
                })
            })?
            .collect::<Result<_, _>>()?;
        let mut st = self.conn.prepare(
            "SELECT stage, count_in, count_out, seconds FROM stage_counts
             WHERE work_unit = ?1 ORDER BY position",
        )?;
        units
            .into_iter()
            .map(|u| {
                let stages = st
                    .query_map([&u.id], |r| {
                        Ok(StageCount {
                            stage: r.get(0)?,
                            count_in: r.get::<_, i64>(1)? as u64,
                            count_out: r.get::<_, i64>(2)? as u64,
                            seconds: r.get(3)?,
                        })
                    })?
                    .collect::<Result<_, _>>()?;
                Ok((u, stages))
            })
            .collect()
    }
}

impl Store {
    /// Overwrites a meta value. Only for tests of version checks.
    #[doc(hidden)]
    pub fn set_meta_for_tests(&self, key: &str, value: &str) -> StoreResult<()> {
        self.conn.execute(
            "INSERT OR REPLACE INTO meta(key, value) VALUES (?1, ?2)",
            params![key, value],
        )?;
        Ok(())
    }
}

//! Joining shard databases.

use crate::error::{StoreError, StoreResult};
use crate::store::Store;
use std::path::Path;

/// What a merge added.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct MergeReport {
    /// Work units copied.
    pub units_added: u64,
    /// Work units already present (skipped).
    pub units_skipped: u64,
    /// Designs copied.
    pub designs_added: u64,
}

impl Store {
    /// Copies every work unit of `other` that this database lacks, with its stage counts and
    /// designs, in one transaction. Both files must have the same schema version and
    /// settings (an empty target takes the other's settings).
    pub fn merge_from(&mut self, other: &Path) -> StoreResult<MergeReport> {
        let theirs = Store::open_any(other)?;
        let their_settings = theirs.settings()?;
        let their_version = theirs.tool_version()?;
        drop(theirs);
        match (self.settings()?, &their_settings) {
            (Some(a), Some(b)) if &a != b => return Err(StoreError::SettingsMismatch(b.clone())),
            (None, Some(b)) => {
                self.conn.execute(
                    "INSERT INTO meta(key, value) VALUES ('settings', ?1), ('tool_version', ?2)",
                    rusqlite::params![b, their_version.unwrap_or_default()],
                )?;
            }
            _ => {}
        }
        self.conn
            .execute("ATTACH DATABASE ?1 AS other", [other.to_string_lossy()])?;
        let result = (|| -> StoreResult<MergeReport> {
            let tx = self.conn.transaction()?;
            let total: i64 =
                tx.query_row("SELECT count(*) FROM other.work_units", [], |r| r.get(0))?;
            tx.execute_batch(
                "CREATE TEMP TABLE new_units AS
                   SELECT id FROM other.work_units WHERE id NOT IN (SELECT id FROM main.work_units);
                 INSERT INTO main.work_units SELECT * FROM other.work_units WHERE id IN (SELECT id FROM new_units);
                 INSERT INTO main.stage_counts SELECT * FROM other.stage_counts WHERE work_unit IN (SELECT id FROM new_units);",
            )?;
            let added: i64 = tx.query_row("SELECT count(*) FROM new_units", [], |r| r.get(0))?;
            let designs = tx.execute(
                "INSERT INTO main.designs SELECT * FROM other.designs WHERE work_unit IN (SELECT id FROM new_units)",
                [],
            )?;
            tx.execute_batch("DROP TABLE new_units;")?;
            tx.commit()?;
            Ok(MergeReport {
                units_added: added as u64,
                units_skipped: (total - added) as u64,
                designs_added: designs as u64,
            })
        })();
        self.conn.execute("DETACH DATABASE other", [])?;
        result
    }
}

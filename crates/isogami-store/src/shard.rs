//! Shard databases: each records which shard of which run it is and the work units it was
//! planned to hold, so that a merge can prove that the shards it joins are all there and
//! complete.
//!
//! A sharded `explore` stores a [`ShardRecord`] under the `meta` key `shard` (checksummed like
//! every meta row): its index and the shard count, the size and a digest of the whole run's
//! unit list (equal in every shard of one run), and its own units. Databases made without
//! `--shard`, or by isogami before shard records, have none and read as before.

use crate::checksum;
use crate::error::{StoreError, StoreResult};
use crate::open::{meta, put_meta, Store};
use isogami::explore::{ExplorePlan, WorkItem};
use rusqlite::types::Value;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;
use thiserror::Error;

/// The `meta` key of the shard record.
pub(crate) const SHARD_KEY: &str = "shard";

/// Which shard of which run a database holds.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardRecord {
    /// 0-based shard index.
    pub index: usize,
    /// Number of shards of the run.
    pub count: usize,
    /// Work items of the whole run (all shards): its units, or with `--unit-parts` their parts.
    pub plan_units: usize,
    /// CRC-32 (hex) of the whole run's item ids in order: equal in every shard of one run.
    pub plan_digest: String,
    /// This shard's work items (unit ids, or `IH1/2x4 part 1/3` for parts), in order.
    pub units: Vec<String>,
}

impl ShardRecord {
    /// The record of a sharded plan (`None` for a whole run).
    pub fn of_plan(plan: &ExplorePlan) -> Option<ShardRecord> {
        let shard = plan.shard?;
        let all = plan.all_items();
        let ids: Vec<Value> = all.iter().map(|u| Value::Text(u.id())).collect();
        Some(ShardRecord {
            index: shard.index(),
            count: shard.count(),
            plan_units: all.len(),
            plan_digest: format!("{:08x}", checksum::of_values(&ids)),
            units: plan.items().iter().map(WorkItem::id).collect(),
        })
    }

    /// Whether `other` is a shard of the same run (same count and whole plan).
    pub fn same_run(&self, other: &ShardRecord) -> bool {
        self.count == other.count
            && self.plan_units == other.plan_units
            && self.plan_digest == other.plan_digest
    }
}

impl fmt::Display for ShardRecord {
    /// `shard 1/4 (5 of a 20-unit run)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "shard {}/{} ({} of a {}-unit run)",
            self.index,
            self.count,
            self.units.len(),
            self.plan_units
        )
    }
}

/// A shard record and how much of it the database holds.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ShardStatus {
    /// The record.
    pub record: ShardRecord,
    /// Planned units committed.
    pub done: usize,
    /// Planned units not committed, in plan order.
    pub missing: Vec<String>,
}

impl ShardStatus {
    /// Whether every planned unit is committed.
    pub fn complete(&self) -> bool {
        self.missing.is_empty()
    }

    /// `3 of 5 work units; IH12/1x1 and 1 more missing` (or `5 of 5 work units`).
    pub fn progress(&self) -> String {
        let planned = self.record.units.len();
        match self.missing.as_slice() {
            [] => format!("{} of {planned} work units", self.done),
            [one] => format!("{} of {planned} work units; {one} missing", self.done),
            [first, rest @ ..] => format!(
                "{} of {planned} work units; {first} and {} more missing",
                self.done,
                rest.len()
            ),
        }
    }
}

impl Store {
    /// The shard record, if the database is a shard of a sharded run.
    pub fn shard(&self) -> StoreResult<Option<ShardRecord>> {
        match meta(&self.conn, SHARD_KEY)? {
            None => Ok(None),
            Some(text) => {
                let record: ShardRecord = serde_json::from_str(&text).map_err(|e| {
                    StoreError::Damaged(format!("the shard record cannot be read: {e}"))
                })?;
                if record.index >= record.count || record.units.len() > record.plan_units {
                    return Err(StoreError::Damaged(format!(
                        "the shard record says {record}"
                    )));
                }
                Ok(Some(record))
            }
        }
    }

    /// The shard record with the planned units committed and missing.
    pub fn shard_status(&self) -> StoreResult<Option<ShardStatus>> {
        let Some(record) = self.shard()? else {
            return Ok(None);
        };
        let done = self.done_units()?;
        let waiting = self.waiting_parts()?;
        // A part is done while it waits for its siblings, and once its unit is joined.
        let is_done = |id: &str| {
            done.contains(id)
                || waiting.contains(id)
                || id
                    .split_once(" part ")
                    .is_some_and(|(unit, _)| done.contains(unit))
        };
        let missing: Vec<String> = record
            .units
            .iter()
            .filter(|u| !is_done(u))
            .cloned()
            .collect();
        Ok(Some(ShardStatus {
            done: record.units.len() - missing.len(),
            missing,
            record,
        }))
    }
}

/// `shard 1/4 (…)` or `a whole run (no shard)`, for messages.
fn describe(record: Option<&ShardRecord>) -> String {
    record.map_or(
        "a whole run (no --shard)".to_string(),
        ShardRecord::to_string,
    )
}

/// Records the plan's shard in a database opened for writing by `explore`, or refuses a plan
/// that does not fit the file: another shard or run than the one recorded, a whole run into a
/// shard database, or a shard into a database holding units outside the shard. A database
/// without a record (new, or made before shard records) takes the shard's when every unit it
/// holds belongs to the shard.
pub(crate) fn record_plan(store: &Store, plan: &ExplorePlan) -> StoreResult<()> {
    let found = store.shard()?;
    let wanted = ShardRecord::of_plan(plan);
    match (&found, &wanted) {
        (None, None) => Ok(()),
        (Some(f), Some(w)) if f == w => Ok(()),
        (None, Some(w)) => {
            let done = store.done_units()?;
            if let Some(stray) = done.iter().find(|u| !w.units.contains(u)) {
                return Err(StoreError::OtherShard {
                    found: format!("work unit {stray}"),
                    wanted: w.to_string(),
                });
            }
            let text = serde_json::to_string(w).map_err(|e| StoreError::InvalidRecord {
                spec: "shard record".into(),
                problem: e.to_string(),
            })?;
            put_meta(&store.conn, SHARD_KEY, &text)
        }
        _ => Err(StoreError::OtherShard {
            found: describe(found.as_ref()),
            wanted: describe(wanted.as_ref()),
        }),
    }
}

/// Why a set of shard databases is not one complete run.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum ShardSetError {
    /// No database given holds this shard.
    #[error("shard {index}/{count} is missing: none of the databases given holds it")]
    Missing {
        /// The shard's index.
        index: usize,
        /// Shards of the run.
        count: usize,
    },
    /// A shard database lacks some of its planned units.
    #[error("{path}: shard {index}/{count} is incomplete ({progress}); rerun that shard")]
    Incomplete {
        /// The database.
        path: String,
        /// Its shard index.
        index: usize,
        /// Shards of the run.
        count: usize,
        /// Done, planned and missing units, e.g. `3 of 5 work units; IH12/1x1 missing`.
        progress: String,
    },
    /// A database without a shard record among shard databases.
    #[error("{path}: not a shard database (made without --shard, or by an older isogami), unlike {other}")]
    NotAShard {
        /// The database without a record.
        path: String,
        /// A shard database of the set.
        other: String,
    },
    /// Two shards of different runs (shard count, families or cells).
    #[error("{path} ({this}) and {other} ({that}) are shards of different runs")]
    OtherRun {
        /// One database.
        path: String,
        /// Its record.
        this: String,
        /// A database of the first run seen.
        other: String,
        /// That one's record.
        that: String,
    },
    /// Two databases hold the same shard.
    #[error("{path} and {other} both hold shard {index}/{count}")]
    Duplicate {
        /// One database.
        path: String,
        /// The other.
        other: String,
        /// The shard.
        index: usize,
        /// Shards of the run.
        count: usize,
    },
}

/// Checks that `inputs` (path, open database) are every shard of one run, each complete.
/// Inputs without shard records are accepted as they are when none has one (a merge of whole
/// runs or of databases made before shard records). Returns the first problem, in the order:
/// a database that is not a shard, shards of different runs, a shard held twice, a missing
/// shard (lowest index first), an incomplete shard (in input order).
pub fn check_shard_set(inputs: &[(&Path, &Store)]) -> StoreResult<Result<(), ShardSetError>> {
    let mut shards: Vec<(String, ShardStatus)> = Vec::new();
    let mut plain: Vec<String> = Vec::new();
    for (path, store) in inputs {
        let name = path.display().to_string();
        match store.shard_status()? {
            Some(status) => shards.push((name, status)),
            None => plain.push(name),
        }
    }
    let Some((first_path, first)) = shards.first() else {
        return Ok(Ok(()));
    };
    if let Some(path) = plain.into_iter().next() {
        return Ok(Err(ShardSetError::NotAShard {
            path,
            other: first_path.clone(),
        }));
    }
    let count = first.record.count;
    if let Some((path, s)) = shards
        .iter()
        .find(|(_, s)| !s.record.same_run(&first.record))
    {
        return Ok(Err(ShardSetError::OtherRun {
            path: path.clone(),
            this: s.record.to_string(),
            other: first_path.clone(),
            that: first.record.to_string(),
        }));
    }
    let mut holder: Vec<Option<&str>> = vec![None; count];
    for (path, s) in &shards {
        // Same run: same count, and every record's index is below its count.
        let slot = &mut holder[s.record.index];
        if let Some(other) = slot {
            return Ok(Err(ShardSetError::Duplicate {
                path: path.clone(),
                other: other.to_string(),
                index: s.record.index,
                count,
            }));
        }
        *slot = Some(path);
    }
    if let Some(index) = holder.iter().position(Option::is_none) {
        return Ok(Err(ShardSetError::Missing { index, count }));
    }
    if let Some((path, s)) = shards.iter().find(|(_, s)| !s.complete()) {
        return Ok(Err(ShardSetError::Incomplete {
            path: path.clone(),
            index: s.record.index,
            count,
            progress: s.progress(),
        }));
    }
    Ok(Ok(()))
}

//! Parts of work units split across processes (`explore --unit-parts P`): a part waits in the
//! optional table `unit_parts` until every part of its unit is in the same file, then the
//! library joins them ([`combine_parts`]) and the unit is committed like any other, its part
//! rows deleted, in one transaction. `merge` copies waiting parts and completes the units it
//! can, so shards that each ran some parts of a big unit merge into exactly the unit run whole.
//!
//! A part row holds the library's [`PartOutcome`] as JSON (parameters and reports bit for bit),
//! its seconds and peak memory, and a checksum over all of it.

use crate::checksum;
use crate::error::{StoreError, StoreResult};
use crate::open::{Store, StoreWriter};
use crate::records::UnitRecords;
use crate::write::insert_records;
use isogami::catalog::{combine_parts, PartOutcome};
use isogami::explore::{ExploreError, UnitPart, WorkItem, WorkUnit};
use rusqlite::types::Value;
use rusqlite::{params, Connection, OptionalExtension};
use std::collections::HashSet;

/// A stored part: the library's outcome and what the run measured.
#[derive(Debug, Clone)]
pub struct StoredPart {
    /// The part's outcome.
    pub outcome: PartOutcome,
    /// Wall time of the part.
    pub seconds: f64,
    /// Peak resident memory while it ran (bytes), when measured.
    pub peak_rss_bytes: Option<u64>,
}

impl StoredPart {
    fn item(&self) -> WorkItem {
        WorkItem {
            unit: WorkUnit {
                family: self.outcome.family,
                dims: self.outcome.dims,
            },
            part: self.outcome.part,
        }
    }
}

fn part_values(
    unit: &str,
    part: &UnitPart,
    seconds: f64,
    peak: Option<i64>,
    data: &str,
) -> [Value; 6] {
    [
        Value::Text(unit.to_string()),
        Value::Integer(part.index() as i64),
        Value::Integer(part.count() as i64),
        Value::Real(seconds),
        peak.map_or(Value::Null, Value::Integer),
        Value::Text(data.to_string()),
    ]
}

fn has_parts_table(conn: &Connection) -> StoreResult<bool> {
    crate::open::has_table(conn, "unit_parts")
}

/// Every part row (of `unit` only, when given), checked against its checksum and parsed.
fn read_parts(conn: &Connection, unit: Option<&str>) -> StoreResult<Vec<StoredPart>> {
    if !has_parts_table(conn)? {
        return Ok(Vec::new());
    }
    let mut stmt = conn.prepare(
        "SELECT work_unit, part, parts, seconds, peak_rss_bytes, data, checksum FROM unit_parts
         WHERE ?1 IS NULL OR work_unit = ?1 ORDER BY work_unit, part",
    )?;
    let mut rows = stmt.query(params![unit])?;
    let mut out = Vec::new();
    while let Some(r) = rows.next()? {
        let id: String = r.get(0)?;
        let (index, count): (i64, i64) = (r.get(1)?, r.get(2)?);
        let seconds: f64 = r.get(3)?;
        let peak: Option<i64> = r.get(4)?;
        let data: String = r.get(5)?;
        let stored: i64 = r.get(6)?;
        let damaged =
            |what: String| StoreError::Damaged(format!("unit part {id} {index}/{count}: {what}"));
        let part =
            UnitPart::new(index as usize, count as usize).map_err(|e| damaged(e.to_string()))?;
        if checksum::of_values(&part_values(&id, &part, seconds, peak, &data)) != stored {
            return Err(damaged("checksum mismatch".into()));
        }
        let outcome: PartOutcome =
            serde_json::from_str(&data).map_err(|e| damaged(e.to_string()))?;
        let found = StoredPart {
            outcome,
            seconds,
            peak_rss_bytes: peak.map(|b| b as u64),
        };
        if found.item().unit.id() != id || found.outcome.part != part {
            return Err(damaged("its data is of another part".into()));
        }
        out.push(found);
    }
    Ok(out)
}

/// Inserts a part row (the table exists: writers create it); refused when the file holds
/// parts of the same unit split another way.
fn insert_part(conn: &Connection, part: &StoredPart) -> StoreResult<()> {
    let count = part.outcome.part.count();
    let other: Option<i64> = conn
        .query_row(
            "SELECT parts FROM unit_parts WHERE work_unit = ?1 AND parts != ?2 LIMIT 1",
            params![part.item().unit.id(), count as i64],
            |r| r.get(0),
        )
        .optional()?;
    if let Some(other) = other {
        return Err(StoreError::Plan(ExploreError::PartsMismatch {
            detail: format!(
                "{} split into {other} parts in the database and into {count} now; use the same --unit-parts",
                part.item().unit
            ),
        }));
    }
    let data = serde_json::to_string(&part.outcome).map_err(|e| StoreError::InvalidRecord {
        spec: part.item().id(),
        problem: e.to_string(),
    })?;
    let unit = part.item().unit.id();
    let peak = part
        .peak_rss_bytes
        .map(|b| i64::try_from(b).unwrap_or(i64::MAX));
    let values = part_values(&unit, &part.outcome.part, part.seconds, peak, &data);
    conn.execute(
        "INSERT INTO unit_parts(work_unit, part, parts, seconds, peak_rss_bytes, data, checksum)
         VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)",
        params![
            unit,
            part.outcome.part.index() as i64,
            part.outcome.part.count() as i64,
            part.seconds,
            peak,
            data,
            checksum::of_values(&values)
        ],
    )?;
    Ok(())
}

/// Joins `unit`'s parts when all of them are in the file and the unit is not: commits the
/// unit (seconds summed, the largest peak) and deletes its part rows. The number of designs
/// committed when it did.
fn complete_unit(conn: &Connection, unit: &str) -> StoreResult<Option<u64>> {
    let done: Option<i64> = conn
        .query_row("SELECT 1 FROM work_units WHERE id = ?1", [unit], |r| {
            r.get(0)
        })
        .optional()?;
    let parts = read_parts(conn, Some(unit))?;
    let Some(first) = parts.first() else {
        return Ok(None);
    };
    if done.is_some() || parts.len() < first.outcome.part.count() {
        return Ok(None);
    }
    let records = unit_records(parts)?;
    // insert_unit, through insert_records, deletes the unit's part rows.
    insert_records(conn, &records)?;
    Ok(Some(records.designs.len() as u64))
}

/// The unit records of every part of one unit, joined by the library: seconds summed, the
/// largest peak memory.
pub(crate) fn unit_records(parts: Vec<StoredPart>) -> StoreResult<UnitRecords> {
    let seconds = parts.iter().fold(0.0, |a, p| a + p.seconds);
    let peak = parts.iter().filter_map(|p| p.peak_rss_bytes).max();
    let outcome = combine_parts(parts.into_iter().map(|p| p.outcome).collect())?;
    let mut records = UnitRecords::from_outcome(&outcome, seconds)?;
    records.unit.peak_rss_bytes = peak;
    Ok(records)
}

impl Store {
    /// Ids of the parts waiting in the file (`IH1/2x4 part 1/3`), for skipping them on a rerun.
    pub fn waiting_parts(&self) -> StoreResult<HashSet<String>> {
        Ok(read_parts(&self.conn, None)?
            .iter()
            .map(|p| p.item().id())
            .collect())
    }

    /// Every waiting part, checked.
    pub fn parts(&self) -> StoreResult<Vec<StoredPart>> {
        read_parts(&self.conn, None)
    }

    /// How many parts wait for their units' other parts (no JSON parsed).
    pub fn waiting_part_count(&self) -> StoreResult<u64> {
        if !has_parts_table(&self.conn)? {
            return Ok(0);
        }
        let n: i64 = self
            .conn
            .query_row("SELECT count(*) FROM unit_parts", [], |r| r.get(0))?;
        Ok(n as u64)
    }
}

impl StoreWriter {
    /// Stores a finished part and, when it was its unit's last, joins the unit and commits it;
    /// one transaction. Returns whether the unit was completed.
    pub fn commit_part(&mut self, part: &StoredPart) -> StoreResult<bool> {
        let tx = self.store.conn.transaction()?;
        insert_part(&tx, part)?;
        let completed = complete_unit(&tx, &part.item().unit.id())?.is_some();
        tx.commit()?;
        Ok(completed)
    }
}

/// Copies the parts of `other` that `conn`'s file has neither as parts nor as finished units,
/// then completes every unit whose parts are all there. Returns (parts copied, units
/// completed, their designs). Runs inside the caller's transaction.
pub(crate) fn merge_parts(conn: &Connection, other: &Store) -> StoreResult<(u64, u64, u64)> {
    let theirs = other.parts()?;
    if theirs.is_empty() {
        return Ok((0, 0, 0));
    }
    let mine: HashSet<String> = read_parts(conn, None)?
        .iter()
        .map(|p| p.item().id())
        .collect();
    let mut copied = 0;
    let mut units: Vec<String> = Vec::new();
    for p in &theirs {
        let unit = p.item().unit.id();
        let done: Option<i64> = conn
            .query_row("SELECT 1 FROM work_units WHERE id = ?1", [&unit], |r| {
                r.get(0)
            })
            .optional()?;
        if done.is_some() || mine.contains(&p.item().id()) {
            continue;
        }
        insert_part(conn, p)?;
        copied += 1;
        if !units.contains(&unit) {
            units.push(unit);
        }
    }
    let (mut completed, mut designs) = (0, 0);
    for unit in units {
        if let Some(n) = complete_unit(conn, &unit)? {
            completed += 1;
            designs += n;
        }
    }
    Ok((copied, completed, designs))
}

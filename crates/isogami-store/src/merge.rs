//! Joining shard databases.

use crate::error::{StoreError, StoreResult};
use crate::open::{put_meta, Store, StoreWriter};
use crate::parts::merge_parts;
use crate::write::{insert_design, insert_unit};

/// What a merge added.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub struct MergeReport {
    /// Work units copied.
    pub units_added: u64,
    /// Work units already present (skipped).
    pub units_skipped: u64,
    /// Designs copied with their units.
    pub designs_added: u64,
    /// User designs copied.
    pub user_designs_added: u64,
    /// User designs whose spec the target already had (skipped).
    pub user_designs_skipped: u64,
    /// Parts of split units copied (`explore --unit-parts`).
    pub parts_added: u64,
    /// Split units whose last part came in: joined and committed (counted in `units_added`).
    pub units_joined: u64,
}

impl StoreWriter {
    /// Copies every work unit of `other` that this database lacks, with its stage counts and
    /// designs, every part of a split unit it lacks (joining the units whose parts are then
    /// all here), and every user design whose spec it lacks, in one transaction. Both must have
    /// the same settings (a target without settings takes the other's). Rows are copied
    /// through the checked reads, so a damaged row in `other` stops the merge before anything
    /// is written.
    pub fn merge_from(&mut self, other: &Store) -> StoreResult<MergeReport> {
        self.merge_all(&[other])
            .map(|mut r| r.remove(0))
            .map_err(|(_, e)| e)
    }

    /// [`merge_from`](Self::merge_from) of every store of `others`, in order, in **one**
    /// transaction: the settings of all of them are compared with each other and with the
    /// target's before anything is written, and any failure rolls the whole merge back, so
    /// the target is either unchanged or holds all of them. The error names the index of the
    /// store it came from.
    pub fn merge_all(
        &mut self,
        others: &[&Store],
    ) -> Result<Vec<MergeReport>, (usize, StoreError)> {
        let mut settings: Vec<Option<String>> = Vec::with_capacity(others.len());
        for (k, other) in others.iter().enumerate() {
            settings.push(other.settings().map_err(|e| (k, e))?);
        }
        let tx = self.store.conn.transaction().map_err(|e| (0, e.into()))?;
        let mut target = crate::open::meta(&tx, "settings").map_err(|e| (0, e))?;
        let target_named = target.is_some();
        for (k, theirs) in settings.iter().enumerate() {
            match (&target, theirs) {
                (Some(a), Some(b)) if a != b => {
                    let what = if target_named || k == 0 {
                        "the target"
                    } else {
                        "the inputs before it"
                    };
                    return Err((
                        k,
                        StoreError::SettingsMismatch(crate::settings_diff::settings_difference(
                            a,
                            what,
                            b,
                            "the input",
                        )),
                    ));
                }
                (None, Some(b)) => {
                    let version = others[k].tool_version().map_err(|e| (k, e))?;
                    put_meta(&tx, "settings", b).map_err(|e| (k, e))?;
                    put_meta(&tx, "tool_version", version.as_deref().unwrap_or_default())
                        .map_err(|e| (k, e))?;
                    target = Some(b.clone());
                }
                _ => {}
            }
        }
        let mut reports = Vec::with_capacity(others.len());
        for (k, other) in others.iter().enumerate() {
            reports.push(merge_one(&tx, other).map_err(|e| (k, e))?);
        }
        tx.commit()
            .map_err(|e| (others.len().saturating_sub(1), e.into()))?;
        if reports
            .iter()
            .any(|r| r.units_added + r.user_designs_added > 0)
        {
            let last = others.len().saturating_sub(1);
            self.refresh_cell_twins().map_err(|e| (last, e))?;
            self.refresh_motion_classes().map_err(|e| (last, e))?;
        }
        Ok(reports)
    }
}

/// Copies what `other` has and the target (seen through `tx`) lacks.
fn merge_one(tx: &rusqlite::Transaction<'_>, other: &Store) -> StoreResult<MergeReport> {
    let mine: std::collections::HashSet<String> = tx
        .prepare("SELECT id FROM work_units")?
        .query_map([], |r| r.get(0))?
        .collect::<Result<_, _>>()?;
    let mut report = MergeReport::default();
    for (unit, stages) in &other.work_units()? {
        if mine.contains(&unit.id) {
            report.units_skipped += 1;
            continue;
        }
        insert_unit(tx, unit, stages)?;
        for d in other.designs_of_unit(&unit.id)? {
            insert_design(tx, &d, Some(&unit.id))?;
            report.designs_added += 1;
        }
        report.units_added += 1;
    }
    for (spec, kept) in other.cell_twins()? {
        tx.prepare_cached(
            "INSERT OR IGNORE INTO cell_twins(spec, kept, checksum) VALUES (?1, ?2, ?3)",
        )?
        .execute(rusqlite::params![
            spec,
            kept,
            crate::checksum::of_values(&crate::rows::cell_twin_values(&spec, &kept))
        ])?;
    }
    let (parts, joined, designs) = merge_parts(tx, other)?;
    report.parts_added = parts;
    report.units_joined = joined;
    report.units_added += joined;
    report.designs_added += designs;
    for d in other.user_designs()? {
        match insert_design(tx, &d, None) {
            Ok(()) => report.user_designs_added += 1,
            Err(StoreError::DuplicateSpec(_)) => report.user_designs_skipped += 1,
            Err(e) => return Err(e),
        }
    }
    Ok(report)
}

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
        let their_settings = other.settings()?;
        let their_version = other.tool_version()?;
        let mine = self.done_units()?;
        let units = other.work_units()?;
        let mut report = MergeReport::default();
        let tx = self.store.conn.transaction()?;
        match (crate::open::meta(&tx, "settings")?, &their_settings) {
            (Some(a), Some(b)) if &a != b => {
                return Err(StoreError::SettingsMismatch(
                    crate::settings_diff::settings_difference(&a, "the target", b, "the input"),
                ))
            }
            (None, Some(b)) => {
                put_meta(&tx, "settings", b)?;
                put_meta(
                    &tx,
                    "tool_version",
                    their_version.as_deref().unwrap_or_default(),
                )?;
            }
            _ => {}
        }
        for (unit, stages) in &units {
            if mine.contains(&unit.id) {
                report.units_skipped += 1;
                continue;
            }
            insert_unit(&tx, unit, stages)?;
            for d in other.designs_of_unit(&unit.id)? {
                insert_design(&tx, &d, Some(&unit.id))?;
                report.designs_added += 1;
            }
            report.units_added += 1;
        }
        let (parts, joined, designs) = merge_parts(&tx, other)?;
        report.parts_added = parts;
        report.units_joined = joined;
        report.units_added += joined;
        report.designs_added += designs;
        for d in other.user_designs()? {
            match insert_design(&tx, &d, None) {
                Ok(()) => report.user_designs_added += 1,
                Err(StoreError::DuplicateSpec(_)) => report.user_designs_skipped += 1,
                Err(e) => return Err(e),
            }
        }
        tx.commit()?;
        if report.units_added + report.user_designs_added > 0 {
            self.refresh_motion_classes()?;
        }
        Ok(report)
    }
}

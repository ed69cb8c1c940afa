//! Summaries of a database.

use crate::error::StoreResult;
use crate::open::Store;
use crate::records::{StageCount, WorkUnitRecord};
use crate::shard::ShardStatus;
use serde::Serialize;
use std::collections::BTreeMap;

/// Per-family summary.
#[derive(Debug, Clone, Default, Serialize)]
pub struct FamilyStats {
    /// Finished work units.
    pub units: u64,
    /// Kept designs.
    pub designs: u64,
    /// Stage totals in pipeline order.
    pub stages: Vec<StageCount>,
    /// Largest peak memory of its work units in bytes (see
    /// [`WorkUnitRecord::peak_rss_bytes`](crate::WorkUnitRecord)); None when none was measured.
    pub peak_rss_bytes: Option<u64>,
}

/// One work unit's figures, for sizing runs (`isogami db units`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UnitSummary {
    /// Unit id, e.g. `IH22/3x1`.
    pub id: String,
    /// Wall time in seconds.
    pub seconds: f64,
    /// Peak memory in bytes, when measured.
    pub peak_rss_bytes: Option<u64>,
    /// Designs it kept.
    pub designs: u64,
}

/// The finite 6×6 patches of a database's designs (`finite_raw_dof`, `finite_covered`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FiniteCounts {
    /// Designs with the figures (explored designs).
    pub measured: u64,
    /// Of these, designs whose raw patch has one DOF as cut.
    pub raw_one_dof: u64,
    /// Designs whose patch completes to a one-DOF sheet.
    pub completed: u64,
    /// Of these, completed without losing any of the region's area.
    pub fully_covered: u64,
    /// Smallest covered fraction of a completed patch.
    pub min_covered: Option<f64>,
}

/// The margins of a database's designs (`open_t`, `end_area_ratio`, `shape_tolerance`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MarginCounts {
    /// Designs with the margins (explored designs).
    pub measured: u64,
    /// Of these, designs whose path ends at less than 95 % of their largest area ratio (the
    /// sheet closes again past its most open state).
    pub closing_again: u64,
    /// Of these, designs of families without shape parameters (no tolerance to measure).
    pub fixed_shape: u64,
    /// Special designs: they lose their opening at the smallest shape move.
    pub special: u64,
    /// Designs that keep their opening at the fabrication tolerance (fixed shapes included).
    pub tolerance_met: u64,
    /// Buildable designs: the fabrication tolerance met and a one-DOF finite sheet.
    pub buildable: u64,
}

/// Whole-database summary.
#[derive(Debug, Clone, Serialize)]
pub struct DbStats {
    /// Schema version.
    pub schema_version: i64,
    /// Tool version that made it.
    pub tool_version: Option<String>,
    /// Settings it was made with (JSON).
    pub settings: Option<String>,
    /// Finished work units.
    pub work_units: u64,
    /// Designs (explored and saved by users).
    pub designs: u64,
    /// Of these, designs saved by users.
    pub user_designs: u64,
    /// Specs of explored designs found again on another cell of their family and stored with
    /// that design (cell twins; not counted in `designs`).
    pub cell_twins: u64,
    /// Designs per behaviour class ("none" when unclassified).
    pub by_behaviour: BTreeMap<String, u64>,
    /// Designs per linkage signature.
    pub by_linkage: BTreeMap<String, u64>,
    /// Stage totals over all work units, in pipeline order.
    pub stages: Vec<StageCount>,
    /// Per family.
    pub families: BTreeMap<String, FamilyStats>,
    /// The designs' finite 6×6 patches.
    pub finite: FiniteCounts,
    /// The designs' margins.
    pub margins: MarginCounts,
    /// Distinct motions across cells and families (None when not computed yet).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub motions: Option<crate::MotionCounts>,
    /// The work unit with the largest peak memory and that peak, when any was measured.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_memory: Option<UnitSummary>,
    /// The slowest work unit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slowest: Option<UnitSummary>,
    /// For a database made by `explore --shard`: its shard and how much of it is done.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shard: Option<ShardStatus>,
    /// Parts of split units (`explore --unit-parts`) waiting for their units' other parts.
    #[serde(skip_serializing_if = "is_zero")]
    pub waiting_parts: u64,
}

fn is_zero(n: &u64) -> bool {
    *n == 0
}

/// Adds a unit's stages into running totals, keeping first-seen order.
fn accumulate(into: &mut Vec<StageCount>, stages: &[StageCount]) {
    for s in stages {
        match into.iter_mut().find(|t| t.stage == s.stage) {
            Some(t) => {
                t.count_in += s.count_in;
                t.count_out += s.count_out;
                t.seconds += s.seconds;
            }
            None => into.push(s.clone()),
        }
    }
}

impl Store {
    /// Counts by family, behaviour, linkage and stage (work units checksum-verified).
    pub fn stats(&self) -> StoreResult<DbStats> {
        let units = self.work_units()?;
        let mut stages = Vec::new();
        let mut families: BTreeMap<String, FamilyStats> = BTreeMap::new();
        for (u, st) in &units {
            accumulate(&mut stages, st);
            let f = families.entry(u.family.clone()).or_default();
            f.units += 1;
            accumulate(&mut f.stages, st);
            f.peak_rss_bytes = f.peak_rss_bytes.max(u.peak_rss_bytes);
        }
        let mut by_behaviour = BTreeMap::new();
        let mut by_linkage = BTreeMap::new();
        let mut designs = 0;
        let mut stmt = self.conn.prepare(
            "SELECT family, behaviour, linkage_signature, count(*) FROM designs
             GROUP BY family, behaviour, linkage_signature",
        )?;
        let rows = stmt.query_map([], |r| {
            Ok((
                r.get::<_, i64>(0)?,
                r.get::<_, Option<String>>(1)?,
                r.get::<_, Option<String>>(2)?,
                r.get::<_, i64>(3)? as u64,
            ))
        })?;
        for row in rows {
            let (family, behaviour, linkage, n) = row?;
            designs += n;
            families.entry(format!("IH{family}")).or_default().designs += n;
            *by_behaviour
                .entry(behaviour.unwrap_or_else(|| "none".into()))
                .or_insert(0) += n;
            *by_linkage
                .entry(linkage.unwrap_or_else(|| "unknown".into()))
                .or_insert(0) += n;
        }
        let user_designs: i64 = self.conn.query_row(
            "SELECT count(*) FROM designs WHERE origin = 'user'",
            [],
            |r| r.get(0),
        )?;
        let finite = self.conn.query_row(
            "SELECT count(finite_raw_dof), count(CASE WHEN finite_raw_dof = 1 THEN 1 END),
                    count(finite_covered), count(CASE WHEN finite_covered >= 1.0 THEN 1 END),
                    min(finite_covered)
             FROM designs",
            [],
            |r| {
                Ok(FiniteCounts {
                    measured: r.get::<_, i64>(0)? as u64,
                    raw_one_dof: r.get::<_, i64>(1)? as u64,
                    completed: r.get::<_, i64>(2)? as u64,
                    fully_covered: r.get::<_, i64>(3)? as u64,
                    min_covered: r.get(4)?,
                })
            },
        )?;
        let margins = self.conn.query_row(
            &format!(
                "SELECT count(open_t),
                        count(CASE WHEN end_area_ratio < 0.95 * max_area_ratio THEN 1 END),
                        count(CASE WHEN open_t IS NOT NULL AND shape_tolerance IS NULL THEN 1 END),
                        count(CASE WHEN shape_tolerance = 0 THEN 1 END),
                        count(CASE WHEN {} THEN 1 END),
                        count(CASE WHEN {} THEN 1 END)
                 FROM designs",
                crate::query::filter::tolerance_met_sql(),
                crate::query::filter::buildable_sql()
            ),
            [],
            |r| {
                Ok(MarginCounts {
                    measured: r.get::<_, i64>(0)? as u64,
                    closing_again: r.get::<_, i64>(1)? as u64,
                    fixed_shape: r.get::<_, i64>(2)? as u64,
                    special: r.get::<_, i64>(3)? as u64,
                    tolerance_met: r.get::<_, i64>(4)? as u64,
                    buildable: r.get::<_, i64>(5)? as u64,
                })
            },
        )?;
        let summaries = self.summaries_of(&units)?;
        let peak_memory = summaries
            .iter()
            .filter(|u| u.peak_rss_bytes.is_some())
            .max_by_key(|u| u.peak_rss_bytes)
            .cloned();
        let slowest = summaries
            .iter()
            .max_by(|a, b| a.seconds.total_cmp(&b.seconds))
            .cloned();
        Ok(DbStats {
            schema_version: crate::SCHEMA_VERSION,
            tool_version: self.tool_version()?,
            settings: self.settings()?,
            work_units: units.len() as u64,
            designs,
            user_designs: user_designs as u64,
            cell_twins: self.cell_twin_count()?,
            by_behaviour,
            by_linkage,
            stages,
            families,
            finite,
            margins,
            peak_memory,
            slowest,
            motions: self.motion_counts()?,
            shard: self.shard_status()?,
            waiting_parts: self.waiting_part_count()?,
        })
    }

    /// Every work unit's time, peak memory and kept designs, slowest first (ties by id).
    pub fn unit_summaries(&self) -> StoreResult<Vec<UnitSummary>> {
        self.summaries_of(&self.work_units()?)
    }

    fn summaries_of(
        &self,
        units: &[(WorkUnitRecord, Vec<StageCount>)],
    ) -> StoreResult<Vec<UnitSummary>> {
        let mut kept: BTreeMap<String, u64> = BTreeMap::new();
        let mut stmt = self.conn.prepare(
            "SELECT work_unit, count(*) FROM designs WHERE work_unit IS NOT NULL
             GROUP BY work_unit",
        )?;
        for row in stmt.query_map([], |r| Ok((r.get::<_, String>(0)?, r.get::<_, i64>(1)?)))? {
            let (unit, n) = row?;
            kept.insert(unit, n as u64);
        }
        let mut out: Vec<UnitSummary> = units
            .iter()
            .map(|(u, _)| UnitSummary {
                designs: kept.get(&u.id).copied().unwrap_or(0),
                id: u.id.clone(),
                seconds: u.seconds,
                peak_rss_bytes: u.peak_rss_bytes,
            })
            .collect();
        out.sort_by(|a, b| b.seconds.total_cmp(&a.seconds).then(a.id.cmp(&b.id)));
        Ok(out)
    }
}

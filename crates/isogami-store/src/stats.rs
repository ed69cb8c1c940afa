//! Summaries of a database.

use crate::error::StoreResult;
use crate::records::StageCount;
use crate::store::Store;
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
    /// Kept designs.
    pub designs: u64,
    /// Designs per behaviour class ("none" when unclassified).
    pub by_behaviour: BTreeMap<String, u64>,
    /// Designs per linkage signature.
    pub by_linkage: BTreeMap<String, u64>,
    /// Stage totals over all work units, in pipeline order.
    pub stages: Vec<StageCount>,
    /// Per family.
    pub families: BTreeMap<String, FamilyStats>,
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
    /// Counts by family, behaviour, linkage and stage.
    pub fn stats(&self) -> StoreResult<DbStats> {
        let units = self.work_units()?;
        let mut stages = Vec::new();
        let mut families: BTreeMap<String, FamilyStats> = BTreeMap::new();
        for (u, st) in &units {
            accumulate(&mut stages, st);
            let f = families.entry(u.family.clone()).or_default();
            f.units += 1;
            accumulate(&mut f.stages, st);
        }
        let mut by_behaviour = BTreeMap::new();
        let mut by_linkage = BTreeMap::new();
        let mut stmt = self
            .conn
            .prepare("SELECT family, behaviour, linkage_signature FROM designs")?;
        let rows = stmt.query_map([], |r| {
            Ok((
                r.get::<_, String>(0)?,
                r.get::<_, Option<String>>(1)?,
                r.get::<_, Option<String>>(2)?,
            ))
        })?;
        let mut designs = 0;
        for row in rows {
            let (family, behaviour, linkage) = row?;
            designs += 1;
            families.entry(family).or_default().designs += 1;
            *by_behaviour
                .entry(behaviour.unwrap_or_else(|| "none".into()))
                .or_insert(0) += 1;
            *by_linkage
                .entry(linkage.unwrap_or_else(|| "unknown".into()))
                .or_insert(0) += 1;
        }
        Ok(DbStats {
            schema_version: crate::SCHEMA_VERSION,
            tool_version: self.tool_version()?,
            settings: self.settings()?,
            work_units: units.len() as u64,
            designs,
            by_behaviour,
            by_linkage,
            stages,
            families,
        })
    }
}

//! Distinct motions across cells and families (issue 13, item 5), stored: every topology of
//! the database is put in a class of topologies whose motions match
//! (`isogami::explore::motion_classes`), in the optional `motion_classes` table (one row per
//! topology: its class's representative, the smallest topology spec of the class; checksum).
//! A topology that is not one DOF at its shape, or whose text is no spec, has no row.
//!
//! The classes depend only on the set of topologies in the file (they are formed in spec
//! order), so any job count, unit order or set of merged shards gives the same table. Writers
//! recompute it in one transaction after `explore` commits units and after a merge; files made
//! before it existed read as "not computed" until a writer opens them. A design saved by a
//! user gets its class at the next explore or merge into the file.

use crate::checksum;
use crate::error::StoreResult;
use crate::open::{Store, StoreWriter};
use crate::rows::{motion_class_values, verify};
use isogami::explore::motion_classes;
use isogami::mobility::MobilitySettings;
use isogami::topology::Design;
use rusqlite::params;
use serde::Serialize;
use std::collections::BTreeMap;

/// One topology of a motion class.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionVariant {
    /// The topology's spec (default shape).
    pub topology: String,
    /// Its family, e.g. `IH28`.
    pub family: String,
    /// Its cell, e.g. `2x1`.
    pub cell: String,
    /// Designs of the database sampled from it.
    pub designs: u64,
    /// The first of them by spec (to open it).
    pub example: String,
    /// The largest area ratio the example reaches (its own: other shapes of one mechanism
    /// open differently).
    pub example_area_ratio: f64,
    /// Smallest and largest area ratio over the topology's designs.
    pub area_ratio: [f64; 2],
}

/// A class of topologies that move alike.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionClass {
    /// The class's representative: its smallest topology spec.
    pub representative: String,
    /// Every topology of the class, in spec order.
    pub variants: Vec<MotionVariant>,
}

impl MotionClass {
    /// Distinct families among the variants.
    pub fn families(&self) -> usize {
        let mut f: Vec<&str> = self.variants.iter().map(|v| v.family.as_str()).collect();
        f.sort_unstable();
        f.dedup();
        f.len()
    }
}

/// Counts of the stored classes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct MotionCounts {
    /// Topologies with a class.
    pub topologies: u64,
    /// Distinct motions (classes).
    pub motions: u64,
    /// Classes with topologies of more than one cell or family.
    pub shared: u64,
    /// Classes with topologies of more than one family.
    pub across_families: u64,
}

impl StoreWriter {
    /// Recomputes the motion classes of every topology in the database in one transaction;
    /// topologies without a one-DOF motion at their shape get no row.
    pub fn refresh_motion_classes(&mut self) -> StoreResult<()> {
        let topologies: Vec<String> = {
            let mut stmt = self
                .conn
                .prepare("SELECT DISTINCT topology FROM designs ORDER BY topology")?;
            let rows = stmt.query_map([], |r| r.get(0))?;
            rows.collect::<Result<_, _>>()?
        };
        // A topology text that is no spec (a record made by hand) simply gets no class.
        let (specs, parsed): (Vec<&String>, Vec<Design>) = topologies
            .iter()
            .filter_map(|t| t.parse::<Design>().ok().map(|d| (t, d)))
            .unzip();
        let reps = motion_classes(&parsed, MobilitySettings::default());
        let tx = self.store.conn.transaction()?;
        tx.execute("DELETE FROM motion_classes", [])?;
        {
            let mut insert = tx.prepare(
                "INSERT INTO motion_classes(topology, representative, checksum) VALUES (?1, ?2, ?3)",
            )?;
            for (t, rep) in specs.iter().zip(&reps) {
                let Some(rep) = rep else { continue };
                let rep = specs[*rep];
                insert.execute(params![
                    t,
                    rep,
                    checksum::of_values(&motion_class_values(t, rep))
                ])?;
            }
        }
        tx.commit()?;
        Ok(())
    }
}

impl Store {
    /// Whether the file has the classes table (made or opened by a writer since it existed).
    fn has_motion_classes(&self) -> StoreResult<bool> {
        crate::open::has_table(&self.conn, "motion_classes")
    }

    /// Every stored class with its variants, biggest first (then by representative); None when
    /// the file has no classes table yet.
    pub fn motion_classes(&self) -> StoreResult<Option<Vec<MotionClass>>> {
        if !self.has_motion_classes()? {
            return Ok(None);
        }
        self.classes_where("", []).map(Some)
    }

    /// The class of the design `spec` (through its topology): None when the design is not in
    /// the database or its topology has no class.
    pub fn motion_class_of(&self, spec: &str) -> StoreResult<Option<MotionClass>> {
        if !self.has_motion_classes()? {
            return Ok(None);
        }
        let classes = self.classes_where(
            "WHERE m.representative = (SELECT m2.representative FROM motion_classes m2
               JOIN designs d2 ON d2.topology = m2.topology WHERE d2.spec = ?1)",
            [spec],
        )?;
        Ok(classes.into_iter().next())
    }

    /// Counts of the stored classes; None when not computed.
    pub fn motion_counts(&self) -> StoreResult<Option<MotionCounts>> {
        let Some(classes) = self.motion_classes()? else {
            return Ok(None);
        };
        let shared = classes.iter().filter(|c| c.variants.len() > 1).count();
        let across = classes.iter().filter(|c| c.families() > 1).count();
        Ok(Some(MotionCounts {
            topologies: classes.iter().map(|c| c.variants.len() as u64).sum(),
            motions: classes.len() as u64,
            shared: shared as u64,
            across_families: across as u64,
        }))
    }

    fn classes_where<P: rusqlite::Params>(
        &self,
        filter: &str,
        params: P,
    ) -> StoreResult<Vec<MotionClass>> {
        let mut stmt = self.conn.prepare(&format!(
            "SELECT g.topology, g.representative, g.checksum, g.family, g.cell, g.n, g.example,
                    (SELECT e.max_area_ratio FROM designs e WHERE e.spec = g.example), g.lo, g.hi
             FROM (SELECT m.topology, m.representative, m.checksum, min(d.family) AS family,
                          min(d.cell) AS cell, count(d.id) AS n, min(d.spec) AS example,
                          min(d.max_area_ratio) AS lo, max(d.max_area_ratio) AS hi
                   FROM motion_classes m JOIN designs d ON d.topology = m.topology
                   {filter}
                   GROUP BY m.topology) g
             ORDER BY g.representative, g.topology"
        ))?;
        let rows = stmt.query_map(params, |r| {
            Ok((
                r.get::<_, String>(0)?,
                r.get::<_, String>(1)?,
                r.get::<_, i64>(2)?,
                r.get::<_, i64>(3)?,
                r.get::<_, String>(4)?,
                r.get::<_, i64>(5)?,
                r.get::<_, String>(6)?,
                r.get::<_, f64>(7)?,
                [r.get::<_, f64>(8)?, r.get::<_, f64>(9)?],
            ))
        })?;
        let mut by: BTreeMap<String, Vec<MotionVariant>> = BTreeMap::new();
        for row in rows {
            let (
                topology,
                rep,
                stored,
                family,
                cell,
                designs,
                example,
                example_area_ratio,
                area_ratio,
            ) = row?;
            verify(&motion_class_values(&topology, &rep), stored, || {
                format!("motion class row of {topology}")
            })?;
            by.entry(rep).or_default().push(MotionVariant {
                topology,
                family: format!("IH{family}"),
                cell,
                designs: designs as u64,
                example,
                example_area_ratio,
                area_ratio,
            });
        }
        let mut classes: Vec<MotionClass> = by
            .into_iter()
            .map(|(representative, variants)| MotionClass {
                representative,
                variants,
            })
            .collect();
        classes.sort_by(|a, b| {
            b.variants
                .len()
                .cmp(&a.variants.len())
                .then_with(|| a.representative.cmp(&b.representative))
        });
        Ok(classes)
    }
}

//! The catalogue's mechanisms view (issue 24, item 2): the designs matching a
//! [`DesignQuery`] grouped by the motion class of their topology (the `motion_classes` table,
//! see `motions.rs`), one group per distinct motion, with its counts and the range of every
//! main measure over the matching designs only.
//!
//! Order: designs are taken in the query's order (its sort, or the default), each group's
//! members keep that order, and groups come in the order of their first member — so a group
//! stands where its best design stands in the flat list, and its first member is its best
//! example under that sort. Designs whose topology has no class (not one DOF at its shape, a
//! user design saved since the last explore, or a file without classes) are never dropped:
//! they form one `unclassified` group, listed apart. Limit and offset of the query are
//! ignored (every matching group is returned: a catalogue has tens to hundreds of them).
//! The static site's `web/src/query.js` (`motionGroups`) computes the same answer in the
//! browser.

use crate::error::StoreResult;
use crate::open::Store;
use crate::query::filter::{filters, sorted_order};
use crate::query::DesignQuery;
use crate::records::DesignSummary;
use crate::rows::{motion_class_values, read_design, verify, DESIGN_COLUMNS, DESIGN_COLUMN_COUNT};
use isogami::cell::CellDims;
use isogami::measure::BehaviourClass;
use isogami::tiling::Family;
use rusqlite::params_from_iter;
use serde::Serialize;
use std::collections::HashMap;

/// One matching design of a group (the fields its card and variant list show).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionMember {
    /// Spec.
    pub spec: String,
    /// Family.
    pub family: Family,
    /// Cell.
    pub cell: CellDims,
    /// The topology it was sampled from.
    pub topology: String,
    /// Behaviour class.
    pub behaviour: Option<BehaviourClass>,
    /// Largest area ratio reached.
    pub max_area_ratio: f64,
    /// Largest principal expansion.
    pub max_expansion: f64,
    /// Smallest principal expansion.
    pub min_expansion: f64,
}

/// Smallest and largest value of a measure over a group.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Span {
    /// Smallest.
    pub min: f64,
    /// Largest.
    pub max: f64,
}

impl Span {
    fn of(v: f64) -> Span {
        Span { min: v, max: v }
    }

    fn widen(&mut self, lo: f64, hi: f64) {
        self.min = self.min.min(lo);
        self.max = self.max.max(hi);
    }
}

/// How many members of a group have a behaviour class.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BehaviourCount {
    /// The class (None: unclassified).
    pub value: Option<BehaviourClass>,
    /// Members with it.
    pub count: u64,
}

/// One distinct motion (or the designs without a class) over the matching designs.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionGroup {
    /// The class's representative topology; None for the group of unclassified designs.
    pub representative: Option<String>,
    /// Matching designs.
    pub designs: u64,
    /// Distinct topologies among them.
    pub topologies: u64,
    /// Distinct families, by number.
    pub families: Vec<Family>,
    /// Distinct cells, by (a, b).
    pub cells: Vec<CellDims>,
    /// Behaviour classes present, most frequent first (then by name, unclassified last).
    pub behaviours: Vec<BehaviourCount>,
    /// Range of the largest area ratio.
    pub max_area_ratio: Span,
    /// Range of the largest principal expansion.
    pub max_expansion: Span,
    /// Range of the smallest principal expansion.
    pub min_expansion: Span,
    /// Range of the largest tile rotation (radians).
    pub max_tile_rotation: Span,
    /// Poisson-like ratio: smallest `poisson_min` to largest `poisson_max` of the members
    /// that have one; None when none has.
    pub poisson: Option<Span>,
    /// The matching designs in the query's order (the first is the best example).
    pub members: Vec<MotionMember>,
}

/// The mechanisms view of a query.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MotionGroups {
    /// Whether the file has motion classes (false: every design is unclassified).
    pub computed: bool,
    /// Matching designs (over all groups).
    pub total: u64,
    /// One group per class with a matching design, in the order of their first member.
    pub groups: Vec<MotionGroup>,
    /// The matching designs without a class, if any.
    pub unclassified: Option<MotionGroup>,
}

impl MotionGroup {
    fn new(representative: Option<String>, first: &DesignSummary) -> MotionGroup {
        MotionGroup {
            representative,
            designs: 0,
            topologies: 0,
            families: Vec::new(),
            cells: Vec::new(),
            behaviours: Vec::new(),
            max_area_ratio: Span::of(first.max_area_ratio),
            max_expansion: Span::of(first.max_expansion),
            min_expansion: Span::of(first.min_expansion),
            max_tile_rotation: Span::of(first.max_tile_rotation),
            poisson: None,
            members: Vec::new(),
        }
    }

    fn add(&mut self, d: DesignSummary) {
        self.designs += 1;
        self.max_area_ratio
            .widen(d.max_area_ratio, d.max_area_ratio);
        self.max_expansion.widen(d.max_expansion, d.max_expansion);
        self.min_expansion.widen(d.min_expansion, d.min_expansion);
        self.max_tile_rotation
            .widen(d.max_tile_rotation, d.max_tile_rotation);
        if let (Some(lo), Some(hi)) = (d.poisson_min, d.poisson_max) {
            match &mut self.poisson {
                Some(p) => p.widen(lo, hi),
                None => self.poisson = Some(Span { min: lo, max: hi }),
            }
        }
        match self.behaviours.iter_mut().find(|b| b.value == d.behaviour) {
            Some(b) => b.count += 1,
            None => self.behaviours.push(BehaviourCount {
                value: d.behaviour,
                count: 1,
            }),
        }
        self.members.push(MotionMember {
            spec: d.spec,
            family: d.family,
            cell: d.cell,
            topology: d.topology,
            behaviour: d.behaviour,
            max_area_ratio: d.max_area_ratio,
            max_expansion: d.max_expansion,
            min_expansion: d.min_expansion,
        });
    }

    /// Distinct families, cells and topologies; behaviours in their order.
    fn finish(&mut self) {
        let mut families: Vec<Family> = self.members.iter().map(|m| m.family).collect();
        families.sort_by_key(|f| f.number());
        families.dedup();
        let mut cells: Vec<CellDims> = self.members.iter().map(|m| m.cell).collect();
        cells.sort_by_key(|c| (c.a(), c.b()));
        cells.dedup();
        let mut topologies: Vec<&str> = self.members.iter().map(|m| m.topology.as_str()).collect();
        topologies.sort_unstable();
        topologies.dedup();
        self.topologies = topologies.len() as u64;
        self.families = families;
        self.cells = cells;
        self.behaviours.sort_by(|x, y| {
            y.count.cmp(&x.count).then_with(|| {
                // Unclassified last, then by name.
                match (x.value, y.value) {
                    (Some(a), Some(b)) => a.as_str().cmp(b.as_str()),
                    (Some(_), None) => std::cmp::Ordering::Less,
                    (None, Some(_)) => std::cmp::Ordering::Greater,
                    (None, None) => std::cmp::Ordering::Equal,
                }
            })
        });
    }
}

impl Store {
    /// The designs matching `query` grouped by motion class (see the module docs); limit and
    /// offset are ignored. Every design row and class row read is checked against its checksum.
    pub fn motion_groups(&self, query: &DesignQuery) -> StoreResult<MotionGroups> {
        let computed = crate::open::has_table(&self.conn, "motion_classes")?;
        let w = filters(query, None)?;
        let order = sorted_order(query)?;
        let class = if computed {
            "(SELECT m.representative FROM motion_classes m WHERE m.topology = designs.topology),
             (SELECT m.checksum FROM motion_classes m WHERE m.topology = designs.topology)"
        } else {
            "NULL, NULL"
        };
        let sql = format!(
            "SELECT {DESIGN_COLUMNS}, checksum, {class} FROM designs {} {order}",
            w.sql()
        );
        let mut stmt = self.conn.prepare_cached(&sql)?;
        let mut rows = stmt.query(params_from_iter(w.params.iter()))?;
        let mut groups: Vec<MotionGroup> = Vec::new();
        let mut index: HashMap<String, usize> = HashMap::new();
        let mut unclassified: Option<MotionGroup> = None;
        let mut total = 0;
        while let Some(row) = rows.next()? {
            let (design, _) = read_design(row, 0)?;
            let rep: Option<String> = row.get(DESIGN_COLUMN_COUNT + 1)?;
            total += 1;
            let group = match rep {
                Some(rep) => {
                    let stored: i64 = row.get(DESIGN_COLUMN_COUNT + 2)?;
                    verify(&motion_class_values(&design.topology, &rep), stored, || {
                        format!("motion class row of {}", design.topology)
                    })?;
                    let k = *index.entry(rep.clone()).or_insert_with(|| {
                        groups.push(MotionGroup::new(Some(rep), &design));
                        groups.len() - 1
                    });
                    &mut groups[k]
                }
                None => unclassified.get_or_insert_with(|| MotionGroup::new(None, &design)),
            };
            group.add(design);
        }
        for g in groups.iter_mut().chain(unclassified.iter_mut()) {
            g.finish();
        }
        Ok(MotionGroups {
            computed,
            total,
            groups,
            unclassified,
        })
    }
}

//! Work-unit planning: the deterministic, ordered list of work units (family × supercell) an
//! exploration runs, and the slice of it that one shard of an N-shard run takes.
//!
//! The order is families in the order given (callers sort them), then each family's cells in
//! the order of [`cells_to_explore`] (fewest unique edges first). Shard I of N takes the units
//! at positions I, I + N, I + 2N, … of that list, so the N shards are disjoint, cover the plan
//! exactly and are balanced between cheap and expensive families. No I/O: running the units
//! and storing them is the caller's business (`isogami-store` runs a plan into a database).

use super::dedup::SymmetryGroup;
use super::pipeline::{cells_to_explore, expanded_mask_count, TopologyOptions};
use super::ExploreError;
use crate::cell::{CellDims, UnitCell};
use crate::tiling::{Family, Tiling};
use std::fmt;
use std::str::FromStr;

/// The largest shard count accepted.
pub const MAX_SHARDS: usize = 100_000;

/// The most parts a unit's masks can be split into.
pub const MAX_PARTS: usize = 4096;

/// Defines a slice type "`index` of `count`" (0-based, `count` at most `$max`): one of
/// `count` disjoint slices of a list taking positions index, index + count, …
macro_rules! slice_type {
    ($(#[$doc:meta])* $name:ident, $max:expr, $error:ident, $what:literal) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
        pub struct $name {
            index: usize,
            count: usize,
        }

        impl $name {
            #[doc = concat!("Slice `index` of `count`; refused unless `index < count <= ", stringify!($max), "`.")]
            pub fn new(index: usize, count: usize) -> Result<$name, ExploreError> {
                if count == 0 || index >= count || count > $max {
                    return Err(ExploreError::$error {
                        text: format!("{index}/{count}"),
                    });
                }
                Ok($name { index, count })
            }

            /// 0-based index.
            pub fn index(&self) -> usize {
                self.index
            }

            #[doc = concat!("Number of ", $what, ".")]
            pub fn count(&self) -> usize {
                self.count
            }

            /// Whether the item at `position` of the sliced list is in this slice.
            pub fn takes(&self, position: usize) -> bool {
                position % self.count == self.index
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}/{}", self.index, self.count)
            }
        }
    };
}

slice_type!(
    /// Part `index` of `count` of one unit's masks (see
    /// [`enumerate_topology_part`](super::pipeline::enumerate_topology_part)): how one big
    /// unit is split across processes or cluster tasks; it takes the expanded masks at
    /// positions index, index + count, … [`UnitPart::WHOLE`] is the unit undivided.
    UnitPart,
    MAX_PARTS,
    Parts,
    "parts"
);

impl UnitPart {
    /// The whole unit (part 0 of 1).
    pub const WHOLE: UnitPart = UnitPart { index: 0, count: 1 };
}

/// One item of a plan: a unit, or one part of a unit split into parts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct WorkItem {
    /// The unit.
    pub unit: WorkUnit,
    /// Which part of it ([`UnitPart::WHOLE`] for the unit undivided).
    pub part: UnitPart,
}

impl WorkItem {
    /// `IH28/2x1` for a whole unit, `IH28/2x1 part 1/3` for a part.
    pub fn id(&self) -> String {
        if self.part.count() == 1 {
            self.unit.id()
        } else {
            format!("{} part {}", self.unit, self.part)
        }
    }

    /// The unit's size, its expected cost shared equally by its parts; None when the cell
    /// cannot be built.
    pub fn size(&self) -> Option<UnitSize> {
        let size = self.unit.size()?;
        Some(UnitSize {
            expected_cost: size.expected_cost / self.part.count() as f64,
            ..size
        })
    }

    /// The unit's expected cost ([`WorkUnit::expected_cost`]) shared equally by its parts.
    pub fn expected_cost(&self) -> f64 {
        self.size().map_or(0.0, |s| s.expected_cost)
    }

    /// `items` ordered by [`WorkItem::expected_cost`], largest first (ties keep the order
    /// given): the order in which a scheduler that hands out one item at a time keeps every
    /// core busy to the end.
    pub fn longest_first(items: &[WorkItem]) -> Vec<WorkItem> {
        let mut costed: Vec<(f64, WorkItem)> =
            items.iter().map(|i| (i.expected_cost(), *i)).collect();
        costed.sort_by(|a, b| b.0.total_cmp(&a.0));
        costed.into_iter().map(|(_, i)| i).collect()
    }
}

/// Cells with at most this many unique edges have their masks counted before a split, so
/// that they are never split into parts with nothing to do. Counting runs the unit's reduced
/// checks, cheap at this size (the default exploration's cap) but minutes per process for
/// the 24-edge cells of a cluster run, which have thousands of masks per part anyway.
pub const COUNTED_EDGES: usize = 16;

/// One unit of work: every topology of a family on one supercell, then its shape samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct WorkUnit {
    /// Tiling family.
    pub family: Family,
    /// Supercell.
    pub dims: CellDims,
}

impl WorkUnit {
    /// The unit's id, unique within a database, e.g. `IH28/2x1`.
    pub fn id(&self) -> String {
        self.to_string()
    }
}

/// How big a work unit is, known before running it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct UnitSize {
    /// Unique edges of the cell.
    pub edges: usize,
    /// Order of the sheet's symmetry group.
    pub symmetry_group: usize,
    /// [`WorkUnit::expected_cost`].
    pub expected_cost: f64,
}

impl WorkUnit {
    /// The unit's size, or None when its cell cannot be built.
    pub fn size(&self) -> Option<UnitSize> {
        let cell = UnitCell::new(&Tiling::default_for(self.family), self.dims).ok()?;
        let group = SymmetryGroup::new(&cell).len().max(1);
        Some(UnitSize {
            edges: cell.edges.len(),
            symmetry_group: group,
            expected_cost: 3f64.powi(cell.edges.len() as i32) / group as f64,
        })
    }

    /// A relative estimate of the unit's running time, for handing out the longest units
    /// first: 3^m / |G|, with m the cell's unique edges and |G| the order of the sheet's
    /// symmetry group. Each edge is free, jointed at A or jointed at B, and the enumeration
    /// visits one design per symmetry orbit, so this counts the designs the unit weighs; on
    /// the default run it puts the five slowest units (the low-symmetry hexagon cells, whose
    /// thousands of unique topologies are all deployed) first. Not a time: only the order
    /// matters. 0 for a cell that cannot be built (it fails at once).
    pub fn expected_cost(&self) -> f64 {
        self.size().map_or(0.0, |s| s.expected_cost)
    }
}

impl fmt::Display for WorkUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.family, self.dims)
    }
}

slice_type!(
    /// Shard `index` of `count` (0-based): one of `count` disjoint slices of a plan's items.
    Shard,
    MAX_SHARDS,
    Shard,
    "shards"
);

impl FromStr for Shard {
    type Err = ExploreError;

    /// Reads `I/N` (spaces around either number allowed).
    fn from_str(text: &str) -> Result<Shard, ExploreError> {
        let bad = || ExploreError::Shard {
            text: text.to_string(),
        };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let i: usize = i.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        Shard::new(i, n).map_err(|_| bad())
    }
}

/// An exploration's plan: every unit of the run in order, how many parts each unit's masks
/// are split into, and the shard this process runs.
#[derive(Debug, Clone, PartialEq)]
pub struct ExplorePlan {
    /// Every unit of the whole (unsharded) run, in the deterministic order.
    pub all: Vec<WorkUnit>,
    /// The shard this process runs; `None` for the whole plan.
    pub shard: Option<Shard>,
    /// Parts requested for every unit (1: whole units). A unit is split into at most as many
    /// parts as it has masks to expand ([`ExplorePlan::parts_of`]), never into empty parts.
    /// The plan's items are each unit's parts in turn, and shards take items, so N shards
    /// spread one big unit's P parts over min(N, P) tasks.
    pub parts: usize,
    /// Parts of each unit of `all` (same order): `min(parts, its expanded masks)`, at least 1,
    /// for cells of at most [`COUNTED_EDGES`] unique edges; `parts` for larger ones.
    unit_parts: Vec<usize>,
}

impl ExplorePlan {
    /// Plans the units of `families` (in the order given) on the cells that `options` allow
    /// (at most `max_dims` per side and `max_edges` unique edges), keeping only `cells` when
    /// given, then takes `shard`'s slice.
    ///
    /// Requested cells are never dropped silently: a requested cell larger than `max_dims`
    /// ([`ExploreError::CellOverDims`]), over the edge cap for some family
    /// ([`ExploreError::CellsOverCap`], naming the cap that would take them all) or that
    /// cannot be built for some family is an error.
    pub fn new(
        families: &[Family],
        cells: Option<&[CellDims]>,
        options: &TopologyOptions,
        shard: Option<Shard>,
    ) -> Result<ExplorePlan, ExploreError> {
        let mut wanted: Vec<CellDims> = Vec::new();
        for &dims in cells.unwrap_or_default() {
            if dims.a().max(dims.b()) > options.max_dims {
                return Err(ExploreError::CellOverDims {
                    dims,
                    max_dims: options.max_dims,
                });
            }
            if !wanted.contains(&dims) {
                wanted.push(dims);
            }
        }
        let mut all = Vec::new();
        let mut over: Vec<(WorkUnit, usize)> = Vec::new();
        for &family in families {
            let allowed = cells_to_explore(family, options);
            for &(dims, _) in &allowed {
                if cells.is_none() || wanted.contains(&dims) {
                    all.push(WorkUnit { family, dims });
                }
            }
            for &dims in &wanted {
                if allowed.iter().any(|(d, _)| *d == dims) {
                    continue;
                }
                let cell = UnitCell::new(&Tiling::default_for(family), dims)?;
                over.push((WorkUnit { family, dims }, cell.edges.len()));
            }
        }
        if let Some(&(first, edges)) = over.first() {
            return Err(ExploreError::CellsOverCap {
                family: first.family,
                dims: first.dims,
                edges,
                max_edges: options.max_edges,
                others: over.len() - 1,
                needed: over.iter().map(|(_, m)| *m).max().unwrap_or(edges),
            });
        }
        let unit_parts = vec![1; all.len()];
        Ok(ExplorePlan {
            all,
            shard,
            parts: 1,
            unit_parts,
        })
    }

    /// The same plan with every unit split into `parts` parts (1..=[`MAX_PARTS`]), or into
    /// fewer when a cell of at most [`COUNTED_EDGES`] edges has fewer masks to expand than that
    /// ([`expanded_mask_count`](super::pipeline::expanded_mask_count), which runs the unit's
    /// reduced checks): a part never starts with nothing to do. Still a deterministic function
    /// of the unit and `parts`, so every shard of a run plans the same items.
    pub fn split(self, parts: usize) -> Result<ExplorePlan, ExploreError> {
        UnitPart::new(0, parts).map_err(|_| ExploreError::Parts {
            text: parts.to_string(),
        })?;
        let unit_parts = self
            .all
            .iter()
            .map(|u| {
                let small = u.size().is_some_and(|s| s.edges <= COUNTED_EDGES);
                if parts == 1 || !small {
                    parts
                } else {
                    parts.min(expanded_mask_count(u.family, u.dims)).max(1)
                }
            })
            .collect();
        Ok(ExplorePlan {
            parts,
            unit_parts,
            ..self
        })
    }

    /// How many parts `unit` is split into (1 for a unit not in the plan).
    pub fn parts_of(&self, unit: &WorkUnit) -> usize {
        self.all
            .iter()
            .position(|u| u == unit)
            .map_or(1, |k| self.unit_parts[k])
    }

    /// Every item of the whole run: each unit's parts in turn, in unit order.
    pub fn all_items(&self) -> Vec<WorkItem> {
        self.all
            .iter()
            .zip(&self.unit_parts)
            .flat_map(|(&unit, &count)| {
                (0..count).map(move |k| WorkItem {
                    unit,
                    part: UnitPart { index: k, count },
                })
            })
            .collect()
    }

    /// The items this process runs: the shard's slice of [`ExplorePlan::all_items`], in order.
    pub fn items(&self) -> Vec<WorkItem> {
        self.all_items()
            .into_iter()
            .enumerate()
            .filter(|(k, _)| self.shard.is_none_or(|s| s.takes(*k)))
            .map(|(_, item)| item)
            .collect()
    }

    /// The units this process runs at least a part of, in order.
    pub fn units(&self) -> Vec<WorkUnit> {
        let mut units: Vec<WorkUnit> = self.items().into_iter().map(|i| i.unit).collect();
        units.dedup();
        units
    }
}

#[cfg(test)]
mod tests;

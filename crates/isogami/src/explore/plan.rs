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
mod tests {
    use super::*;
    use std::collections::HashSet;

    fn fam(name: &str) -> Family {
        name.parse().unwrap()
    }

    #[test]
    fn shards_partition_the_plan_in_order() {
        let families = [fam("IH1"), fam("IH28"), fam("IH90")];
        let whole = ExplorePlan::new(&families, None, &TopologyOptions::default(), None).unwrap();
        assert!(whole.all.len() > 5, "{} units", whole.all.len());
        assert_eq!(whole.units(), whole.all);
        let ids: HashSet<String> = whole.all.iter().map(WorkUnit::id).collect();
        assert_eq!(ids.len(), whole.all.len(), "unit ids are unique");
        let n = 4;
        let mut seen = Vec::new();
        for i in 0..n {
            let shard = Shard::new(i, n).unwrap();
            let plan = ExplorePlan::new(&families, None, &TopologyOptions::default(), Some(shard))
                .unwrap();
            assert_eq!(plan.all, whole.all, "every shard knows the whole plan");
            let units = plan.units();
            // Positions i, i + n, …: balanced to within one unit.
            assert!(units.len().abs_diff(whole.all.len() / n) <= 1);
            for (k, u) in units.iter().enumerate() {
                assert_eq!(*u, whole.all[i + k * n]);
            }
            seen.extend(units);
        }
        assert_eq!(seen.len(), whole.all.len());
        let seen: HashSet<String> = seen.iter().map(WorkUnit::id).collect();
        assert_eq!(seen, ids);
    }

    #[test]
    fn cells_filter_keeps_only_the_named_cells() {
        let one = CellDims::new(1, 1).unwrap();
        let plan = ExplorePlan::new(
            &[fam("IH28"), fam("IH1")],
            Some(&[one]),
            &TopologyOptions::default(),
            None,
        )
        .unwrap();
        let ids: Vec<String> = plan.all.iter().map(WorkUnit::id).collect();
        assert_eq!(ids, ["IH28/1x1", "IH1/1x1"], "families in the order given");
    }

    #[test]
    fn requested_cells_over_the_cap_are_an_error_naming_the_cap() {
        let three = CellDims::new(3, 3).unwrap();
        let options = TopologyOptions::default();
        let e = ExplorePlan::new(&[fam("IH76")], Some(&[three]), &options, None).unwrap_err();
        match &e {
            ExploreError::CellsOverCap {
                edges,
                max_edges,
                others,
                needed,
                ..
            } => assert_eq!((*edges, *max_edges, *others, *needed), (18, 16, 0, 18)),
            other => panic!("{other:?}"),
        }
        let text = e.to_string();
        assert!(
            text.contains("IH76/3x3") && text.contains("max_edges = 16"),
            "{text}"
        );
        // Raising the cap takes the cell.
        let wide = TopologyOptions {
            max_edges: 18,
            ..options
        };
        let plan = ExplorePlan::new(&[fam("IH76")], Some(&[three]), &wide, None).unwrap();
        assert_eq!(plan.all.len(), 1);
        // Several families: every pair over the cap is counted, the largest names the cap.
        let one = CellDims::new(1, 1).unwrap();
        let e = ExplorePlan::new(
            &[fam("IH1"), fam("IH76"), fam("IH77")],
            Some(&[one, three]),
            &options,
            None,
        )
        .unwrap_err();
        let ExploreError::CellsOverCap {
            family,
            others,
            needed,
            ..
        } = e
        else {
            panic!("{e:?}");
        };
        assert_eq!(family, fam("IH1"), "the first pair in plan order");
        assert!(others >= 2, "IH76/3x3 and IH77's cells");
        assert!(needed > 18, "IH1 3x3 has more than 18 edges: {needed}");
    }

    #[test]
    fn ih77_minimal_cell_is_planned_only_under_a_raised_cap() {
        let f = fam("IH77");
        let default = ExplorePlan::new(&[f], None, &TopologyOptions::default(), None).unwrap();
        assert!(default.all.is_empty(), "18 edges: nothing at cap 16");
        let one = CellDims::new(1, 1).unwrap();
        assert!(matches!(
            ExplorePlan::new(&[f], Some(&[one]), &TopologyOptions::default(), None),
            Err(ExploreError::CellsOverCap { edges: 18, .. })
        ));
        let cap20 = TopologyOptions {
            max_edges: 20,
            ..TopologyOptions::default()
        };
        let plan = ExplorePlan::new(&[f], None, &cap20, None).unwrap();
        assert_eq!(
            plan.all.first().map(WorkUnit::id).as_deref(),
            Some("IH77/1x1")
        );
    }

    #[test]
    fn requested_cells_beyond_max_dims_are_an_error() {
        let quick = TopologyOptions {
            max_dims: 1,
            ..TopologyOptions::default()
        };
        let two = CellDims::new(2, 1).unwrap();
        let e = ExplorePlan::new(&[fam("IH90")], Some(&[two]), &quick, None).unwrap_err();
        assert_eq!(
            e,
            ExploreError::CellOverDims {
                dims: two,
                max_dims: 1
            }
        );
        assert!(e.to_string().contains("max_dims"), "{e}");
    }

    #[test]
    fn longest_first_orders_by_expected_cost_and_keeps_every_unit() {
        let families = [fam("IH21"), fam("IH22"), fam("IH76"), fam("IH90")];
        let plan = ExplorePlan::new(&families, None, &TopologyOptions::default(), None).unwrap();
        let order: Vec<WorkUnit> = WorkItem::longest_first(&plan.items())
            .into_iter()
            .map(|i| i.unit)
            .collect();
        let mut a: Vec<String> = order.iter().map(WorkUnit::id).collect();
        let mut b: Vec<String> = plan.all.iter().map(WorkUnit::id).collect();
        a.sort();
        b.sort();
        assert_eq!(a, b, "a permutation of the plan");
        let costs: Vec<f64> = order.iter().map(WorkUnit::expected_cost).collect();
        assert!(costs.windows(2).all(|w| w[0] >= w[1]), "{costs:?}");
        // The slowest units of the default run (low-symmetry hexagon cells deploying
        // thousands of topologies) come before every rotating-squares cell.
        let pos = |id: &str| order.iter().position(|u| u.id() == id).unwrap();
        assert!(pos("IH21/1x1") < pos("IH76/2x4") && pos("IH22/3x1") < pos("IH76/2x4"));
        // 3^m / |G|: IH21's minimal cell has 15 edges and 6 symmetries.
        let ih21 = WorkUnit {
            family: fam("IH21"),
            dims: CellDims::new(1, 1).unwrap(),
        };
        assert_eq!(ih21.expected_cost(), 3f64.powi(15) / 6.0);
    }

    #[test]
    fn a_unit_is_never_split_into_more_parts_than_it_has_masks() {
        use super::super::pipeline::enumerate_topology_part;
        let options = TopologyOptions::default();
        let one = CellDims::new(1, 1).unwrap();
        let families = [fam("IH90"), fam("IH28")];
        let plan = ExplorePlan::new(&families, Some(&[one]), &options, None)
            .unwrap()
            .split(MAX_PARTS)
            .unwrap();
        let items = plan.all_items();
        let mut total = 0;
        for unit in &plan.all {
            let masks = expanded_mask_count(unit.family, unit.dims);
            let whole =
                enumerate_topology_part(unit.family, unit.dims, &options, UnitPart::WHOLE).unwrap();
            assert_eq!(masks as u64, whole.masks_expanded, "{unit}");
            assert!(masks < MAX_PARTS, "{unit}: {masks} masks");
            assert_eq!(plan.parts_of(unit), masks.max(1), "{unit}");
            total += plan.parts_of(unit);
            // Every part has work: at least one mask, and the parts' masks add up.
            let mut sum = 0;
            for item in items.iter().filter(|i| i.unit == *unit) {
                assert_eq!(item.part.count(), plan.parts_of(unit));
                let r =
                    enumerate_topology_part(unit.family, unit.dims, &options, item.part).unwrap();
                assert!(r.masks_expanded >= 1, "{} is empty", item.id());
                sum += r.masks_expanded;
            }
            assert_eq!(sum, whole.masks_expanded, "{unit}");
        }
        assert_eq!(items.len(), total);
        // Fewer parts than masks: the count asked for.
        let two = ExplorePlan::new(&families, Some(&[one]), &options, None)
            .unwrap()
            .split(2)
            .unwrap();
        let mut total = 0;
        for u in &two.all {
            let masks = expanded_mask_count(u.family, u.dims);
            assert_eq!(two.parts_of(u), masks.clamp(1, 2), "{u}");
            total += two.parts_of(u);
        }
        assert!(two.all.iter().any(|u| two.parts_of(u) == 2));
        assert_eq!(two.all_items().len(), total);
    }

    #[test]
    fn shard_text_round_trips_and_bad_shards_are_refused() {
        let s: Shard = " 2 / 5".parse().unwrap();
        assert_eq!((s.index(), s.count()), (2, 5));
        assert_eq!(s.to_string().parse::<Shard>().unwrap(), s);
        for bad in ["3/3", "1/0", "x", "1:2", "-1/2", "0/100001", ""] {
            let e = bad.parse::<Shard>().unwrap_err();
            assert!(e.to_string().contains(&format!("'{bad}'")), "{e}");
        }
        assert!(Shard::new(0, MAX_SHARDS).is_ok());
        assert!(Shard::new(4, 4).is_err());
    }
}

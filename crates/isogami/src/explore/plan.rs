//! Work-unit planning: the deterministic, ordered list of work units (family × supercell) an
//! exploration runs, and the slice of it that one shard of an N-shard run takes.
//!
//! The order is families in the order given (callers sort them), then each family's cells in
//! the order of [`cells_to_explore`] (fewest unique edges first). Shard I of N takes the units
//! at positions I, I + N, I + 2N, … of that list, so the N shards are disjoint, cover the plan
//! exactly and are balanced between cheap and expensive families. No I/O: running the units
//! and storing them is the caller's business (`isogami-store` runs a plan into a database).

use super::pipeline::{cells_to_explore, TopologyOptions};
use super::ExploreError;
use crate::cell::CellDims;
use crate::tiling::Family;
use std::fmt;
use std::str::FromStr;

/// The largest shard count accepted.
pub const MAX_SHARDS: usize = 100_000;

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

impl fmt::Display for WorkUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.family, self.dims)
    }
}

/// Shard `index` of `count` (0-based): one of `count` disjoint slices of a plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Shard {
    index: usize,
    count: usize,
}

impl Shard {
    /// Shard `index` of `count`; refused unless `index < count <= MAX_SHARDS`.
    pub fn new(index: usize, count: usize) -> Result<Shard, ExploreError> {
        if count == 0 || index >= count || count > MAX_SHARDS {
            return Err(ExploreError::Shard {
                text: format!("{index}/{count}"),
            });
        }
        Ok(Shard { index, count })
    }

    /// 0-based index.
    pub fn index(&self) -> usize {
        self.index
    }

    /// Number of shards.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Whether the unit at `position` of the whole plan belongs to this shard.
    pub fn takes(&self, position: usize) -> bool {
        position % self.count == self.index
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

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

/// An exploration's plan: every unit of the run in order, and the shard this process runs.
#[derive(Debug, Clone, PartialEq)]
pub struct ExplorePlan {
    /// Every unit of the whole (unsharded) run, in the deterministic order.
    pub all: Vec<WorkUnit>,
    /// The shard this process runs; `None` for the whole plan.
    pub shard: Option<Shard>,
}

impl ExplorePlan {
    /// Plans the units of `families` (in the order given) on the cells that `options` allow
    /// (at most `max_dims` per side and `max_edges` unique edges), keeping only `cells` when
    /// given, then takes `shard`'s slice.
    pub fn new(
        families: &[Family],
        cells: Option<&[CellDims]>,
        options: &TopologyOptions,
        shard: Option<Shard>,
    ) -> ExplorePlan {
        let mut all = Vec::new();
        for &family in families {
            for (dims, _) in cells_to_explore(family, options) {
                if cells.is_none_or(|w| w.contains(&dims)) {
                    all.push(WorkUnit { family, dims });
                }
            }
        }
        ExplorePlan { all, shard }
    }

    /// The units this process runs: the shard's slice of [`ExplorePlan::all`], in order.
    pub fn units(&self) -> Vec<WorkUnit> {
        self.all
            .iter()
            .enumerate()
            .filter(|(k, _)| self.shard.is_none_or(|s| s.takes(*k)))
            .map(|(_, u)| *u)
            .collect()
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
        let whole = ExplorePlan::new(&families, None, &TopologyOptions::default(), None);
        assert!(whole.all.len() > 5, "{} units", whole.all.len());
        assert_eq!(whole.units(), whole.all);
        let ids: HashSet<String> = whole.all.iter().map(WorkUnit::id).collect();
        assert_eq!(ids.len(), whole.all.len(), "unit ids are unique");
        let n = 4;
        let mut seen = Vec::new();
        for i in 0..n {
            let shard = Shard::new(i, n).unwrap();
            let plan = ExplorePlan::new(&families, None, &TopologyOptions::default(), Some(shard));
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
        );
        let ids: Vec<String> = plan.all.iter().map(WorkUnit::id).collect();
        assert_eq!(ids, ["IH28/1x1", "IH1/1x1"], "families in the order given");
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

//! Topology enumeration for one family and cell at default shape parameters: the reduced
//! checks, expansion to endpoint choices with mobility = 1, separation, deduplication — with
//! the count and time of every stage — and the list of cells to explore for a family.
//!
//! Only one mask per symmetry orbit of masks is expanded; the counts of dof = 1 and separating
//! configurations are weighted by the orbit size, so they count every configuration of every
//! surviving mask (the tests check this against brute force). Every kept design is analysed
//! once more by `mobility::analyze`, which supplies its reported gap and motion.
//!
//! Deterministic: the same input gives the same counts and designs in the same order, whatever
//! the number of threads. The expansion of the masks and the analyses of deduplication run on
//! the current rayon pool (every tally is a sum or a set union, and deduplication merges its
//! analysed orbits in key order), so one large cell keeps every core busy; stage times are
//! seconds of work summed over threads. Deployment and the expansion threshold come after this
//! stage and are not done here. No I/O.

use super::dedup::{dedup_orbits, MotionInvariant, SymmetryGroup};
use super::error::ExploreError;
use super::expand::{ExpandStats, Expander};
use super::plan::UnitPart;
use super::reduced::{ReducedGraph, MAX_REDUCED_EDGES};
use super::separate::{separation, Separation, SeparationRule};
use crate::cell::{CellDims, UnitCell};
use crate::kinematics::Mechanism;
use crate::mobility::MobilitySettings;
use crate::settings_error::{Requirement, SettingsError};
use crate::tiling::{Family, Tiling};
use crate::topology::{Design, JointChoice};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeSet;
use std::time::{Duration, Instant};

/// Options of the topology enumeration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TopologyOptions {
    /// Largest number of unique edges of an explored cell (the paper: 16).
    pub max_edges: usize,
    /// Largest supercell repetition along either tiling vector (1..=4).
    pub max_dims: u8,
    /// The mobility analysis used at the leaves (the same default as `isogami analyze`).
    pub mobility: MobilitySettings,
    /// Which motions count as separating.
    pub separation: SeparationRule,
}

impl Default for TopologyOptions {
    fn default() -> Self {
        TopologyOptions {
            max_edges: 16,
            max_dims: 4,
            mobility: MobilitySettings::default(),
            separation: SeparationRule::default(),
        }
    }
}

/// Largest supercell repetition along either tiling vector (`CellDims`' own limit).
pub const MAX_DIMS: u8 = 4;

impl TopologyOptions {
    /// Checks the cell limits: `max_edges` in 1..=24 (the enumerator's limit, masks are
    /// `u32` and 2^24 is already hours of work per cell) and `max_dims` in 1..=4.
    pub fn validate(&self) -> Result<(), SettingsError> {
        if self.max_edges == 0 || self.max_edges > MAX_REDUCED_EDGES {
            return Err(SettingsError::new(
                "max_edges",
                self.max_edges,
                Requirement::CountIn {
                    low: 1,
                    high: MAX_REDUCED_EDGES as u64,
                },
            )
            .with_note("the topology enumeration's limit"));
        }
        if self.max_dims == 0 || self.max_dims > MAX_DIMS {
            return Err(SettingsError::new(
                "max_dims",
                usize::from(self.max_dims),
                Requirement::CountIn {
                    low: 1,
                    high: u64::from(MAX_DIMS),
                },
            ));
        }
        Ok(())
    }
}

/// Wall-clock time of every stage.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StageTimings {
    /// Building the tiling, the cell and its adjacency structure.
    pub setup: Duration,
    /// The four cheap checks over all 2^m masks.
    pub reduced: Duration,
    /// Expansion to endpoint choices and mobility (separation time excluded).
    pub expand: Duration,
    /// The separation test of the dof = 1 configurations.
    pub separate: Duration,
    /// Deduplication.
    pub dedup: Duration,
    /// Everything.
    pub total: Duration,
}

/// Facts about one kept design; `details[i]` belongs to `designs[i]`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DesignDetails {
    /// The design's spec string.
    pub spec: String,
    /// Number of pin joints.
    pub joints: usize,
    /// Spectral gap of the mobility analysis (decades).
    pub gap_decades: Option<f64>,
    /// Rate of change of the cell area along the motion (non-dimensional).
    pub area_rate: f64,
    /// Separation verdict.
    pub separation: Separation,
    /// Largest first-order closing rates along both signs of its motion (see
    /// [`closing_rates`](super::separate::closing_rates)).
    pub closing: Option<[f64; 2]>,
    /// Size of its symmetry orbit: designs equal to it up to a symmetry of the sheet.
    pub orbit_size: usize,
    /// Other symmetry orbits with the same motion merged into it.
    pub same_motion_merged: usize,
    /// Its motion invariant (comparable across cells and families with the same edge count).
    pub invariant: MotionInvariant,
    /// Its canonical key (keys order like specs within a cell).
    pub key: u64,
    /// Key of the first design of its motion class (see `dedup::Kept`).
    pub first_key: u64,
    /// The first design's invariant when it is not this design's (see `dedup::Kept`).
    pub first_invariant: Option<MotionInvariant>,
}

/// The result of enumerating the topologies of one family and cell.
#[derive(Debug, Clone, PartialEq)]
pub struct TopologyReport {
    /// Tiling family.
    pub family: Family,
    /// Supercell.
    pub dims: CellDims,
    /// Tiles in the cell.
    pub tiles: usize,
    /// Unique edges m.
    pub edges: usize,
    /// 2^m.
    pub masks_total: u64,
    /// Masks passing check 1 (degree ≥ 2).
    pub after_degree: u64,
    /// … and check 2 (path-connected).
    pub after_connected: u64,
    /// … and check 3 (two independent directions).
    pub after_directions: u64,
    /// … and check 4 (no jointed triangle).
    pub after_triangles: u64,
    /// … and Maxwell's count 2k ≥ 3n (reported, not a separate filter: the expansion drops
    /// the other masks at once).
    pub after_counting: u64,
    /// Σ 2^k over surviving masks (k jointed edges): the endpoint configurations expanded.
    pub configurations_expanded: u64,
    /// Surviving masks actually expanded: one per symmetry orbit of masks.
    pub masks_expanded: u64,
    /// Order of the sheet's symmetry group (modulo the supercell lattice).
    pub symmetry_group: usize,
    /// Configurations with exactly one degree of freedom (over all surviving masks).
    pub mobility_one: u64,
    /// … whose motion separates under `options.separation`.
    pub separating: u64,
    /// Distinct symmetry orbits among those.
    pub symmetry_classes: u64,
    /// Orbit representatives that `mobility::analyze` did not confirm at dof = 1 (expected 0).
    pub unconfirmed: u64,
    /// Orbits left after removing repeats of smaller cells.
    pub after_repeats: u64,
    /// Designs left after merging equal motions.
    pub unique: u64,
    /// Details of the expansion search (nodes, prunes, certified leaves, analyses) over the
    /// expanded masks; `configurations` counts all surviving masks.
    pub expand_stats: ExpandStats,
    /// The kept designs, in spec order.
    pub designs: Vec<Design>,
    /// Facts about each kept design (same order).
    pub details: Vec<DesignDetails>,
    /// Time per stage.
    pub timings: StageTimings,
}

/// What the parallel expansion of many masks adds up: sums and a set union, so independent of
/// the order and grouping of the masks.
#[derive(Default)]
struct ExpandTally {
    stats: ExpandStats,
    mobility_one: u64,
    separating: u64,
    orbits: BTreeSet<u64>,
    /// Time spent expanding, summed over the masks.
    work: Duration,
    /// Of which in the separation test.
    separate: Duration,
}

impl ExpandTally {
    fn merge(mut self, mut other: ExpandTally) -> ExpandTally {
        self.stats.add(&other.stats);
        self.mobility_one += other.mobility_one;
        self.separating += other.separating;
        if self.orbits.len() < other.orbits.len() {
            std::mem::swap(&mut self.orbits, &mut other.orbits);
        }
        self.orbits.append(&mut other.orbits);
        self.work += other.work;
        self.separate += other.separate;
        self
    }
}

/// Enumerates the joint topologies of `family` (default shape parameters) on the `dims`
/// supercell. Fails when the cell has more than `options.max_edges` unique edges (or more than
/// the enumerator's limit of 24) or cannot be built.
pub fn enumerate_topologies(
    family: Family,
    dims: CellDims,
    options: &TopologyOptions,
) -> Result<TopologyReport, ExploreError> {
    enumerate_topology_part(family, dims, options, UnitPart::WHOLE)
}

/// How many masks `family` on `dims` expands: the masks that pass the reduced checks, one per
/// symmetry orbit, the list that [`enumerate_topology_part`] slices into parts. A split into
/// more parts than this leaves parts with nothing to do. Runs only the reduced checks (no
/// expansion); 0 when the cell cannot be built or has more than the enumerator's limit of
/// edges. Memoised per (family, cell) for the life of the process.
pub fn expanded_mask_count(family: Family, dims: CellDims) -> usize {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static MEMO: OnceLock<Mutex<HashMap<(Family, CellDims), usize>>> = OnceLock::new();
    let memo = MEMO.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(n) = memo
        .lock()
        .ok()
        .and_then(|m| m.get(&(family, dims)).copied())
    {
        return n;
    }
    let count = (|| {
        let cell = UnitCell::new(&Tiling::default_for(family), dims).ok()?;
        if cell.edges.len() > MAX_REDUCED_EDGES {
            return None;
        }
        let graph = ReducedGraph::new(&cell)?;
        let group = SymmetryGroup::new(&cell);
        let survivors = graph.enumerate().survivors;
        Some(
            survivors
                .par_iter()
                .filter(|&&mask| group.mask_orbit(mask).0 == mask)
                .count(),
        )
    })()
    .unwrap_or(0);
    if let Ok(mut m) = memo.lock() {
        m.insert((family, dims), count);
    }
    count
}

/// [`enumerate_topologies`] on one part of the cell's masks: the masks expanded are one per
/// symmetry orbit, and part I of N takes those at positions I, I + N, … of that list. The
/// parts' orbits are disjoint (an orbit of configurations lies over one orbit of masks), so
/// their counts add up; the reduced checks' counts and `configurations_expanded` cover every
/// mask in every part. `designs` and `details` are the part's own deduplication: a design of
/// one part may repeat the motion of another part's, which `catalog::combine_parts` merges.
pub fn enumerate_topology_part(
    family: Family,
    dims: CellDims,
    options: &TopologyOptions,
    part: UnitPart,
) -> Result<TopologyReport, ExploreError> {
    let start = Instant::now();
    let tiling = Tiling::default_for(family);
    let cell = UnitCell::new(&tiling, dims)?;
    let m = cell.edges.len();
    let limit = options.max_edges.min(MAX_REDUCED_EDGES);
    let too_many = || ExploreError::TooManyEdges {
        family,
        dims,
        edges: m,
        limit,
    };
    if m > limit {
        return Err(too_many());
    }
    let graph = ReducedGraph::new(&cell).ok_or_else(too_many)?;
    let reference = Mechanism::new(&cell, &vec![JointChoice::None; m])?;
    let expander = Expander::new(&cell, options.mobility)?;
    let group = SymmetryGroup::new(&cell);
    let mut timings = StageTimings {
        setup: start.elapsed(),
        ..StageTimings::default()
    };

    let t = Instant::now();
    let reduced = graph.enumerate();
    timings.reduced = t.elapsed();

    // Expand one mask per symmetry orbit; a configuration's images under the orbit's other
    // masks have the same dof and separation, so counts are weighted by the orbit size.
    // Masks are expanded in parallel; every tally is a sum or a set union, so the result does
    // not depend on how the masks are split between threads.
    let t = Instant::now();
    let canonical: Vec<(u32, u64)> = reduced
        .survivors
        .par_iter()
        .filter_map(|&mask| {
            let (canonical, size) = group.mask_orbit(mask);
            (canonical == mask).then_some((mask, size as u64))
        })
        .collect::<Vec<_>>()
        .into_iter()
        .enumerate()
        .filter(|(k, _)| part.takes(*k))
        .map(|(_, m)| m)
        .collect();
    let masks_expanded = canonical.len() as u64;
    let orbit_time = t.elapsed();
    let tally = canonical
        .par_iter()
        .fold(ExpandTally::default, |mut acc, &(mask, weight)| {
            let started = Instant::now();
            let mut local_sep = 0u64;
            let mut separate_time = Duration::ZERO;
            let s = expander.expand(mask, &mut |leaf| {
                let ts = Instant::now();
                let sep = separation(&cell, &reference, leaf.joints, leaf.motion);
                if sep.passes(options.separation) {
                    local_sep += 1;
                    acc.orbits.insert(group.canonical_key(leaf.joints).0);
                }
                separate_time += ts.elapsed();
            });
            acc.mobility_one += weight * s.mobility_one;
            acc.separating += weight * local_sep;
            acc.stats.add(&s);
            acc.separate += separate_time;
            acc.work += started.elapsed();
            acc
        })
        .reduce(ExpandTally::default, ExpandTally::merge);
    let ExpandTally {
        mut stats,
        mobility_one,
        separating,
        orbits,
        work,
        separate: separate_time,
    } = tally;
    // Configurations stand for every surviving mask, expanded or not.
    stats.configurations = reduced
        .survivors
        .iter()
        .map(|mask| 1u64 << mask.count_ones())
        .sum();
    // Seconds of work summed over threads (the wall time when single threaded).
    timings.expand = (orbit_time + work).saturating_sub(separate_time);
    timings.separate = separate_time;

    let t = Instant::now();
    let result = dedup_orbits(
        &cell,
        &reference,
        &group,
        &expander,
        &orbits,
        options.mobility,
    );
    // Seconds of work: the analyses summed over threads (at least the wall time).
    let wall = t.elapsed();
    timings.dedup = result.work.max(wall);

    let mut designs = Vec::with_capacity(result.kept.len());
    let mut details = Vec::with_capacity(result.kept.len());
    for k in &result.kept {
        let design = Design::new(family, tiling.params(), dims, k.joints.clone());
        details.push(DesignDetails {
            spec: design.to_string(),
            joints: design.joint_count(),
            gap_decades: k.gap_decades,
            area_rate: k.area_rate,
            separation: k.separation,
            closing: k.closing,
            orbit_size: k.orbit_size,
            same_motion_merged: k.same_motion_merged,
            invariant: k.invariant.clone(),
            key: k.key,
            first_key: k.first_key,
            first_invariant: k.first_invariant.clone(),
        });
        designs.push(design);
    }
    timings.total = start.elapsed();
    Ok(TopologyReport {
        family,
        dims,
        tiles: cell.tiles.len(),
        edges: m,
        masks_total: reduced.masks_total,
        after_degree: reduced.after_degree,
        after_connected: reduced.after_connected,
        after_directions: reduced.after_directions,
        after_triangles: reduced.after_triangles,
        after_counting: reduced.after_counting,
        configurations_expanded: stats.configurations,
        masks_expanded,
        symmetry_group: group.len(),
        mobility_one,
        separating,
        symmetry_classes: result.symmetry_classes as u64,
        unconfirmed: result.unconfirmed as u64,
        after_repeats: result.after_repeats as u64,
        unique: designs.len() as u64,
        expand_stats: stats,
        designs,
        details,
        timings,
    })
}

/// The cells to explore for `family`: every a×b with 1 ≤ a, b ≤ `options.max_dims` (at most
/// 4) whose cell has at most `options.max_edges` unique edges, as (dims, edge count), ordered
/// by edge count, then a, then b. Cells that fail to build are left out.
pub fn cells_to_explore(family: Family, options: &TopologyOptions) -> Vec<(CellDims, usize)> {
    let tiling = Tiling::default_for(family);
    let top = options.max_dims.clamp(1, MAX_DIMS);
    let mut out = Vec::new();
    for a in 1..=top {
        for b in 1..=top {
            let Ok(dims) = CellDims::new(a, b) else {
                continue;
            };
            if let Ok(cell) = UnitCell::new(&tiling, dims) {
                if cell.edges.len() <= options.max_edges {
                    out.push((dims, cell.edges.len()));
                }
            }
        }
    }
    out.sort_by_key(|(d, m)| (*m, d.a(), d.b()));
    out
}

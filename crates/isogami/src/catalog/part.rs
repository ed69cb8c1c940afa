//! A work unit split into parts (issue 13: one big unit over several cluster tasks): each part
//! enumerates its share of the unit's masks ([`enumerate_topology_part`]), deduplicates and
//! deploys what it found, and samples the shapes of what it kept; [`combine_parts`] then joins
//! the parts into exactly the unit's outcome.
//!
//! Why the join is exact. The parts' symmetry orbits are disjoint, so every count of the
//! enumeration adds up, and a motion class of the whole unit is the union of the parts' classes
//! with the same motion. The unit keeps, of each class, the first design in key order with the
//! most pin joints ([`dedup_orbits`](crate::explore::dedup::dedup_orbits)); that design is also
//! what its own part kept, so joining takes the part winners in key order of their classes'
//! first designs, looks each up by that first design's invariant (as the undivided merge does)
//! and keeps the one with the most pins (ties: the smaller key). Every part deploys its own
//! winners and samples their shapes, so the unit's entries are the joined winners' entries,
//! computed once; a part winner that another part's design beats costs its deployment for
//! nothing (counted in the stage seconds). [`run_unit`](super::run_unit) is the join of one
//! whole part, so both paths are one. Plain data; serialisable so a part can wait in a
//! database until its siblings arrive.

use super::settings::CatalogSettings;
use super::unit::{characterise_all, sample_shapes, tally, topology_tallies, Candidate, Closing};
use super::{CatalogEntry, StageTally, UnitOutcome};
use crate::cell::CellDims;
use crate::error::Result;
use crate::explore::dedup::MOTION_TOL;
use crate::explore::{
    enumerate_topology_part, ExploreError, MotionIndex, MotionInvariant, UnitPart,
};
use crate::tiling::Family;
use serde::{Deserialize, Serialize};

/// One motion class a part kept.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PartClass {
    /// Key of the design kept (its spec order within the unit).
    pub key: u64,
    /// Key of the class's first design in key order.
    pub first_key: u64,
    /// The first design's motion invariant: what the join looks the class up by.
    pub lookup: MotionInvariant,
    /// Pin joints of the design kept.
    pub pins: usize,
    /// Symmetry orbits in the class.
    pub members: u64,
    /// The kept design's catalogue entries: its default shape, then its admitted shape
    /// samples; empty when its deployment did not pass the threshold.
    pub entries: Vec<CatalogEntry>,
}

/// What one part of a unit produced.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PartOutcome {
    /// Family.
    pub family: Family,
    /// Supercell.
    pub dims: CellDims,
    /// Which part.
    pub part: UnitPart,
    /// The enumeration's tallies for this part (the reduced checks and the configurations
    /// expanded count every mask of the unit).
    pub stages: Vec<StageTally>,
    /// Its motion classes, in key order of the kept designs.
    pub classes: Vec<PartClass>,
    /// Seconds of deployment for the threshold, summed over threads.
    pub threshold_seconds: f64,
    /// Seconds of shape sampling, summed over threads.
    pub shapes_seconds: f64,
    /// Shapes tried per kept topology, its default shape included.
    pub shapes_per_topology: u64,
}

/// Runs part `part` of the unit `family` × `dims`; see the module docs. Deterministic, like
/// [`run_unit`](super::run_unit).
pub fn run_unit_part(
    family: Family,
    dims: CellDims,
    part: UnitPart,
    settings: &CatalogSettings,
) -> Result<PartOutcome> {
    settings.validate()?;
    let topo = enumerate_topology_part(family, dims, &settings.topology, part)?;
    let stages = topology_tallies(&topo);
    let work: Vec<Candidate> = topo
        .designs
        .iter()
        .zip(&topo.details)
        .map(|(d, details)| Candidate {
            design: d.clone(),
            topology: d.to_string(),
            closing: Closing::Known(details.closing),
        })
        .collect();
    let (deployed, threshold_seconds) = characterise_all(&work, settings)?;
    let sampled = sample_shapes(family, dims, &deployed, settings)?;
    let mut classes = Vec::with_capacity(topo.details.len());
    for ((details, kept), samples) in topo.details.into_iter().zip(deployed).zip(sampled.entries) {
        let entries = kept
            .map(|k| std::iter::once(k).chain(samples).collect())
            .unwrap_or_default();
        classes.push(PartClass {
            key: details.key,
            first_key: details.first_key,
            lookup: details.first_invariant.unwrap_or(details.invariant),
            pins: details.joints,
            members: details.same_motion_merged as u64 + 1,
            entries,
        });
    }
    Ok(PartOutcome {
        family,
        dims,
        part,
        stages,
        classes,
        threshold_seconds,
        shapes_seconds: sampled.seconds,
        shapes_per_topology: sampled.per_topology,
    })
}

fn mismatch(detail: String) -> ExploreError {
    ExploreError::PartsMismatch { detail }
}

/// Checks that `parts` are every part of one unit, once each, from one enumeration.
fn check_parts(parts: &[PartOutcome]) -> std::result::Result<(), ExploreError> {
    let Some(first) = parts.first() else {
        return Err(mismatch("no parts given".into()));
    };
    let count = first.part.count();
    let mut seen = vec![false; count];
    for p in parts {
        if (p.family, p.dims) != (first.family, first.dims) {
            return Err(mismatch(format!(
                "parts of {}/{} and {}/{}",
                first.family, first.dims, p.family, p.dims
            )));
        }
        if p.part.count() != count {
            return Err(mismatch(format!(
                "{}/{} split into {count} and into {} parts",
                p.family,
                p.dims,
                p.part.count()
            )));
        }
        if std::mem::replace(&mut seen[p.part.index()], true) {
            return Err(mismatch(format!(
                "{}/{} part {} given twice",
                p.family, p.dims, p.part
            )));
        }
        let whole = |s: &[StageTally]| -> Vec<(u64, u64)> {
            s.iter()
                .take(4)
                .map(|t| (t.count_in, t.count_out))
                .collect()
        };
        if whole(&p.stages) != whole(&first.stages)
            || p.stages.get(4).map(|t| t.count_in) != first.stages.get(4).map(|t| t.count_in)
            || p.shapes_per_topology != first.shapes_per_topology
        {
            return Err(mismatch(format!(
                "{}/{} part {} disagrees with part {} on the unit's masks (other settings?)",
                p.family, p.dims, p.part, first.part
            )));
        }
    }
    if let Some(k) = seen.iter().position(|s| !s) {
        return Err(mismatch(format!(
            "{}/{} part {k}/{count} is missing",
            first.family, first.dims
        )));
    }
    Ok(())
}

/// Joins every part of one unit into the unit's outcome, equal to running it undivided (see
/// the module docs); an error when the parts are not all the parts of one unit.
pub fn combine_parts(parts: Vec<PartOutcome>) -> std::result::Result<UnitOutcome, ExploreError> {
    check_parts(&parts)?;
    let (family, dims) = (parts[0].family, parts[0].dims);
    let per_topology = parts[0].shapes_per_topology;
    // The enumeration's stages: the whole-mask counts from any part, the rest summed.
    let mut stages: Vec<StageTally> = parts[0].stages.clone();
    for p in &parts[1..] {
        for (s, t) in stages.iter_mut().zip(&p.stages).skip(4) {
            s.count_out += t.count_out;
            s.seconds += t.seconds;
        }
        for (s, t) in stages.iter_mut().zip(&p.stages).skip(5) {
            s.count_in += t.count_in;
        }
    }
    let threshold_seconds = parts.iter().fold(0.0, |a, p| a + p.threshold_seconds);
    let shapes_seconds = parts.iter().fold(0.0, |a, p| a + p.shapes_seconds);
    let mut classes: Vec<PartClass> = parts.into_iter().flat_map(|p| p.classes).collect();
    classes.sort_by_key(|c| c.first_key);
    let mut index = MotionIndex::new();
    let mut joined: Vec<PartClass> = Vec::with_capacity(classes.len());
    for c in classes {
        match index.find(&c.lookup, MOTION_TOL) {
            Some(k) => {
                let g = &mut joined[k];
                g.members += c.members;
                if c.pins > g.pins || (c.pins == g.pins && c.key < g.key) {
                    g.key = c.key;
                    g.pins = c.pins;
                    g.entries = c.entries;
                }
            }
            None => {
                index.insert(c.lookup.clone());
                joined.push(c);
            }
        }
    }
    joined.sort_by_key(|c| c.key);
    if let Some(unique) = stages.get_mut(6) {
        unique.count_out = joined.len() as u64;
    }
    let admitted = joined.iter().filter(|c| !c.entries.is_empty()).count() as u64;
    let entries: Vec<CatalogEntry> = joined.into_iter().flat_map(|c| c.entries).collect();
    stages.push(tally(
        "deploy_threshold",
        stages.get(6).map_or(0, |s| s.count_out),
        admitted,
        threshold_seconds,
    ));
    stages.push(tally(
        "shapes",
        admitted * per_topology,
        entries.len() as u64,
        shapes_seconds,
    ));
    Ok(UnitOutcome {
        family,
        dims,
        stages,
        entries,
    })
}

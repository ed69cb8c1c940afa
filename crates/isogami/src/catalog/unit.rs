//! One work unit: a family on one supercell, from joint masks to catalogue entries.

use super::assess::{assess, Assessment};
use super::settings::CatalogSettings;
use crate::api;
use crate::cell::{CellDims, UnitCell};
use crate::deploy::DeploymentReport;
use crate::error::Result;
use crate::explore::{enumerate_topologies, TopologyReport};
use crate::linkage::LinkageAnalysis;
use crate::tiling::{shape_grid, Family, Tiling};
use crate::topology::Design;
use serde::Serialize;
use std::time::Instant;

/// Count in, count out and time of one stage.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StageTally {
    /// Stage name.
    pub stage: String,
    /// Candidates entering.
    pub count_in: u64,
    /// Candidates leaving.
    pub count_out: u64,
    /// Seconds spent.
    pub seconds: f64,
}

/// One kept design.
#[derive(Debug, Clone)]
pub struct CatalogEntry {
    /// The design (sampled shape).
    pub design: Design,
    /// Spec of its topology at the default shape.
    pub topology: String,
    /// Its deployment.
    pub report: DeploymentReport,
    /// Its linkages.
    pub linkages: LinkageAnalysis,
}

/// Everything a work unit produced.
#[derive(Debug, Clone)]
pub struct UnitOutcome {
    /// Family.
    pub family: Family,
    /// Supercell.
    pub dims: CellDims,
    /// Stages in pipeline order.
    pub stages: Vec<StageTally>,
    /// Kept designs, in a deterministic order.
    pub entries: Vec<CatalogEntry>,
}

fn tally(stage: &str, count_in: u64, count_out: u64, seconds: f64) -> StageTally {
    StageTally {
        stage: stage.to_string(),
        count_in,
        count_out,
        seconds,
    }
}

/// The enumeration's stages as tallies.
fn topology_tallies(r: &TopologyReport) -> Vec<StageTally> {
    let t = &r.timings;
    let reduced = t.reduced.as_secs_f64();
    vec![
        tally("degree", r.masks_total, r.after_degree, reduced),
        tally("connected", r.after_degree, r.after_connected, 0.0),
        tally("directions", r.after_connected, r.after_directions, 0.0),
        tally("triangles", r.after_directions, r.after_triangles, 0.0),
        tally(
            "mobility",
            r.configurations_expanded,
            r.mobility_one,
            t.expand.as_secs_f64(),
        ),
        tally(
            "separating",
            r.mobility_one,
            r.separating,
            t.separate.as_secs_f64(),
        ),
        tally("unique", r.separating, r.unique, t.dedup.as_secs_f64()),
    ]
}

/// Deploys `design` and characterises it; `None` when it is not admitted (see
/// [`assess`]: one DOF, not locked, past the threshold). Uses the library's one deploy entry
/// point with the catalogue's settings, so `isogami deploy` with the same settings gives the
/// same report.
fn characterise(
    design: &Design,
    topology: &str,
    settings: &CatalogSettings,
) -> Result<Option<CatalogEntry>> {
    let report = match assess(design, settings, &mut |_| true)? {
        Assessment::Admitted(report) => *report,
        Assessment::Rejected(_) => return Ok(None),
    };
    let linkages = api::linkages(design)?;
    Ok(Some(CatalogEntry {
        design: design.clone(),
        topology: topology.to_string(),
        report,
        linkages,
    }))
}

/// Runs one work unit. Deterministic: the same inputs give the same outcome.
pub fn run_unit(family: Family, dims: CellDims, settings: &CatalogSettings) -> Result<UnitOutcome> {
    settings.validate()?;
    let topo = enumerate_topologies(family, dims, &settings.topology)?;
    let mut stages = topology_tallies(&topo);

    let start = Instant::now();
    let mut kept_topologies = Vec::new();
    for d in &topo.designs {
        if let Some(entry) = characterise(d, &d.to_string(), settings)? {
            kept_topologies.push(entry);
        }
    }
    stages.push(tally(
        "deploy_threshold",
        topo.designs.len() as u64,
        kept_topologies.len() as u64,
        start.elapsed().as_secs_f64(),
    ));

    let start = Instant::now();
    let grid = shape_grid(
        family,
        settings.shape_levels,
        settings.shape_span,
        settings.samples,
    );
    let mut sampled = 0u64;
    let mut entries = Vec::new();
    for kept in kept_topologies {
        // The default shape is the grid's first sample and is already deployed.
        sampled += 1;
        let topology = kept.topology.clone();
        let joints = kept.design.joints.clone();
        entries.push(kept);
        for params in grid.iter().skip(1) {
            sampled += 1;
            let design = Design {
                family,
                params: params.clone(),
                dims,
                joints: joints.clone(),
            };
            // Parameters that the grid found valid build; a shape whose cell cannot be built
            // with this joint list is simply not kept.
            let builds = Tiling::new(family, params).is_ok_and(|t| UnitCell::new(&t, dims).is_ok());
            if !builds {
                continue;
            }
            if let Some(entry) = characterise(&design, &topology, settings)? {
                entries.push(entry);
            }
        }
    }
    stages.push(tally(
        "shapes",
        sampled,
        entries.len() as u64,
        start.elapsed().as_secs_f64(),
    ));
    Ok(UnitOutcome {
        family,
        dims,
        stages,
        entries,
    })
}

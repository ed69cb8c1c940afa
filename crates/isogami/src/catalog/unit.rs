//! One work unit: a family on one supercell, from joint masks to catalogue entries.

use super::assess::{admit, Admission};
use super::finite::{figures_of_trajectory, FiniteFigures};
use super::margins::{margins_of_trajectory, Margins};
use super::part::{combine_parts, run_unit_part};
use super::screen::{applies, closing_rates, screens_out};
use super::settings::CatalogSettings;
use crate::api;
use crate::cell::{CellDims, UnitCell};
use crate::deploy::DeploymentReport;
use crate::error::Result;
use crate::explore::{TopologyReport, UnitPart};
use crate::linkage::LinkageAnalysis;
use crate::tiling::{shape_grid, Family, Tiling};
use crate::topology::Design;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// Count in, count out and time of one stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CatalogEntry {
    /// The design (sampled shape).
    #[serde(with = "design_wire")]
    pub design: Design,
    /// Spec of its topology at the default shape.
    pub topology: String,
    /// Its deployment.
    pub report: DeploymentReport,
    /// Its linkages.
    pub linkages: LinkageAnalysis,
    /// Its finite 6×6 patch: raw DOF and covered fraction of the completed sheet. None only
    /// in entries made before the catalogue had them (parts of split units waiting in a
    /// database, read back).
    #[serde(default)]
    pub finite: Option<FiniteFigures>,
    /// Its margins: shape tolerance and most open state. None only in entries made before the
    /// catalogue had them (parts of split units waiting in a database, read back).
    #[serde(default)]
    pub margins: Option<Margins>,
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

pub(super) fn tally(stage: &str, count_in: u64, count_out: u64, seconds: f64) -> StageTally {
    StageTally {
        stage: stage.to_string(),
        count_in,
        count_out,
        seconds,
    }
}

/// The enumeration's stages as tallies.
pub(super) fn topology_tallies(r: &TopologyReport) -> Vec<StageTally> {
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

/// Deploys `design` and characterises it (report, linkages, finite 6×6 patch); `None` when it is not admitted (see
/// [`assess`]: one DOF, not locked, past the threshold) or, with `settings.screen`, screened
/// out from its first-order motion without deploying it (a cut shuts too soon along both
/// signs). Uses the library's one deploy entry
/// point with the catalogue's settings, so `isogami deploy` with the same settings gives the
/// same report.
fn characterise(candidate: &Candidate, settings: &CatalogSettings) -> Result<Option<CatalogEntry>> {
    let Candidate {
        design,
        topology,
        closing,
    } = candidate;
    if settings.screen && applies(settings) {
        let rates = match closing {
            Closing::Known(rates) => *rates,
            Closing::Unknown => closing_rates(design, settings),
        };
        if screens_out(rates, settings) {
            return Ok(None);
        }
    }
    let run = match admit(design, settings, &mut |_| true)? {
        Admission::Admitted(run) => *run,
        Admission::Rejected(_) => return Ok(None),
    };
    // The finite patch from the same trajectory: no second deployment.
    let cell = design.cell()?;
    let finite = figures_of_trajectory(design, &cell, &run.mechanism, &run.trajectory, settings)?;
    let margins = margins_of_trajectory(
        design,
        &run.mechanism,
        &run.trajectory,
        &settings.deploy_request().settings,
    )?;
    let linkages = api::linkages(design)?;
    Ok(Some(CatalogEntry {
        design: design.clone(),
        topology: topology.to_string(),
        report: run.report,
        linkages,
        finite: Some(finite),
        margins: Some(margins),
    }))
}

/// A design's first-order closing rates for the screen, when known before it is characterised.
#[derive(Debug, Clone, Copy)]
pub(super) enum Closing {
    /// Computed by the screen.
    Unknown,
    /// From the exploration's deduplication (`DesignDetails::closing`).
    Known(Option<[f64; 2]>),
}

/// One design to characterise.
pub(super) struct Candidate {
    /// The design.
    pub design: Design,
    /// Spec of its topology at the default shape.
    pub topology: String,
    /// Its closing rates, when known.
    pub closing: Closing,
}

/// Characterises every design of `work` on the current rayon pool; results in the order of
/// `work` (the first error in that order wins), with the seconds of work summed over threads.
pub(super) fn characterise_all(
    work: &[Candidate],
    settings: &CatalogSettings,
) -> Result<(Vec<Option<CatalogEntry>>, f64)> {
    let done: Vec<(Result<Option<CatalogEntry>>, f64)> = work
        .par_iter()
        .map(|candidate| {
            let t = Instant::now();
            let r = characterise(candidate, settings);
            (r, t.elapsed().as_secs_f64())
        })
        .collect();
    // A fold from +0.0: an empty f64 sum is -0.0, which the store would not read back bit
    // for bit.
    let seconds = done.iter().fold(0.0, |acc, (_, s)| acc + s);
    let entries = done.into_iter().map(|(r, _)| r).collect::<Result<_>>()?;
    Ok((entries, seconds))
}

/// The admitted shape samples of each deployed topology.
pub(super) struct Sampled {
    /// Per topology (same order as given): its admitted samples, in grid order; empty for a
    /// topology that was not kept.
    pub entries: Vec<Vec<CatalogEntry>>,
    /// Seconds of work summed over threads.
    pub seconds: f64,
    /// Shapes tried per kept topology, its default shape included.
    pub per_topology: u64,
}

/// Samples the family's shape grid for every kept topology of `deployed` (`None`: not kept)
/// and deploys every sample; shapes whose cell cannot be built are tried, never kept.
pub(super) fn sample_shapes(
    family: Family,
    dims: CellDims,
    deployed: &[Option<CatalogEntry>],
    settings: &CatalogSettings,
) -> Result<Sampled> {
    let grid = shape_grid(
        family,
        settings.shape_levels,
        settings.shape_span,
        settings.samples,
    );
    let mut work = Vec::new();
    let mut slots: Vec<Vec<usize>> = Vec::with_capacity(deployed.len());
    for kept in deployed {
        let mut mine = Vec::new();
        if let Some(kept) = kept {
            // Every grid shape but the first (the default shape, deployed already).
            for params in grid.iter().skip(1) {
                let builds =
                    Tiling::new(family, params).is_ok_and(|t| UnitCell::new(&t, dims).is_ok());
                if !builds {
                    continue;
                }
                mine.push(work.len());
                work.push(Candidate {
                    design: Design::new(family, params, dims, kept.design.joints.clone()),
                    topology: kept.topology.clone(),
                    closing: Closing::Unknown,
                });
            }
        }
        slots.push(mine);
    }
    let (mut samples, seconds) = characterise_all(&work, settings)?;
    let entries = slots
        .into_iter()
        .map(|mine| mine.into_iter().filter_map(|k| samples[k].take()).collect())
        .collect();
    Ok(Sampled {
        entries,
        seconds,
        per_topology: 1 + grid.len().saturating_sub(1) as u64,
    })
}

/// Runs one work unit. Deterministic: the same inputs give the same outcome, whatever the
/// number of threads of the current rayon pool, on which the enumeration, the deployments and
/// the shape samples run in parallel. Stage seconds are seconds of work summed over threads.
/// The same as joining the parts of the unit split into any number of parts
/// ([`super::part`]); this is the join of one whole part.
pub fn run_unit(family: Family, dims: CellDims, settings: &CatalogSettings) -> Result<UnitOutcome> {
    let whole = run_unit_part(family, dims, UnitPart::WHOLE, settings)?;
    Ok(combine_parts(vec![whole])?)
}

/// A design as plain data for serialisation (parameters bit for bit, unlike the spec text);
/// read back only when its cell builds with its joints.
mod design_wire {
    use crate::cell::CellDims;
    use crate::tiling::Family;
    use crate::topology::{Design, JointChoice};
    use serde::{de::Error, Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize, Deserialize)]
    struct Wire {
        family: Family,
        params: Vec<f64>,
        dims: CellDims,
        joints: Vec<JointChoice>,
    }

    pub fn serialize<S: Serializer>(d: &Design, s: S) -> Result<S::Ok, S::Error> {
        Wire {
            family: d.family,
            params: d.params.clone(),
            dims: d.dims,
            joints: d.joints.clone(),
        }
        .serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Design, D::Error> {
        let w = Wire::deserialize(d)?;
        let design = Design {
            family: w.family,
            params: w.params,
            dims: w.dims,
            joints: w.joints,
        };
        design.cell().map_err(D::Error::custom)?;
        Ok(design)
    }
}

//! Records built from the library's results: a catalogue entry or any deployed design becomes
//! a [`DesignRecord`], a work unit's outcome becomes [`UnitRecords`].

use crate::error::{StoreError, StoreResult};
use crate::records::{
    DesignRecord, DesignSummary, Origin, StageCount, UnitRecords, WorkUnitRecord,
};
use crate::schema::PARAM_SLOTS;
use isogami::catalog::{CatalogEntry, FiniteFigures, Margins, UnitOutcome};
use isogami::deploy::DeploymentReport;
use isogami::linkage::LinkageAnalysis;
use isogami::topology::Design;

/// Frames count as open for the Poisson-like ratio when their largest principal expansion
/// reaches this fraction of the largest one of the whole deployment (the library's constant,
/// so that stored ranges and the inverse design's Poisson targets agree).
pub use isogami::deploy::POISSON_OPEN_FRACTION;

fn invalid(spec: &str, problem: impl Into<String>) -> StoreError {
    StoreError::InvalidRecord {
        spec: spec.to_string(),
        problem: problem.into(),
    }
}

/// The `kind` tag of the report's end reason, e.g. `contact_limit`.
fn end_reason_kind(spec: &str, report: &DeploymentReport) -> StoreResult<String> {
    let value = serde_json::to_value(&report.end_reason)
        .map_err(|e| invalid(spec, format!("end reason: {e}")))?;
    value
        .get("kind")
        .and_then(|k| k.as_str())
        .map(str::to_string)
        .ok_or_else(|| invalid(spec, "end reason has no kind"))
}

impl DesignRecord {
    /// Builds the record of `design` from its deployment `report` and, if computed, its
    /// `linkages`. `topology` is the spec of the topology the design was sampled from (its own
    /// spec for a user design).
    ///
    /// Refused (with the field named): shape parameters not in their canonical form (two
    /// spellings of one shape would be two rows; see `isogami::tiling::canonical_param`),
    /// more than six shape parameters, a non-finite summary
    /// value, or a report whose JSON would not read back as a `DeploymentReport` (a NaN or
    /// infinite number anywhere in it, which JSON writes as `null`).
    ///
    /// The Poisson-like ratio range is the report's: −ε_min/ε_max over the accepted states
    /// whose largest principal expansion reaches [`POISSON_OPEN_FRACTION`] of the largest one reached: −1 for
    /// isotropic opening, positive when one direction shrinks while the other grows.
    pub fn from_parts(
        design: &Design,
        topology: &str,
        origin: Origin,
        report: &DeploymentReport,
        linkages: Option<&LinkageAnalysis>,
    ) -> StoreResult<DesignRecord> {
        let spec = design.to_string();
        if !design.is_canonical() {
            return Err(invalid(
                &spec,
                "shape parameters are not canonical (12 significant digits); make the design \
                 with Design::new or parse its spec"
                    .to_string(),
            ));
        }
        if design.params.len() > PARAM_SLOTS {
            return Err(invalid(
                &spec,
                format!(
                    "{} shape parameters (at most {PARAM_SLOTS})",
                    design.params.len()
                ),
            ));
        }
        let info = design.family.info();
        let tile_count =
            info.aspect_count * usize::from(design.dims.a()) * usize::from(design.dims.b());
        let (poisson_min, poisson_max) = match report.poisson_range() {
            Some((lo, hi)) => (Some(lo), Some(hi)),
            None => (None, None),
        };
        let summary = DesignSummary {
            spec: spec.clone(),
            origin,
            family: design.family,
            cell: design.dims,
            tile_count: u32::try_from(tile_count)
                .map_err(|_| invalid(&spec, format!("{tile_count} tiles")))?,
            joints: design.joints.iter().map(|j| j.to_char()).collect(),
            topology: topology.to_string(),
            params: design.params.clone(),
            behaviour: report.behaviour,
            linkage_signature: linkages.map(|l| l.signature.clone()),
            end_reason: end_reason_kind(&spec, report)?,
            method: report.method,
            dof: u32::try_from(report.dof)
                .map_err(|_| invalid(&spec, format!("{} degrees of freedom", report.dof)))?,
            kerf: report.kerf,
            max_expansion: report.max_expansion,
            min_expansion: report.min_expansion,
            max_area_ratio: report.max_area_ratio,
            max_tile_rotation: report.max_tile_rotation,
            poisson_min,
            poisson_max,
            steps: report.steps as u64,
            finite_raw_dof: None,
            finite_covered: None,
            open_t: None,
            end_area_ratio: None,
            shape_tolerance: None,
            fabrication_kept: None,
        };
        check_finite(&summary)?;
        report
            .check_finite()
            .map_err(|e| invalid(&spec, format!("deployment report: {e}")))?;
        let report_json =
            serde_json::to_string(report).map_err(|e| invalid(&spec, format!("report: {e}")))?;
        if let Err(e) = serde_json::from_str::<DeploymentReport>(&report_json) {
            return Err(invalid(
                &spec,
                format!(
                    "the deployment report does not read back ({e}); a NaN or infinite number?"
                ),
            ));
        }
        let linkages_json = linkages
            .map(serde_json::to_string)
            .transpose()
            .map_err(|e| invalid(&spec, format!("linkages: {e}")))?;
        Ok(DesignRecord {
            summary,
            report: report_json,
            linkages: linkages_json,
        })
    }

    /// The record of a design the exploration kept, with its finite 6×6 patch's figures.
    pub fn from_entry(entry: &CatalogEntry) -> StoreResult<DesignRecord> {
        DesignRecord::from_parts(
            &entry.design,
            &entry.topology,
            Origin::Explored,
            &entry.report,
            Some(&entry.linkages),
        )?
        .with_finite(entry.finite.as_ref())?
        .with_margins(entry.margins.as_ref())
    }

    /// The record with its design's margins ([`isogami::catalog::Margins`], e.g. from
    /// `isogami::catalog::margins`), or without (None); refused when one is not a finite
    /// number in its range.
    pub fn with_margins(mut self, margins: Option<&Margins>) -> StoreResult<DesignRecord> {
        let s = &mut self.summary;
        s.open_t = margins.map(|m| m.open_t);
        s.end_area_ratio = margins.map(|m| m.end_area_ratio);
        s.shape_tolerance = margins.and_then(|m| m.shape_tolerance);
        s.fabrication_kept = margins.and_then(|m| m.fabrication_kept);
        let checks = [
            ("open_t", s.open_t, 0.0, 1.0),
            ("end_area_ratio", s.end_area_ratio, 0.0, f64::MAX),
            ("shape_tolerance", s.shape_tolerance, 0.0, 1.0),
            ("fabrication_kept", s.fabrication_kept, 0.0, f64::MAX),
        ];
        for (name, value, low, high) in checks {
            if let Some(x) = value {
                if !(x.is_finite() && (low..=high).contains(&x)) {
                    return Err(invalid(&s.spec, format!("{name} is {x}")));
                }
            }
        }
        Ok(self)
    }

    /// The record with the figures of its design's finite 6×6 patch
    /// ([`isogami::catalog::FiniteFigures`], e.g. from `isogami::catalog::finite_figures`), or
    /// without any (None); refused when the covered fraction is not a number in [0, 1].
    pub fn with_finite(mut self, figures: Option<&FiniteFigures>) -> StoreResult<DesignRecord> {
        let s = &mut self.summary;
        s.finite_raw_dof = figures
            .map(|f| u32::try_from(f.raw_dof))
            .transpose()
            .map_err(|_| invalid(&s.spec, "finite raw DOF out of range"))?;
        s.finite_covered = figures.and_then(|f| f.covered);
        if let Some(c) = s.finite_covered {
            if !(0.0..=1.0).contains(&c) {
                return Err(invalid(&s.spec, format!("finite_covered is {c}")));
            }
        }
        Ok(self)
    }
}

/// Refuses a summary with a NaN or infinite number, naming the field.
fn check_finite(s: &DesignSummary) -> StoreResult<()> {
    let named = [
        ("kerf", Some(s.kerf)),
        ("max_expansion", Some(s.max_expansion)),
        ("min_expansion", Some(s.min_expansion)),
        ("max_area_ratio", Some(s.max_area_ratio)),
        ("max_tile_rotation", Some(s.max_tile_rotation)),
        ("poisson_min", s.poisson_min),
        ("poisson_max", s.poisson_max),
    ];
    for (name, v) in named {
        if let Some(x) = v {
            if !x.is_finite() {
                return Err(invalid(&s.spec, format!("{name} is {x}")));
            }
        }
    }
    if let Some((k, x)) = s.params.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(invalid(&s.spec, format!("shape parameter v{k} is {x}")));
    }
    Ok(())
}

impl UnitRecords {
    /// The records of one finished work unit that took `seconds`.
    pub fn from_outcome(outcome: &UnitOutcome, seconds: f64) -> StoreResult<UnitRecords> {
        let unit = WorkUnitRecord {
            id: format!("{}/{}", outcome.family, outcome.dims),
            family: outcome.family.name(),
            cell: outcome.dims.to_string(),
            kind: "topology+shapes".into(),
            seconds: positive_zero(seconds),
            peak_rss_bytes: None,
        };
        let stages = outcome
            .stages
            .iter()
            .map(|s| StageCount {
                stage: s.stage.clone(),
                count_in: s.count_in,
                count_out: s.count_out,
                seconds: positive_zero(s.seconds),
            })
            .collect();
        let designs = outcome
            .entries
            .iter()
            .map(DesignRecord::from_entry)
            .collect::<StoreResult<_>>()?;
        Ok(UnitRecords {
            unit,
            stages,
            designs,
        })
    }
}

/// −0.0 as +0.0 (an empty `f64` sum is −0.0): SQLite stores both as the same zero, so the
/// row's checksum must be computed on the value read back.
fn positive_zero(x: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        x
    }
}

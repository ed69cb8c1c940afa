//! What an inverse-design run is asked to do, and what it reports back.

use super::error::InverseError;
use super::objective::Score;
use super::target::Target;
use super::verdict::Verdict;
use crate::catalog::CatalogSettings;
use crate::cell::CellDims;
use crate::contact::{ContactSettings, MAX_KERF};
use crate::deploy::DeploymentReport;
use crate::math::Real;
use crate::measure::BehaviourClass;
use crate::settings_error::Requirement;
use crate::tiling::Family;
use crate::topology::Design;
use serde::Serialize;

/// Most designs kept from screening and refined.
pub const MAX_TOP: usize = 50;
/// Most evaluations per refined design.
pub const MAX_BUDGET: usize = 10_000;
/// Most designs re-deployed after the pre-screening, and most fresh shape samples per
/// topology.
pub const MAX_CONFIRM: usize = 10_000;

/// An inverse-design run: the target and how hard to search.
#[derive(Debug, Clone, PartialEq)]
pub struct InverseRequest {
    /// Goals and constraints.
    pub target: Target,
    /// How many designs of different topologies to keep from screening and refine (k).
    pub top: usize,
    /// Evaluations (deployments) per refined design; 0 screens only.
    pub budget: usize,
    /// How many of the best pre-screened designs to re-deploy (M); 0 means 16 · `top`.
    pub confirm: usize,
    /// How many screened designs (at most two shapes per topology) get a short first
    /// refinement (a quarter of `budget`) before the best `top` topologies are refined
    /// further; 0 means 16 · `top`.
    pub triage: usize,
    /// Fresh shape samples around each of the `top` best screened topologies (0: none).
    pub samples: usize,
    /// Half-width of the fresh sample grid, relative to each parameter's scale
    /// max(|Kaplan default|, 0.25).
    pub sample_span: Real,
    /// Kerf every design is deployed with (units of the mean edge length L); raised to the
    /// target's minimum kerf when below it.
    pub kerf: Real,
    /// Also optimise the kerf (within [min kerf, 0.2]) during refinement.
    pub refine_kerf: bool,
    /// Admission rule and deployment settings (threshold, frames, tolerances); the contact
    /// settings' kerf is replaced by `kerf`.
    pub settings: CatalogSettings,
}

impl InverseRequest {
    /// A request for `target` with the defaults: top 3, budget 80, confirm 48, triage 48, no
    /// fresh samples (span 0.15 when asked), the catalogue's kerf and settings.
    pub fn new(target: Target) -> InverseRequest {
        let settings = CatalogSettings::default();
        InverseRequest {
            target,
            top: 3,
            budget: 80,
            confirm: 0,
            triage: 0,
            samples: 0,
            sample_span: 0.15,
            kerf: settings.deploy.contact.kerf,
            refine_kerf: false,
            settings,
        }
    }

    /// Checks the target and every count and setting.
    pub fn validate(&self) -> Result<(), InverseError> {
        self.target.validate()?;
        let count = |what: &'static str, v: usize, low: usize, high: usize| {
            if (low..=high).contains(&v) {
                Ok(())
            } else {
                Err(InverseError::OutOfRange {
                    what,
                    value: v as Real,
                    requirement: Requirement::CountIn {
                        low: low as u64,
                        high: high as u64,
                    },
                })
            }
        };
        count("top", self.top, 1, MAX_TOP)?;
        count("budget", self.budget, 0, MAX_BUDGET)?;
        count("confirm", self.confirm, 0, MAX_CONFIRM)?;
        count("triage", self.triage, 0, MAX_CONFIRM)?;
        count("samples", self.samples, 0, MAX_CONFIRM)?;
        if !(self.sample_span.is_finite() && self.sample_span > 0.0 && self.sample_span <= 1.0) {
            return Err(InverseError::OutOfRange {
                what: "sample span",
                value: self.sample_span,
                requirement: Requirement::Within {
                    low: 0.0,
                    high: 1.0,
                    open_low: true,
                    open_high: false,
                },
            });
        }
        // The kerf given is checked as `deploy` checks it (a kerf <= 0 was raised to the
        // smallest one silently), then raised to the target's minimum.
        let range = crate::contact::MIN_KERF..=MAX_KERF;
        if !(self.kerf.is_finite() && range.contains(&self.kerf)) {
            return Err(InverseError::OutOfRange {
                what: "kerf",
                value: self.kerf,
                requirement: Requirement::closed(crate::contact::MIN_KERF, MAX_KERF),
            });
        }
        let kerf = self.effective_kerf();
        if !range.contains(&kerf) {
            return Err(InverseError::OutOfRange {
                what: "the target's min_kerf",
                value: kerf,
                requirement: Requirement::closed(crate::contact::MIN_KERF, MAX_KERF),
            });
        }
        let mut settings = self.settings;
        settings.deploy.contact = ContactSettings {
            kerf,
            dhat: 0.5 * kerf,
            ..settings.deploy.contact
        };
        settings.validate().map_err(|e| InverseError::Settings {
            message: e.to_string(),
        })
    }

    /// The kerf designs are deployed with: `kerf`, raised to the target's minimum.
    pub fn effective_kerf(&self) -> Real {
        self.kerf.max(super::evaluate::min_kerf(&self.target))
    }

    /// M: how many pre-screened designs are re-deployed.
    pub fn confirm_count(&self) -> usize {
        if self.confirm == 0 {
            16 * self.top
        } else {
            self.confirm
        }
    }

    /// How many screened designs are triaged (never fewer than `top`).
    pub fn triage_count(&self) -> usize {
        if self.triage == 0 {
            16 * self.top
        } else {
            self.triage.max(self.top)
        }
    }
}

/// The stages of a run, in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stage {
    /// Re-deploying the best pre-screened designs.
    Confirm,
    /// Deploying fresh shape samples of the best topologies.
    Sample,
    /// A short refinement of every screened design.
    Triage,
    /// Refining the shapes of the best k topologies further.
    Refine,
    /// Re-deploying and checking every refined design.
    Verify,
}

impl Stage {
    /// Name for progress displays.
    pub fn as_str(self) -> &'static str {
        match self {
            Stage::Confirm => "confirm",
            Stage::Sample => "sample",
            Stage::Triage => "triage",
            Stage::Refine => "refine",
            Stage::Verify => "verify",
        }
    }
}

/// Fewest leaders a progress report lists (more when the request keeps more topologies).
pub const LEADERS: usize = 8;

/// What the progress callback is told after every evaluation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InverseProgress {
    /// Current stage.
    pub stage: Stage,
    /// Evaluations done in this stage.
    pub done: usize,
    /// Evaluations planned in this stage (an upper bound while refining).
    pub total: usize,
    /// Best objective seen so far in the whole run (None before the first valid design).
    pub best: Option<Real>,
    /// The best valid design so far of each of the leading topologies, best first: at most
    /// max([`LEADERS`], top) of them. A topology's entry only ever improves; at the end the
    /// first `top` leaders are the result's designs, in its order.
    pub leaders: Vec<Leader>,
}

/// One topology's best valid design so far (a row of the live leader board).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Leader {
    /// Spec of the topology at default shape (candidates' `topology`).
    pub topology: String,
    /// Spec of its best design so far.
    pub spec: String,
    /// Kerf that design was deployed with.
    pub kerf: Real,
    /// Its objective.
    pub objective: Real,
    /// The stage that found it.
    pub stage: Stage,
}

/// Where a screened design came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// One of the candidates (the database).
    Candidate,
    /// A fresh shape sample of a candidate's topology.
    Sample,
}

/// The measures a results table shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Measures {
    /// Largest area ratio reached.
    pub max_area_ratio: Real,
    /// Largest principal expansion reached.
    pub max_expansion: Real,
    /// Smallest principal expansion reached.
    pub min_expansion: Real,
    /// Largest tile rotation reached, degrees.
    pub max_tile_rotation_deg: Real,
    /// Smallest and largest Poisson-like ratio over the open frames.
    pub poisson: Option<[Real; 2]>,
    /// Behaviour class.
    pub behaviour: Option<BehaviourClass>,
    /// Why the deployment ended (`contact_limit`, ...).
    pub end_reason: String,
    /// The same in words (`contact limit`, `locked by contact`, ...), as `isogami deploy`
    /// prints it: what front ends show.
    pub end_label: String,
    /// Principal expansions (min, max) at the end of the deployment.
    pub end_expansions: [Real; 2],
    /// Direction of the largest expansion at the end, degrees.
    pub end_angle_deg: Real,
    /// U at the end, rows.
    pub end_u: [[Real; 2]; 2],
    /// Accepted deployment states.
    pub steps: usize,
}

impl Measures {
    /// The measures of a report (which has at least one frame).
    pub fn of(report: &DeploymentReport) -> Measures {
        let end = report.frames.last().map(|f| f.measures.clone());
        let end_reason = serde_json::to_value(&report.end_reason)
            .ok()
            .and_then(|v| v.get("kind").and_then(|k| k.as_str()).map(str::to_string))
            .unwrap_or_default();
        Measures {
            max_area_ratio: report.max_area_ratio,
            max_expansion: report.max_expansion,
            min_expansion: report.min_expansion,
            max_tile_rotation_deg: report.max_tile_rotation.to_degrees(),
            poisson: report.poisson_range().map(|(a, b)| [a, b]),
            behaviour: report.behaviour,
            end_reason,
            end_label: report.end_reason.to_string(),
            end_expansions: end
                .as_ref()
                .map_or([0.0; 2], |m| [m.min_expansion, m.max_expansion]),
            end_angle_deg: end.as_ref().map_or(0.0, |m| m.principal_angle.to_degrees()),
            end_u: end.map_or([[1.0, 0.0], [0.0, 1.0]], |m| m.u),
            steps: report.steps,
        }
    }
}

/// One valid design with its score: a row of the results table.
#[derive(Debug, Clone, Serialize)]
pub struct Scored {
    /// Spec string.
    pub spec: String,
    /// The design.
    #[serde(skip)]
    pub design: Design,
    /// Kerf it was deployed with.
    pub kerf: Real,
    /// Objective (smaller is better).
    pub objective: Real,
    /// Each goal's value.
    pub terms: Vec<Real>,
    /// Its measures.
    pub measures: Measures,
    /// Its deployment report (for saving and drawing).
    #[serde(skip)]
    pub report: DeploymentReport,
}

impl Scored {
    pub(crate) fn new(
        design: &Design,
        kerf: Real,
        score: &Score,
        report: &DeploymentReport,
    ) -> Scored {
        Scored {
            spec: design.to_string(),
            design: design.clone(),
            kerf,
            objective: score.objective,
            terms: score.terms.clone(),
            measures: Measures::of(report),
            report: report.clone(),
        }
    }
}

/// One of the k: the screened design and its refinement.
#[derive(Debug, Clone, Serialize)]
pub struct RefinedDesign {
    /// 1-based rank by the refined objective.
    pub rank: usize,
    /// Spec of the topology at default shape (candidates' `topology`).
    pub topology: String,
    /// Family.
    pub family: Family,
    /// Supercell.
    pub cell: CellDims,
    /// Where the screened design came from.
    pub source: Source,
    /// Best screened design of this topology.
    pub before: Scored,
    /// The refined design (equal to `before` when refinement found nothing better).
    pub after: Scored,
    /// Evaluations spent refining it (triage and refinement, every starting shape).
    pub evaluations: usize,
    /// Of those, how many points were invalid.
    pub invalid_evaluations: usize,
    /// True when the refined objective is below the screened one.
    pub improved: bool,
    /// Whether the refined design meets the target, goal by goal.
    pub verdict: Verdict,
}

/// Everything a run found.
#[derive(Debug, Clone, Serialize)]
pub struct InverseResult {
    /// The target in canonical text form.
    pub target: String,
    /// Whether the best design meets the target (every goal that names a value within its
    /// tolerance); `None` when no goal names a value. See each result's `verdict`.
    pub met: Option<bool>,
    /// Kerf the designs were deployed with (before kerf refinement).
    pub kerf: Real,
    /// Candidates given.
    pub candidates: usize,
    /// Candidates passing the family, cell and tile constraints.
    pub admitted: usize,
    /// Candidates scored from their stored reports.
    pub prescored: usize,
    /// Candidates re-deployed.
    pub confirmed: usize,
    /// Of those, valid.
    pub confirmed_valid: usize,
    /// Fresh shape samples deployed.
    pub sampled: usize,
    /// Designs given a first, short refinement.
    pub triaged: usize,
    /// Deployments in total (confirm, sample, refine, verify).
    pub evaluations: usize,
    /// Wall time, seconds.
    pub seconds: Real,
    /// The k designs, best refined objective first.
    pub results: Vec<RefinedDesign>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::{deploy, resolve_design, DeployRequest};
    use crate::deploy::EndReason;

    /// The end reason comes as its key and in the words `isogami deploy` prints (issue 24: the
    /// inverse page showed `contact_limit`).
    #[test]
    fn measures_carry_the_end_reason_in_words() {
        let design = resolve_design("rotating-squares").unwrap();
        let mut report = deploy(&design, &DeployRequest::default(), &mut |_| true)
            .unwrap()
            .report;
        let m = Measures::of(&report);
        assert_eq!(m.end_reason, "contact_limit");
        assert_eq!(m.end_label, EndReason::ContactLimit.to_string());
        assert!(!m.end_label.contains('_'));
        report.end_reason = EndReason::MaxSteps;
        let m = Measures::of(&report);
        assert_eq!(
            (m.end_reason.as_str(), m.end_label.as_str()),
            ("max_steps", "step limit reached")
        );
    }
}

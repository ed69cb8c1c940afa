//! Settings of the catalogue stages.

use crate::api::{DeployRequest, FrameSelection};
use crate::deploy::{DeploySettings, Method};
use crate::explore::TopologyOptions;
use crate::math::Real;
use crate::settings_error::{Requirement, SettingValue, SettingsError};
use serde::{Deserialize, Serialize};

/// Everything that decides what a work unit keeps. Stored with the database so any row can
/// be regenerated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatalogSettings {
    /// A design is kept when its largest principal expansion over the deployment reaches
    /// this (0.1: the sheet stretches by 10 % in some direction). The paper does not give its
    /// threshold.
    pub threshold: Real,
    /// Shape samples per kept topology, the default shape included.
    pub samples: usize,
    /// Grid values per shape parameter.
    pub shape_levels: usize,
    /// Grid half-width relative to each default (times max(|v|, 0.25)).
    pub shape_span: Real,
    /// Frames stored per deployment.
    pub frame_count: usize,
    /// Topology enumeration options.
    pub topology: TopologyOptions,
    /// Deployment settings (rigid modes). Its mobility tolerance is replaced by the
    /// topology's, so one tolerance decides the DOF everywhere (see
    /// [`CatalogSettings::deploy_request`]).
    pub deploy: DeploySettings,
    /// Screen out designs whose cuts shut, along both signs of their first-order motion, too
    /// soon to open past the threshold, before deploying them (see [`super::screen`]). Saves time, never changes what is kept (tested),
    /// so it is not part of the fingerprint. On by default.
    pub screen: bool,
}

impl Default for CatalogSettings {
    fn default() -> Self {
        CatalogSettings {
            threshold: 0.1,
            samples: 12,
            shape_levels: 3,
            shape_span: 0.3,
            frame_count: 40,
            topology: TopologyOptions::default(),
            deploy: DeploySettings::default(),
            screen: true,
        }
    }
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SettingsRecord {
    threshold: Real,
    samples: usize,
    shape_levels: usize,
    shape_span: Real,
    frame_count: usize,
    frame_joint_tolerance: Real,
    joint_tolerance: Real,
    step_tolerance: Real,
    growth: Real,
    max_steps: usize,
    max_attempts: usize,
    max_stretch: Real,
    max_edges: usize,
    max_dims: u8,
    mobility_rel_tol: Real,
    kerf: Real,
    dhat: Real,
    barrier_stiffness: Real,
    step_weight: Real,
    initial_step: Real,
    max_step: Real,
    max_halvings: u32,
}

impl CatalogSettings {
    /// The quick exploration's settings (`isogami explore --quick`): minimal cells only
    /// (`max_dims` 1) with at most 12 unique edges, and at most four shape samples per
    /// topology; every other setting as in `self`. Finishes in minutes on a laptop.
    pub fn quick(self) -> CatalogSettings {
        let mut s = self;
        s.topology.max_dims = 1;
        s.topology.max_edges = 12;
        s.samples = s.samples.min(4);
        s
    }

    /// Checks every field.
    pub fn validate(&self) -> Result<(), SettingsError> {
        self.deploy.validate()?;
        if self.deploy.method != Method::RigidModes {
            return Err(SettingsError::new(
                "method",
                SettingValue::Text(self.deploy.method.to_string()),
                Requirement::OneOf(&["rigid-modes"]),
            )
            .with_note("exploration deploys with rigid modes"));
        }
        if !(self.threshold.is_finite() && self.threshold >= 0.0) {
            return Err(SettingsError::new(
                "threshold",
                self.threshold,
                Requirement::AtLeast(0.0),
            ));
        }
        if self.samples == 0 || self.samples > 10_000 {
            return Err(SettingsError::new(
                "samples",
                self.samples,
                Requirement::CountIn {
                    low: 1,
                    high: 10_000,
                },
            ));
        }
        if self.shape_levels < 2 || self.shape_levels > 16 {
            return Err(SettingsError::new(
                "shape levels",
                self.shape_levels,
                Requirement::CountIn { low: 2, high: 16 },
            ));
        }
        if !(self.shape_span.is_finite() && self.shape_span > 0.0 && self.shape_span <= 2.0) {
            return Err(SettingsError::new(
                "shape span",
                self.shape_span,
                Requirement::Within {
                    low: 0.0,
                    high: 2.0,
                    open_low: true,
                    open_high: false,
                },
            ));
        }
        self.topology.validate()?;
        self.deploy_request().validate()
    }

    /// What every work unit deploys with: the deploy settings with the topology's mobility
    /// tolerance (the one the fingerprint records), `frame_count` frames.
    pub fn deploy_request(&self) -> DeployRequest {
        DeployRequest {
            settings: DeploySettings {
                mobility: self.topology.mobility,
                ..self.deploy
            },
            frames: FrameSelection::Evenly(self.frame_count),
        }
    }

    /// The settings a [`CatalogSettings::fingerprint`] records (the others at their
    /// defaults), validated: how a database's run is rebuilt, e.g. to migrate it. None when the
    /// text is not a fingerprint of this version or names invalid settings.
    pub fn from_fingerprint(text: &str) -> Option<CatalogSettings> {
        let r: SettingsRecord = serde_json::from_str(text).ok()?;
        let mut s = CatalogSettings {
            threshold: r.threshold,
            samples: r.samples,
            shape_levels: r.shape_levels,
            shape_span: r.shape_span,
            frame_count: r.frame_count,
            ..CatalogSettings::default()
        };
        s.topology.max_edges = r.max_edges;
        s.topology.max_dims = r.max_dims;
        s.topology.mobility.rel_tol = r.mobility_rel_tol;
        let d = &mut s.deploy;
        d.frame_joint_tolerance = r.frame_joint_tolerance;
        d.joint_tolerance = r.joint_tolerance;
        d.step_tolerance = r.step_tolerance;
        d.growth = r.growth;
        d.max_steps = r.max_steps;
        d.max_attempts = r.max_attempts;
        d.max_stretch = r.max_stretch;
        d.contact.kerf = r.kerf;
        d.contact.dhat = r.dhat;
        d.contact.stiffness = r.barrier_stiffness;
        d.step_weight = r.step_weight;
        d.initial_step = r.initial_step;
        d.max_step = r.max_step;
        d.max_halvings = r.max_halvings;
        (s.validate().is_ok() && s.fingerprint() == text).then_some(s)
    }

    /// A canonical JSON text of every setting that changes results (stored with the
    /// database; a resumed run must match it).
    pub fn fingerprint(&self) -> String {
        let d = &self.deploy;
        serde_json::to_string(&SettingsRecord {
            threshold: self.threshold,
            samples: self.samples,
            shape_levels: self.shape_levels,
            shape_span: self.shape_span,
            frame_count: self.frame_count,
            frame_joint_tolerance: d.frame_joint_tolerance,
            joint_tolerance: d.joint_tolerance,
            step_tolerance: d.step_tolerance,
            growth: d.growth,
            max_steps: d.max_steps,
            max_attempts: d.max_attempts,
            max_stretch: d.max_stretch,
            max_edges: self.topology.max_edges,
            max_dims: self.topology.max_dims,
            mobility_rel_tol: self.topology.mobility.rel_tol,
            kerf: d.contact.kerf,
            dhat: d.contact.dhat,
            barrier_stiffness: d.contact.stiffness,
            step_weight: d.step_weight,
            initial_step: d.initial_step,
            max_step: d.max_step,
            max_halvings: d.max_halvings,
        })
        .expect("plain numbers serialise")
    }
}

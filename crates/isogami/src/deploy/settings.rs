//! Deployment settings.

use crate::contact::ContactSettings;
use crate::math::Real;
use crate::mobility::MobilitySettings;
use crate::settings_error::{Requirement, SettingValue, SettingsError};

/// Which deployment algorithm to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Method {
    /// Nonlinear rigid modes: eigenvector recomputed every step (the paper's method).
    RigidModes,
    /// Nonlinear compliant modes: projection on the initial eigenvector only.
    Ncm,
    /// Springs pulling the cell open, a relaxation per load step.
    Springs,
}

impl std::str::FromStr for Method {
    type Err = SettingsError;
    fn from_str(s: &str) -> Result<Method, SettingsError> {
        match s {
            "rigid-modes" => Ok(Method::RigidModes),
            "ncm" => Ok(Method::Ncm),
            "springs" => Ok(Method::Springs),
            _ => Err(SettingsError::new(
                "method",
                SettingValue::Text(crate::topology::quote_input(s)),
                Requirement::OneOf(&["rigid-modes", "ncm", "springs"]),
            )),
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Method::RigidModes => "rigid-modes",
            Method::Ncm => "ncm",
            Method::Springs => "springs",
        })
    }
}

/// Settings of a deployment. Lengths are in units of the mean edge length L.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeploySettings {
    /// Algorithm.
    pub method: Method,
    /// Contact model (kerf, barrier).
    pub contact: ContactSettings,
    /// Weight w of the progress term E_step (paper: 1e-4).
    pub step_weight: Real,
    /// First target step length β.
    pub initial_step: Real,
    /// Largest β.
    pub max_step: Real,
    /// Halvings of the initial β that give the smallest step; a step that fails at that size
    /// ends the deployment (paper: 10).
    pub max_halvings: u32,
    /// β grows by this factor after a success.
    pub growth: Real,
    /// Largest number of accepted steps.
    pub max_steps: usize,
    /// A step is accepted when its projection on the motion vector is within this fraction
    /// of β (the paper's ε threshold on E_step, made relative).
    pub step_tolerance: Real,
    /// Largest joint residual of an accepted state (units of L).
    pub joint_tolerance: Real,
    /// Largest joint residual of a reported frame, re-checked independently of the solver
    /// (units of L).
    pub frame_joint_tolerance: Real,
    /// Largest number of attempted steps (accepted or not, both opening signs together):
    /// with `max_steps`, it bounds the run time of every deployment.
    pub max_attempts: usize,
    /// A state whose tiling vectors grew beyond this multiple of the closed cell's size
    /// (|u₀| + |w₀|) ends the run as diverged: the sheet has come apart (a design whose
    /// pieces are not held together moves them apart without limit) or the method ran away.
    pub max_stretch: Real,
    /// Mobility tolerance used to count the degrees of freedom and pick the opening motion.
    pub mobility: MobilitySettings,
    /// For a design with several degrees of freedom, which first-order motion to open along:
    /// `None` (the default) the fastest-opening combination of all of them
    /// ([`crate::mobility::Mobility::motion`]), `Some(k)` the k-th basis motion of
    /// [`crate::mobility::Mobility::modes`] (0-based, must be below the DOF).
    pub mode: Option<usize>,
}

impl Default for DeploySettings {
    fn default() -> Self {
        DeploySettings {
            method: Method::RigidModes,
            contact: ContactSettings::default(),
            step_weight: 1e-4,
            initial_step: 0.02,
            max_step: 0.1,
            max_halvings: 10,
            growth: 1.5,
            max_steps: 5000,
            step_tolerance: 1e-3,
            joint_tolerance: 1e-9,
            frame_joint_tolerance: 1e-8,
            max_attempts: 20_000,
            max_stretch: 100.0,
            mobility: MobilitySettings::default(),
            mode: None,
        }
    }
}

impl DeploySettings {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), SettingsError> {
        self.contact.validate()?;
        let positive = |name: &'static str, v: Real| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(SettingsError::new(name, v, Requirement::Positive))
            }
        };
        positive("step_weight", self.step_weight)?;
        positive("initial_step", self.initial_step)?;
        positive("max_step", self.max_step)?;
        positive("step_tolerance", self.step_tolerance)?;
        positive("joint_tolerance", self.joint_tolerance)?;
        positive("frame_joint_tolerance", self.frame_joint_tolerance)?;
        self.mobility.validate()?;
        if !(self.max_stretch.is_finite() && self.max_stretch > 1.0) {
            return Err(SettingsError::new(
                "max_stretch",
                self.max_stretch,
                Requirement::Above(1.0),
            ));
        }
        if self.frame_joint_tolerance < self.joint_tolerance {
            return Err(SettingsError::new(
                "frame_joint_tolerance",
                self.frame_joint_tolerance,
                Requirement::AtLeast(self.joint_tolerance),
            )
            .with_note("at least joint_tolerance"));
        }
        if !(self.growth.is_finite() && self.growth >= 1.0) {
            return Err(SettingsError::new(
                "growth",
                self.growth,
                Requirement::AtLeast(1.0),
            ));
        }
        for (name, n) in [
            ("max_steps", self.max_steps),
            ("max_attempts", self.max_attempts),
        ] {
            if n == 0 {
                return Err(SettingsError::new(name, n, Requirement::AtLeast(1.0)));
            }
        }
        if self.max_halvings > 50 {
            return Err(SettingsError::new(
                "max_halvings",
                self.max_halvings,
                Requirement::AtMost(50.0),
            ));
        }
        Ok(())
    }
}

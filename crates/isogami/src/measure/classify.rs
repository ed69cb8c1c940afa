//! The behaviour class of a whole deployment trajectory.
//!
//! Rule (decided on all frames together, with per-frame tolerance
//! tol = rel · max(|ε_min|, |ε_max|) + abs, defaults rel = 1e-3, abs = 1e-6). Only *open*
//! frames count: those stretched in some direction (ε_max > abs). Frames contracted in every
//! direction, such as a sheet closing again past its second closed state by up to a kerf,
//! say nothing about how it opens.
//!
//! 1. No open frame (or no frame): no class (`None`).
//! 2. Orthotropic with positive Poisson ratio when some open frame has ε_min < −tol (one
//!    direction shrinks while the other grows).
//! 3. Otherwise auxetic (both principal stretches ≥ 0 wherever the sheet is open):
//!    - isotropic auxetic when ε_max − ε_min ≤ tol at every open frame (U stays a multiple
//!      of I: threefold-symmetric designs, rotating squares);
//!    - anisotropic auxetic otherwise.
//!
//! abs = 1e-6 sits well above the noise of a converged frame (joint residuals ≤ 1e-8 of the
//! edge length perturb F by about that much) and far below any expansion worth reporting.

use super::frame::FrameMeasures;
use serde::{Deserialize, Serialize};
use std::fmt;

use crate::math::Real;

/// How a sheet expands along its deployment (paper §5, "Expansion ratios").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BehaviourClass {
    /// Equal expansion in every direction (Poisson ratio −1) throughout.
    IsotropicAuxetic,
    /// Expands in every direction, by different amounts.
    AnisotropicAuxetic,
    /// Shrinks in one direction while it grows in the other (positive Poisson ratio).
    OrthotropicPositivePoisson,
}

impl BehaviourClass {
    /// The snake_case name used in JSON and on the command line.
    pub fn as_str(self) -> &'static str {
        match self {
            BehaviourClass::IsotropicAuxetic => "isotropic_auxetic",
            BehaviourClass::AnisotropicAuxetic => "anisotropic_auxetic",
            BehaviourClass::OrthotropicPositivePoisson => "orthotropic_positive_poisson",
        }
    }
}

impl fmt::Display for BehaviourClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Tolerances of [`classify_with`]; see the module documentation for the rule.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ClassifyTolerances {
    /// Relative part of the per-frame tolerance (times max(|ε_min|, |ε_max|)).
    pub relative: Real,
    /// Absolute part of the per-frame tolerance.
    pub absolute: Real,
}

impl Default for ClassifyTolerances {
    fn default() -> Self {
        ClassifyTolerances {
            relative: 1e-3,
            absolute: 1e-6,
        }
    }
}

/// Classifies a trajectory with the default tolerances (rel 1e-3, abs 1e-6).
pub fn classify(frames: &[FrameMeasures]) -> Option<BehaviourClass> {
    classify_with(frames, ClassifyTolerances::default())
}

/// Classifies a trajectory; `None` when it never opens or holds a non-finite expansion.
pub fn classify_with(frames: &[FrameMeasures], tol: ClassifyTolerances) -> Option<BehaviourClass> {
    let pairs: Vec<(Real, Real)> = frames
        .iter()
        .map(|f| (f.min_expansion, f.max_expansion))
        .collect();
    if pairs.iter().any(|(a, b)| !a.is_finite() || !b.is_finite()) {
        return None;
    }
    let tol_at = |(lo, hi): (Real, Real)| tol.relative * lo.abs().max(hi.abs()) + tol.absolute;
    // Only frames where the sheet is stretched in some direction say how it opens; frames
    // that are contracted in every direction (a sheet closing again past its second closed
    // state, by up to a kerf) are left out.
    let open: Vec<(Real, Real)> = pairs
        .iter()
        .copied()
        .filter(|&(_, hi)| hi > tol.absolute)
        .collect();
    if open.is_empty() {
        return None;
    }
    if open.iter().any(|&p| p.0 < -tol_at(p)) {
        Some(BehaviourClass::OrthotropicPositivePoisson)
    } else if open.iter().all(|&p| p.1 - p.0 <= tol_at(p)) {
        Some(BehaviourClass::IsotropicAuxetic)
    } else {
        Some(BehaviourClass::AnisotropicAuxetic)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{rotation, vec2, Mat2};

    /// Frames of F(t) = R(0.3 t) diag(1 + a t, 1 + b t) applied to a square lattice.
    fn trajectory(a: Real, b: Real) -> Vec<FrameMeasures> {
        let (u0, w0) = (vec2(1.0, 0.0), vec2(0.0, 1.0));
        (0..=20)
            .map(|k| {
                let t = k as Real / 20.0;
                let f = rotation(0.3 * t) * Mat2::new(1.0 + a * t, 0.0, 0.0, 1.0 + b * t);
                FrameMeasures::new(t, (u0, w0), (f * u0, f * w0), &[], &[]).unwrap()
            })
            .collect()
    }

    #[test]
    fn classes_of_simple_trajectories() {
        use BehaviourClass::*;
        assert_eq!(classify(&trajectory(0.4, 0.4)), Some(IsotropicAuxetic));
        assert_eq!(
            classify(&trajectory(0.4, 0.4 * (1.0 + 1e-5))),
            Some(IsotropicAuxetic)
        );
        assert_eq!(classify(&trajectory(0.4, 0.3)), Some(AnisotropicAuxetic));
        assert_eq!(classify(&trajectory(0.4, 0.0)), Some(AnisotropicAuxetic));
        assert_eq!(
            classify(&trajectory(0.8, -0.2)),
            Some(OrthotropicPositivePoisson)
        );
        assert_eq!(classify(&trajectory(0.0, 0.0)), None);
        assert_eq!(classify(&trajectory(-0.1, -0.2)), None);
        assert_eq!(classify(&[]), None);
    }

    #[test]
    fn serde_names_are_snake_case() {
        let s = serde_json::to_string(&BehaviourClass::OrthotropicPositivePoisson).unwrap();
        assert_eq!(s, "\"orthotropic_positive_poisson\"");
        assert_eq!(
            BehaviourClass::IsotropicAuxetic.to_string(),
            "isotropic_auxetic"
        );
        let back: BehaviourClass = serde_json::from_str("\"anisotropic_auxetic\"").unwrap();
        assert_eq!(back, BehaviourClass::AnisotropicAuxetic);
    }
}

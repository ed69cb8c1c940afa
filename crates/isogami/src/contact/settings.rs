//! Contact settings: cut width (kerf), barrier activation distance and barrier stiffness.

use crate::math::Real;
use crate::settings_error::{Requirement, SettingsError};

/// Largest accepted kerf (units of the mean edge length L).
pub const MAX_KERF: Real = 0.2;

/// Smallest accepted kerf (units of L): 2 µm on 20 mm edges, fifty times finer than a laser
/// cut. Contact is resolved within the gap the kerf leaves, and conservative advancement
/// bounds each step by that gap, so the number of steps grows as the kerf shrinks (1e-4: about
/// 100 steps for rotating squares, like the default; 1e-5: about 900; 1e-7 no longer opens
/// within the step limit). Below this the run would end at the step limit half open.
pub const MIN_KERF: Real = 1e-4;

/// How the collision geometry and the barrier are set up. All lengths are non-dimensional
/// (units of the cell's mean edge length L), like the mechanism's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSettings {
    /// Physical cut width. Every tile's collision polygon is the tile inset by `kerf / 2`, so
    /// in the closed state collision polygons of neighbouring tiles are a kerf apart.
    /// Must lie in [[`MIN_KERF`], [`MAX_KERF`]] = [1e-4, 0.2].
    pub kerf: Real,
    /// Barrier activation distance d̂: a vertex–edge pair closer than this is repelled.
    /// Must satisfy 0 < dhat < kerf, so that the closed state is barrier-free.
    pub dhat: Real,
    /// Barrier stiffness κ in b(d) = −κ (d − d̂)² ln(d / d̂).
    ///
    /// The default κ = 1 is chosen from the curvature of the barrier: b″(d) depends on d / d̂
    /// only (b″(d̂/2) ≈ 6.4 κ, whatever the kerf), and the joint energy's Hessian JᵀJ has O(1)
    /// eigenvalues in these non-dimensional units, so κ = 1 keeps the Newton matrix of the
    /// deployment step well conditioned. The barrier force (≈ κ d̂ at d = d̂/2, 5·10⁻³ at the
    /// default d̂) is then orders of magnitude above the progress force of the step term
    /// (w·β with w = 10⁻⁴), so contact stops a step while the tiles are still close to d̂
    /// apart, far from touching. κ must be finite and positive.
    pub stiffness: Real,
}

impl Default for ContactSettings {
    /// Kerf 1 % of the mean edge length, d̂ = kerf / 2, κ = 1.
    fn default() -> Self {
        ContactSettings {
            kerf: 0.01,
            dhat: 0.005,
            stiffness: 1.0,
        }
    }
}

impl ContactSettings {
    /// Settings with this kerf and d̂ = kerf / 2 (other fields default). Not validated here:
    /// call [`ContactSettings::validate`] or pass to [`super::ContactModel::new`].
    pub fn with_kerf(kerf: Real) -> Self {
        ContactSettings {
            kerf,
            dhat: 0.5 * kerf,
            ..Self::default()
        }
    }

    /// The same settings with another barrier stiffness.
    pub fn with_stiffness(self, stiffness: Real) -> Self {
        ContactSettings { stiffness, ..self }
    }

    /// Checks kerf ∈ [1e-4, 0.2], 0 < d̂ < kerf and κ > 0 (all finite).
    pub fn validate(&self) -> Result<(), SettingsError> {
        if !(self.kerf.is_finite() && (MIN_KERF..=MAX_KERF).contains(&self.kerf)) {
            return Err(SettingsError::new(
                "kerf",
                self.kerf,
                Requirement::closed(MIN_KERF, MAX_KERF),
            )
            .with_note(
                "units of the mean edge length; no cut is narrower and steps shrink with the gap",
            ));
        }
        if !(self.dhat.is_finite() && self.dhat > 0.0 && self.dhat < self.kerf) {
            return Err(SettingsError::new(
                "barrier distance dhat",
                self.dhat,
                Requirement::Within {
                    low: 0.0,
                    high: self.kerf,
                    open_low: true,
                    open_high: true,
                },
            )
            .with_note("the upper end is the kerf"));
        }
        if !(self.stiffness.is_finite() && self.stiffness > 0.0) {
            return Err(SettingsError::new(
                "barrier stiffness",
                self.stiffness,
                Requirement::Positive,
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_bounds_are_enforced() {
        let d = ContactSettings::default();
        assert!(d.validate().is_ok());
        assert_eq!(d.dhat, 0.5 * d.kerf);
        assert!(ContactSettings::with_kerf(0.2).validate().is_ok());
        assert!(ContactSettings::with_kerf(MIN_KERF).validate().is_ok());
        for kerf in [0.0, -0.01, 0.21, 9e-5, 1e-7, Real::NAN, Real::INFINITY] {
            assert!(
                ContactSettings::with_kerf(kerf).validate().is_err(),
                "{kerf}"
            );
        }
        for dhat in [0.0, 0.01, 0.02, Real::NAN] {
            let s = ContactSettings { dhat, ..d };
            assert!(s.validate().is_err(), "{dhat}");
        }
        for k in [0.0, -1.0, Real::INFINITY] {
            assert!(d.with_stiffness(k).validate().is_err(), "{k}");
        }
        let e = ContactSettings::with_kerf(0.5).validate().unwrap_err();
        assert_eq!((e.name, e.value), ("kerf", 0.5.into()));
        assert_eq!(e.requirement, Requirement::closed(MIN_KERF, MAX_KERF));
    }
}

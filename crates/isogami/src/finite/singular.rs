//! Singular states along a path: where a mechanism's or a sheet's lowest non-zero
//! eigenvalues of H fall to zero between states where they are not.
//!
//! A one-DOF path has, at a generic state, one zero eigenvalue (its motion) and a spectrum
//! above it. At a singular (bifurcation) state some of those non-zero eigenvalues reach zero
//! together — the sheet has extra first-order motions there — and rise again past it (their
//! singular values vanish linearly in t). The deployment steps through such a state without
//! noticing (its count at the states around it is one DOF), but a physical sheet pulled
//! through it can take one of the other branches: it stops following the periodic motion and
//! parts of it drift off. So every accepted state of the path is counted, and a state whose
//! lowest non-zero eigenvalue (scaled by λ_max) lies more than [`DIP`] below the path's median
//! of it is reported, one per run of such states (its lowest), when the eigenvalue rises
//! again on both sides of the run: a run at the path's first or last state is where the path
//! begins (beside the closed tiling, singular as every closed tiling is) or ends, not a state
//! the sheet is pulled through.

use super::error::FiniteError;
use super::kernel::sheet_kernel;
use super::sheet::FiniteSheet;
use crate::deploy::Trajectory;
use crate::kinematics::Mechanism;
use crate::math::Real;
use crate::mobility::{analyze, MobilitySettings};
use crate::stop::KeepGoing;
use rayon::prelude::*;
use serde::Serialize;

/// A state is singular when its lowest non-zero eigenvalue (scaled by λ_max) is below this
/// fraction of the path's median of it: three decades in eigenvalue, 1.5 in singular value.
/// The completed 4×4 sheets of the issue that found these dip by about 5.5 decades.
pub const DIP: Real = 1e-3;

/// One singular state of a path.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct SingularState {
    /// Accepted step of the path.
    pub step: usize,
    /// Its t (normalised arc length).
    pub t: Real,
    /// Eigenvalues that fell with the lowest (those below the geometric mean of the lowest
    /// and the path's median): the extra first-order motions the state has.
    pub extra_motions: usize,
    /// The lowest non-zero eigenvalue there, scaled by λ_max.
    pub lowest: Real,
    /// The path's median of that eigenvalue, scaled by λ_max.
    pub typical: Real,
}

/// The singular states of a path given, per accepted step, its t and its non-zero scaled
/// eigenvalues (ascending; the lowest few suffice). Steps without a non-zero eigenvalue are
/// skipped.
pub fn singular_states(spectra: &[(usize, Real, Vec<Real>)]) -> Vec<SingularState> {
    let mut lowest: Vec<Real> = spectra
        .iter()
        .filter_map(|(_, _, v)| v.first().copied())
        .collect();
    if lowest.len() < 3 {
        return Vec::new();
    }
    lowest.sort_by(Real::total_cmp);
    let typical = lowest[lowest.len() / 2];
    // Runs of states below the dip, each as its lowest state and whether it began at the
    // path's first state.
    let mut runs: Vec<(SingularState, bool)> = Vec::new();
    let mut open = false;
    for (k, (step, t, values)) in spectra.iter().enumerate() {
        let low = match values.first() {
            Some(&low) if low < DIP * typical => low,
            _ => {
                open = false;
                continue;
            }
        };
        let bound = (low.max(0.0) * typical).sqrt();
        let state = SingularState {
            step: *step,
            t: *t,
            extra_motions: values.iter().filter(|&&v| v <= bound).count(),
            lowest: low,
            typical,
        };
        match runs.last_mut() {
            Some((last, _)) if open => {
                if low < last.lowest {
                    *last = state;
                }
            }
            _ => runs.push((state, k == 0)),
        }
        open = true;
    }
    // A run at either end of the path is where the path begins (beside the closed state,
    // singular as a tiling) or ends (its contact limit), not a state the sheet is pulled
    // through: only runs with a rise on both sides are singular states of the path.
    if open {
        runs.pop();
    }
    runs.into_iter()
        .filter(|(_, at_start)| !at_start)
        .map(|(state, _)| state)
        .collect()
}

/// The singular states of `sheet` along `traj` of `mech` (every accepted state but the
/// closed one, counted separately), the sheet's generic degrees of freedom `dof` left out
/// of each spectrum.
pub fn sheet_singular_states(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    traj: &Trajectory,
    dof: usize,
    keep_going: KeepGoing<'_>,
) -> Result<Vec<SingularState>, FiniteError> {
    let spectra = (1..traj.steps.len())
        .into_par_iter()
        .map(|k| {
            let poses = sheet.poses(mech, &traj.steps[k].q);
            let kernel = sheet_kernel(sheet, mech, &poses, keep_going)?;
            let scaled = kernel.values.iter().skip(dof).map(|v| v / kernel.scale);
            Ok((k, traj.t(k), scaled.collect()))
        })
        .collect::<Result<Vec<_>, FiniteError>>()?;
    Ok(singular_states(&spectra))
}

/// The singular states of the periodic path `traj` of `mech`, its generic degrees of
/// freedom (the most common count along it) left out of each spectrum.
pub fn periodic_singular_states(
    mech: &Mechanism,
    traj: &Trajectory,
    settings: MobilitySettings,
) -> Result<Vec<SingularState>, FiniteError> {
    let counts = (1..traj.steps.len())
        .into_par_iter()
        .map(|k| {
            let m = analyze(mech, &traj.steps[k].q, settings).map_err(|_| FiniteError::Eigen)?;
            let scale = m
                .eigenvalues
                .last()
                .copied()
                .unwrap_or(1.0)
                .max(Real::MIN_POSITIVE);
            Ok((
                k,
                m.dof,
                m.eigenvalues.iter().map(|v| v / scale).collect::<Vec<_>>(),
            ))
        })
        .collect::<Result<Vec<_>, FiniteError>>()?;
    let mut dofs: Vec<usize> = counts.iter().map(|c| c.1).collect();
    dofs.sort_unstable();
    let generic = dofs.get(dofs.len() / 2).copied().unwrap_or(1);
    let spectra: Vec<(usize, Real, Vec<Real>)> = counts
        .into_iter()
        .map(|(k, _, v)| (k, traj.t(k), v.into_iter().skip(generic).collect()))
        .collect();
    Ok(singular_states(&spectra))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Paths made by a rule: a smooth spectrum (lowest 1e-4..1e-2, drifting) over 40..200
    /// states, with singular states put at seeded steps where m eigenvalues vanish
    /// linearly in t; each is found once, with its multiplicity, and nothing else is.
    #[test]
    fn a_dip_to_zero_is_found_once_with_its_multiplicity() {
        let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
        let mut rand = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as Real / (1u64 << 53) as Real
        };
        for case in 0..300 {
            let steps = 40 + (rand() * 160.0) as usize;
            let base = (10.0 as Real).powf(-4.0 + 2.0 * rand());
            let where_ = if rand() < 0.3 {
                None
            } else {
                Some(5 + (rand() * (steps - 10) as Real) as usize)
            };
            let m = 1 + (rand() * 4.0) as usize;
            let spectra: Vec<(usize, Real, Vec<Real>)> = (1..steps)
                .map(|k| {
                    let t = k as Real / steps as Real;
                    let drift = 1.0 + 0.5 * (3.0 * t).sin();
                    let mut v: Vec<Real> =
                        (0..6).map(|i| base * drift * (1.0 + i as Real)).collect();
                    if let Some(s) = where_ {
                        // Singular values linear in the distance: 0 at s, eigenvalues quadratic.
                        let d = (k as Real - s as Real).abs() / steps as Real;
                        let sv = 1e-6 + d;
                        for x in v.iter_mut().take(m) {
                            *x = (*x).min(base * sv * sv);
                        }
                    }
                    v.sort_by(Real::total_cmp);
                    (k, t, v)
                })
                .collect();
            let found = singular_states(&spectra);
            match where_ {
                None => assert!(found.is_empty(), "case {case}: {found:?}"),
                Some(s) => {
                    assert_eq!(found.len(), 1, "case {case}: {found:?}");
                    assert_eq!(found[0].step, s, "case {case}");
                    assert_eq!(found[0].extra_motions, m, "case {case}");
                }
            }
        }
    }

    /// A spectrum falling to zero towards the path's ends — beside the closed tiling, and at
    /// a contact limit where the tiles close again (rotating squares' completed sheets were
    /// flagged at t = 0.002 and 0.998) — is no state the sheet passes through: nothing is
    /// reported there, while an interior dip of the same path still is.
    #[test]
    fn falls_at_the_ends_of_the_path_are_not_singular_states() {
        for interior in [None, Some(0.5)] {
            let steps = 120;
            let spectra: Vec<(usize, Real, Vec<Real>)> = (1..steps)
                .map(|k| {
                    let t = k as Real / steps as Real;
                    let mut edge = t.min(1.0 - t);
                    if let Some(c) = interior {
                        edge = edge.min((t - c).abs() + 1e-4);
                    }
                    let low = 1e-4 * (edge / 0.05).powi(4).min(1.0);
                    (k, t, vec![low, 2e-4, 3e-4])
                })
                .collect();
            let found = singular_states(&spectra);
            match interior {
                None => assert!(found.is_empty(), "{found:?}"),
                Some(c) => {
                    assert_eq!(found.len(), 1, "{found:?}");
                    assert!((found[0].t - c).abs() < 0.01, "{found:?}");
                }
            }
        }
    }
}

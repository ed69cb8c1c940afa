//! Singular states along a path: where a mechanism's or a sheet's lowest non-zero
//! eigenvalues of H fall to zero between states where they are not.
//!
//! A one-DOF path has, at a generic state, one zero eigenvalue (its motion) and a spectrum
//! above it. At a singular (bifurcation) state some of those non-zero eigenvalues reach zero
//! together — the sheet has extra first-order motions there — and rise again past it (their
//! singular values vanish linearly in t). The deployment steps through such a state without
//! noticing (its count at the states around it is one DOF), but a physical sheet pulled
//! through it can take one of the other branches: it stops following the periodic motion and
//! parts of it drift off.
//!
//! So every accepted state of the path is counted. The zero itself falls between two
//! accepted states, where the samples see only its flanks — possibly no more than a decade
//! or two down — so every interior local minimum of the lowest eigenvalue well below the
//! path's median ([`CANDIDATE`]) is refined between its two neighbouring states, on states
//! projected onto the joint constraints, and reported when the refined minimum lies more than
//! [`DIP`] below the median. A fall at the path's first or last state is where the path
//! begins (beside the closed tiling, singular as every closed tiling is) or ends, not a state
//! the sheet is pulled through.

use super::error::FiniteError;
use super::kernel::sheet_kernel;
use super::sheet::FiniteSheet;
use crate::deploy::{project_between, DeploySettings, Trajectory};
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};
use crate::mobility::analyze;
use crate::stop::KeepGoing;
use rayon::prelude::*;
use serde::Serialize;

/// A state is singular when its lowest non-zero eigenvalue (scaled by λ_max), refined, is
/// below this fraction of the path's median of it: three decades in eigenvalue, 1.5 in
/// singular value.
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

/// A sampled local minimum of the lowest eigenvalue this far below the path's median is
/// refined between its neighbouring states: a singular value that vanishes linearly between
/// two samples can leave the nearest sample only a decade or two below the path (IH4's
/// completed 4×4 sheet: 3e-10 at t = 0.4966 against a median of 6e-8, zero at t ≈ 0.4995).
pub const CANDIDATE: Real = 0.1;

/// Golden-section steps refining a candidate: the bracket of two steps shrinks to 0.618^16 ≈
/// 5e-4 of itself, so a singular value vanishing linearly falls about three decades below its
/// sampled neighbours (six in eigenvalue), while a minimum that does not reach zero stays at
/// its floor.
pub const REFINE_STEPS: usize = 16;

/// The singular states of a path given, per accepted step, its t and its non-zero scaled
/// eigenvalues (ascending; the lowest few suffice), from the samples alone. Steps without a
/// non-zero eigenvalue are skipped.
pub fn singular_states(spectra: &[(usize, Real, Vec<Real>)]) -> Vec<SingularState> {
    refined_singular_states(spectra, &|_, _| None)
}

/// [`singular_states`] with every candidate (an interior local minimum of the lowest
/// eigenvalue below [`CANDIDATE`] times the path's median) refined between its neighbouring
/// accepted states: `probe(k, f)` is the scaled spectrum of the state `f` ∈ (0, 1) of the way
/// from accepted step `k` to `k + 1` (None when it cannot be made). A candidate is a singular
/// state when its refined lowest eigenvalue is below [`DIP`] times the median. A candidate
/// needs the eigenvalue back at ordinary levels (at least [`CANDIDATE`] times the median) at
/// some state before it and some state after it: the spectrum falls towards the closed tiling
/// (singular as every closed tiling is) and towards a contact limit where the tiles close
/// again, and the sheet is not pulled through either.
pub fn refined_singular_states(
    spectra: &[(usize, Real, Vec<Real>)],
    probe: &(dyn Fn(usize, Real) -> Option<Vec<Real>> + Sync),
) -> Vec<SingularState> {
    let samples: Vec<(usize, Real, &Vec<Real>, Real)> = spectra
        .iter()
        .filter_map(|(k, t, v)| v.first().map(|&low| (*k, *t, v, low)))
        .collect();
    if samples.len() < 3 {
        return Vec::new();
    }
    let mut sorted: Vec<Real> = samples.iter().map(|s| s.3).collect();
    sorted.sort_by(Real::total_cmp);
    let typical = sorted[sorted.len() / 2];
    // A candidate has the spectrum back at ordinary levels somewhere on both sides: a fall
    // that lasts to the path's end (or from its start) is where the path ends (or begins).
    let ordinary = |s: &(usize, Real, &Vec<Real>, Real)| s.3 >= CANDIDATE * typical;
    let candidates: Vec<usize> = (1..samples.len() - 1)
        .filter(|&i| {
            let low = samples[i].3;
            low < samples[i - 1].3
                && low <= samples[i + 1].3
                && low < CANDIDATE * typical
                && samples[..i].iter().any(ordinary)
                && samples[i + 1..].iter().any(ordinary)
        })
        .collect();
    let found: Vec<SingularState> = candidates
        .par_iter()
        .filter_map(|&i| {
            let (before, here, after) = (&samples[i - 1], &samples[i], &samples[i + 1]);
            // Refined only between consecutive accepted steps (else the samples alone).
            let consecutive = before.0 + 1 == here.0 && here.0 + 1 == after.0;
            let at = |x: Real| -> Option<(Real, Vec<Real>)> {
                if x == 0.0 || !consecutive {
                    return Some((here.1, here.2.clone()));
                }
                let (k, f, t) = if x < 0.0 {
                    (before.0, 1.0 + x, here.1 + x * (here.1 - before.1))
                } else {
                    (here.0, x, here.1 + x * (after.1 - here.1))
                };
                let values = probe(k, f)?;
                values.first()?;
                Some((t, values))
            };
            let best = golden_minimum(&at)?;
            let (t, values) = best;
            let low = values[0];
            (low < DIP * typical).then(|| {
                let bound = (low.max(0.0) * typical).sqrt();
                SingularState {
                    step: here.0,
                    t,
                    extra_motions: values.iter().filter(|&&v| v <= bound).count(),
                    lowest: low,
                    typical,
                }
            })
        })
        .collect();
    // Two candidates on either side of one zero are one singular state: the lower one.
    let mut out: Vec<SingularState> = Vec::new();
    for s in found {
        match out.last_mut() {
            Some(last) if s.step <= last.step + 2 => {
                if s.lowest < last.lowest {
                    *last = s;
                }
            }
            _ => out.push(s),
        }
    }
    out
}

/// The lowest of `at` over x ∈ [−1, 1] found by golden-section search (the lowest eigenvalue
/// near a singular state is V-shaped in its square root, so unimodal in the bracket), the
/// sample at x = 0 included; points `at` cannot make count as +∞.
fn golden_minimum(at: &dyn Fn(Real) -> Option<(Real, Vec<Real>)>) -> Option<(Real, Vec<Real>)> {
    let mut best = at(0.0)?;
    let value = |x: Real, best: &mut (Real, Vec<Real>)| -> Real {
        match at(x) {
            Some(p) => {
                let low = p.1[0];
                if low < best.1[0] {
                    *best = p;
                }
                low
            }
            None => Real::INFINITY,
        }
    };
    let ratio = (5.0_f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (-1.0, 1.0);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (value(c, &mut best), value(d, &mut best));
    for _ in 0..REFINE_STEPS {
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = value(c, &mut best);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = value(d, &mut best);
        }
    }
    Some(best)
}

/// The singular states of `sheet` along `traj` of `mech` (every accepted state but the
/// closed one, counted separately), the sheet's generic degrees of freedom `dof` left out
/// of each spectrum; candidates are refined between accepted states projected onto the joint
/// constraints with `settings` ([`project_between`]).
pub fn sheet_singular_states(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    traj: &Trajectory,
    dof: usize,
    settings: &DeploySettings,
    keep_going: KeepGoing<'_>,
) -> Result<Vec<SingularState>, FiniteError> {
    let spectrum = |q: &DVec| -> Result<Vec<Real>, FiniteError> {
        let poses = sheet.poses(mech, q);
        let kernel = sheet_kernel(sheet, mech, &poses, keep_going)?;
        Ok(kernel
            .values
            .iter()
            .skip(dof)
            .map(|v| v / kernel.scale)
            .collect())
    };
    let spectra = (1..traj.steps.len())
        .into_par_iter()
        .map(|k| Ok((k, traj.t(k), spectrum(&traj.steps[k].q)?)))
        .collect::<Result<Vec<_>, FiniteError>>()?;
    let probe = |k: usize, f: Real| {
        let q = project_between(mech, traj, k, f, settings).ok()?;
        spectrum(&q).ok()
    };
    if !keep_going() {
        return Err(FiniteError::Cancelled);
    }
    Ok(refined_singular_states(&spectra, &probe))
}

/// The singular states of the periodic path `traj` of `mech`, its generic degrees of
/// freedom (the most common count along it) left out of each spectrum; candidates refined as
/// for a sheet.
pub fn periodic_singular_states(
    mech: &Mechanism,
    traj: &Trajectory,
    settings: &DeploySettings,
) -> Result<Vec<SingularState>, FiniteError> {
    let spectrum = |q: &DVec| -> Result<(usize, Vec<Real>), FiniteError> {
        let m = analyze(mech, q, settings.mobility).map_err(|_| FiniteError::Eigen)?;
        let scale = m
            .eigenvalues
            .last()
            .copied()
            .unwrap_or(1.0)
            .max(Real::MIN_POSITIVE);
        Ok((m.dof, m.eigenvalues.iter().map(|v| v / scale).collect()))
    };
    let counts = (1..traj.steps.len())
        .into_par_iter()
        .map(|k| Ok((k, spectrum(&traj.steps[k].q)?)))
        .collect::<Result<Vec<_>, FiniteError>>()?;
    let mut dofs: Vec<usize> = counts.iter().map(|c| c.1 .0).collect();
    dofs.sort_unstable();
    let generic = dofs.get(dofs.len() / 2).copied().unwrap_or(1);
    let spectra: Vec<(usize, Real, Vec<Real>)> = counts
        .into_iter()
        .map(|(k, (_, v))| (k, traj.t(k), v.into_iter().skip(generic).collect()))
        .collect();
    let probe = |k: usize, f: Real| {
        let q = project_between(mech, traj, k, f, settings).ok()?;
        Some(spectrum(&q).ok()?.1.into_iter().skip(generic).collect())
    };
    Ok(refined_singular_states(&spectra, &probe))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::xorshift;

    /// Paths made by a rule: a smooth spectrum (lowest 1e-4..1e-2, drifting) over 40..200
    /// states, with singular states put at seeded steps in the path's inner 80 % where m
    /// eigenvalues vanish linearly in t; each is found once, with its multiplicity, and
    /// nothing else is.
    #[test]
    fn a_dip_to_zero_is_found_once_with_its_multiplicity() {
        let mut rand = xorshift(0x2545_f491_4f6c_dd1d);
        for case in 0..300 {
            let steps = 40 + (rand() * 160.0) as usize;
            let base = (10.0 as Real).powf(-4.0 + 2.0 * rand());
            let where_ = if rand() < 0.3 {
                None
            } else {
                Some(((0.1 + 0.8 * rand()) * steps as Real) as usize)
            };
            let m = 1 + (rand() * 4.0) as usize;
            // How fast the singular values fall (per unit of t): the completed 4×4 sheets of
            // IH4 and IH44 fall at about 50.
            let slope = 5.0 + 45.0 * rand();
            let spectra: Vec<(usize, Real, Vec<Real>)> = (1..steps)
                .map(|k| {
                    let t = k as Real / steps as Real;
                    let drift = 1.0 + 0.5 * (3.0 * t).sin();
                    let mut v: Vec<Real> =
                        (0..6).map(|i| base * drift * (1.0 + i as Real)).collect();
                    if let Some(s) = where_ {
                        // Singular values linear in the distance: 0 at s, eigenvalues quadratic.
                        let d = (k as Real - s as Real).abs() / steps as Real;
                        let sv = 1e-6 + slope * d;
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

    /// Paths made by a rule on which the zero falls between two samples (0.1 to 0.3 of a step
    /// from the nearest), so the nearest sample lies only one to two decades below the path's
    /// median: the samples alone report nothing; refined with a probe of the same spectrum,
    /// the state is found once, within 1e-3 of its t, with its multiplicity. The same path
    /// whose minimum stops at 1e-2 of the median (no zero) is reported with or without the
    /// probe by neither.
    #[test]
    fn a_zero_between_samples_is_found_by_refinement() {
        let mut rand = xorshift(0x9e37_79b9_7f4a_7c15);
        for case in 0..200 {
            let steps = 40 + (rand() * 80.0) as usize;
            let base = (10.0 as Real).powf(-6.0 + 3.0 * rand());
            let near = 0.1 + 0.2 * rand();
            let at = 5 + (rand() * (steps - 10) as Real) as usize;
            let side = if rand() < 0.5 { -1.0 } else { 1.0 };
            let t0 = (at as Real + side * near) / steps as Real;
            let m = 1 + (rand() * 4.0) as usize;
            for floor in [0.0, 1e-2] {
                let spectrum = |t: Real| -> Vec<Real> {
                    let mut v: Vec<Real> = (0..6)
                        .map(|i| {
                            let full = base * (1.0 + i as Real);
                            if i < m {
                                let d = (t - t0) * steps as Real;
                                full.min(base * (d * d + floor))
                            } else {
                                full
                            }
                        })
                        .collect();
                    v.sort_by(Real::total_cmp);
                    v
                };
                let spectra: Vec<(usize, Real, Vec<Real>)> = (1..steps)
                    .map(|k| {
                        let t = k as Real / steps as Real;
                        (k, t, spectrum(t))
                    })
                    .collect();
                let probe = |k: usize, f: Real| Some(spectrum((k as Real + f) / steps as Real));
                let refined = refined_singular_states(&spectra, &probe);
                assert!(singular_states(&spectra).is_empty(), "case {case}");
                if floor > 0.0 {
                    assert!(refined.is_empty(), "case {case}: {refined:?}");
                    continue;
                }
                assert_eq!(refined.len(), 1, "case {case}: {refined:?}");
                assert!(
                    (refined[0].t - t0).abs() < 1e-3,
                    "case {case}: {refined:?} {t0}"
                );
                assert_eq!(refined[0].extra_motions, m, "case {case}");
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

//! The scalar to minimise: a target's goals evaluated on a deployment report.
//!
//! Pure functions of the report (no deployment here), so the same numbers come from a stored
//! report (screening) and a fresh one (refinement). A report that cannot meet a goal (it
//! never opens, or a lock goal on a deployment that did not end at a contact limit) gives a
//! typed [`Unmet`], never a NaN. See [`Goal`] for the definition of every value.

use super::target::{Goal, Target};
use crate::deploy::{DeploymentReport, EndReason, FrameReport};
use crate::math::{rotation, Mat2, Real};
use crate::measure::{directional_expansion, polar};
use serde::Serialize;
use std::fmt;

/// Why a deployment cannot be scored for a goal.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Unmet {
    /// The report has no frames.
    NoFrames,
    /// No frame opens (the Poisson-like ratio is undefined).
    NeverOpens,
    /// A lock goal on a deployment that ended for another reason than contact.
    NoContactLimit {
        /// The end reason.
        end_reason: String,
    },
    /// A value came out non-finite.
    NotFinite,
}

impl fmt::Display for Unmet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Unmet::NoFrames => f.write_str("the deployment has no frames"),
            Unmet::NeverOpens => f.write_str("the sheet never opens"),
            Unmet::NoContactLimit { end_reason } => {
                write!(
                    f,
                    "the deployment ends by '{end_reason}', not at a contact limit"
                )
            }
            Unmet::NotFinite => f.write_str("a goal value is not finite"),
        }
    }
}

/// The objective of one deployment: the weighted sum and each goal's value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Score {
    /// Σ weight · value (smaller is better).
    pub objective: Real,
    /// Each goal's value, in the target's order (unweighted).
    pub terms: Vec<Real>,
    /// When every goal names a value (lock, lock-f, path, area(r), expansion(θ, e); not
    /// poisson, held over the motion): the stacked residuals √weight · rᵢ
    /// with ‖rᵢ‖ the goal's value, for least-squares refinement. None otherwise.
    #[serde(skip)]
    pub residual: Option<Vec<Real>>,
}

/// U of F given as rows.
fn stretch(f: &[[Real; 2]; 2]) -> Option<Mat2> {
    let m = Mat2::new(f[0][0], f[0][1], f[1][0], f[1][1]);
    polar(&m).ok().map(|(_, u)| u)
}

/// Linear interpolation of (ε_min, ε_max) at `t` over frames ordered by t.
fn expansions_at(frames: &[FrameReport], t: Real) -> (Real, Real) {
    let pair = |f: &FrameReport| (f.measures.min_expansion, f.measures.max_expansion);
    let first = &frames[0];
    if t <= first.t {
        return pair(first);
    }
    for w in frames.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if t <= b.t {
            let span = b.t - a.t;
            let s = if span > 0.0 { (t - a.t) / span } else { 1.0 };
            let (pa, pb) = (pair(a), pair(b));
            return (pa.0 + s * (pb.0 - pa.0), pa.1 + s * (pb.1 - pa.1));
        }
    }
    pair(&frames[frames.len() - 1])
}

fn end_state(report: &DeploymentReport) -> Result<&FrameReport, Unmet> {
    if report.end_reason != EndReason::ContactLimit {
        let end_reason = serde_json::to_value(&report.end_reason)
            .ok()
            .and_then(|v| v.get("kind").and_then(|k| k.as_str()).map(str::to_string))
            .unwrap_or_else(|| report.end_reason.to_string());
        return Err(Unmet::NoContactLimit { end_reason });
    }
    report.frames.last().ok_or(Unmet::NoFrames)
}

/// The entries of a symmetric 2×2 matrix whose Euclidean norm is its Frobenius norm.
fn sym_entries(m: &Mat2) -> [Real; 3] {
    let off = 0.5 * (m[(0, 1)] + m[(1, 0)]);
    [m[(0, 0)], std::f64::consts::SQRT_2 * off, m[(1, 1)]]
}

/// The largest ε(θ) over the frames, θ in degrees.
fn largest_expansion_along(frames: &[FrameReport], angle_deg: Real) -> Real {
    let theta = angle_deg.to_radians();
    frames
        .iter()
        .map(|f| directional_expansion(&f.measures.u_matrix(), theta))
        .fold(Real::NEG_INFINITY, Real::max)
}

/// The residual vector of a matching goal (its Euclidean norm is [`goal_value`]); `None` for
/// goals that are not matches (extreme expansion, Poisson-like ratio held over the motion).
pub fn goal_residual(goal: &Goal, report: &DeploymentReport) -> Result<Option<Vec<Real>>, Unmet> {
    let r = match goal {
        Goal::Area { ratio: Some(r) } => {
            if report.frames.is_empty() {
                return Err(Unmet::NoFrames);
            }
            vec![report.max_area_ratio - r]
        }
        Goal::Expansion {
            angle_deg,
            value: Some(e),
        } => {
            if report.frames.is_empty() {
                return Err(Unmet::NoFrames);
            }
            vec![largest_expansion_along(&report.frames, *angle_deg) - e]
        }
        Goal::LockF { f } => {
            let want = stretch(f).ok_or(Unmet::NotFinite)?;
            sym_entries(&(end_state(report)?.measures.u_matrix() - want)).to_vec()
        }
        Goal::Lock {
            min,
            max,
            angle_deg,
        } => {
            let end = &end_state(report)?.measures;
            match angle_deg {
                Some(a) => {
                    let r = rotation(a.to_radians());
                    let want = r * Mat2::new(1.0 + max, 0.0, 0.0, 1.0 + min) * r.transpose();
                    sym_entries(&(end.u_matrix() - want)).to_vec()
                }
                None => vec![end.min_expansion - min, end.max_expansion - max],
            }
        }
        Goal::Path { points } => {
            if report.frames.is_empty() {
                return Err(Unmet::NoFrames);
            }
            let k = 1.0 / (points.len() as Real).sqrt();
            points
                .iter()
                .flat_map(|p| {
                    let (lo, hi) = expansions_at(&report.frames, p.t);
                    [k * (lo - p.min), k * (hi - p.max)]
                })
                .collect()
        }
        _ => return Ok(None),
    };
    if r.iter().all(|v| v.is_finite()) {
        Ok(Some(r))
    } else {
        Err(Unmet::NotFinite)
    }
}

/// The value of one goal on a deployment (see [`Goal`]).
pub fn goal_value(goal: &Goal, report: &DeploymentReport) -> Result<Real, Unmet> {
    let frames = &report.frames;
    if frames.is_empty() {
        return Err(Unmet::NoFrames);
    }
    let max_over =
        |f: &dyn Fn(&FrameReport) -> Real| frames.iter().map(f).fold(Real::NEG_INFINITY, Real::max);
    let value = match goal {
        // Over every accepted step (the report's summary), so that the value does not
        // depend on how many frames were asked for.
        Goal::Area { ratio: None } => -(report.max_area_ratio - 1.0),
        Goal::Uniform {} => -max_over(&|f| f.measures.min_expansion),
        Goal::Expansion {
            angle_deg,
            value: None,
        } => -largest_expansion_along(frames, *angle_deg),
        Goal::Poisson { nu } => {
            let (lo, hi) = report.poisson_range().ok_or(Unmet::NeverOpens)?;
            (lo - nu).abs().max((hi - nu).abs())
        }
        // Matching goals: the Euclidean norm of the residual (Frobenius for U, since the
        // off-diagonal entry carries √2; RMS over the path's points; |A − r|, |ε − e|).
        Goal::LockF { .. }
        | Goal::Lock { .. }
        | Goal::Path { .. }
        | Goal::Area { ratio: Some(_) }
        | Goal::Expansion { value: Some(_), .. } => {
            let r = goal_residual(goal, report)?.ok_or(Unmet::NotFinite)?;
            r.iter().map(|v| v * v).sum::<Real>().sqrt()
        }
    };
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Unmet::NotFinite)
    }
}

/// The target's objective on a deployment: Σ weight · [`goal_value`].
pub fn score(target: &Target, report: &DeploymentReport) -> Result<Score, Unmet> {
    let terms = target
        .terms
        .iter()
        .map(|t| goal_value(&t.goal, report))
        .collect::<Result<Vec<_>, _>>()?;
    let objective = target
        .terms
        .iter()
        .zip(&terms)
        .map(|(t, v)| t.weight * v)
        .sum::<Real>();
    if !objective.is_finite() {
        return Err(Unmet::NotFinite);
    }
    let mut residual = Some(Vec::new());
    for t in &target.terms {
        match (goal_residual(&t.goal, report)?, residual.as_mut()) {
            (Some(r), Some(all)) => all.extend(r.iter().map(|v| t.weight.sqrt() * v)),
            _ => residual = None,
        }
    }
    Ok(Score {
        objective,
        terms,
        residual,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::{deploy, resolve_design, DeployRequest};
    use crate::inverse::target::PathPoint;

    fn rotating_squares() -> DeploymentReport {
        let d = resolve_design("rotating-squares").unwrap();
        deploy(&d, &DeployRequest::default(), &mut |_| true)
            .unwrap()
            .report
    }

    #[test]
    fn rotating_squares_scores() {
        let r = rotating_squares();
        let value = |g: Goal| goal_value(&g, &r).unwrap();
        // Largest area ratio (cos φ + sin φ)² = 2 at φ = 45°.
        assert!(
            (value(Goal::Area { ratio: None }) + 1.0).abs() < 2e-3,
            "{}",
            value(Goal::Area { ratio: None })
        );
        // Isotropic: ε(θ) is the same in every direction, √2 − 1 at best.
        let best = 2f64.sqrt() - 1.0;
        for a in [0.0, 30.0, 90.0] {
            let v = value(Goal::Expansion {
                angle_deg: a,
                value: None,
            });
            assert!((v + best).abs() < 2e-3, "{a}: {v}");
            // The same with a value: the distance of the largest ε(θ) from it.
            let at = value(Goal::Expansion {
                angle_deg: a,
                value: Some(0.25),
            });
            assert!((at - (-v - 0.25)).abs() < 1e-12, "{a}: {at} vs {v}");
        }
        // Opens to twice its area: area(2) is met, area(1.6) is 0.4 away (either side).
        let reached = r.max_area_ratio;
        assert!(value(Goal::Area { ratio: Some(2.0) }) < 2e-3);
        assert!((value(Goal::Area { ratio: Some(1.6) }) - (reached - 1.6)).abs() < 1e-12);
        assert!((value(Goal::Area { ratio: Some(2.5) }) - (2.5 - reached)).abs() < 1e-12);
        assert!((value(Goal::Uniform {}) + best).abs() < 2e-3);
        assert!(value(Goal::Poisson { nu: -1.0 }) < 1e-6);
        assert!((value(Goal::Poisson { nu: 0.0 }) - 1.0).abs() < 1e-6);
        // It closes again at 90°, where U = I: the contact limit is near the closed shape.
        let end = &r.frames.last().unwrap().measures;
        let lock = value(Goal::Lock {
            min: end.min_expansion,
            max: end.max_expansion,
            angle_deg: None,
        });
        assert!(lock < 1e-12);
        let f = r.frames.last().unwrap().f;
        assert!(value(Goal::LockF { f }) < 1e-9);
        // The sheet's turn does not matter: F* = R(0.7) F has the same U.
        let m = rotation(0.7) * Mat2::new(f[0][0], f[0][1], f[1][0], f[1][1]);
        let turned = [[m[(0, 0)], m[(0, 1)]], [m[(1, 0)], m[(1, 1)]]];
        assert!(value(Goal::LockF { f: turned }) < 1e-9);
        // A path read off the report's own frames scores 0; a shifted one by the shift.
        let points: Vec<PathPoint> = r
            .frames
            .iter()
            .step_by(7)
            .map(|f| PathPoint {
                t: f.t,
                min: f.measures.min_expansion,
                max: f.measures.max_expansion,
            })
            .collect();
        assert!(
            value(Goal::Path {
                points: points.clone()
            }) < 1e-12
        );
        let shifted = points
            .iter()
            .map(|p| PathPoint {
                min: p.min + 0.03,
                max: p.max + 0.04,
                ..*p
            })
            .collect();
        assert!((value(Goal::Path { points: shifted }) - 0.05).abs() < 1e-12);
    }

    #[test]
    fn residuals_have_the_goal_values_as_norms() {
        let r = rotating_squares();
        let mid = &r.frames[r.frames.len() / 3].measures;
        let goals = [
            Goal::LockF {
                f: [[1.1, 0.05], [-0.02, 1.3]],
            },
            Goal::Lock {
                min: 0.1,
                max: 0.25,
                angle_deg: Some(30.0),
            },
            Goal::Lock {
                min: 0.1,
                max: 0.25,
                angle_deg: None,
            },
            Goal::Path {
                points: vec![
                    PathPoint {
                        t: 0.3,
                        min: mid.min_expansion + 0.01,
                        max: 0.2,
                    },
                    PathPoint {
                        t: 0.9,
                        min: 0.0,
                        max: 0.1,
                    },
                ],
            },
        ];
        for g in &goals {
            let res = goal_residual(g, &r).unwrap().expect("a matching goal");
            let norm = res.iter().map(|v| v * v).sum::<Real>().sqrt();
            let value = goal_value(g, &r).unwrap();
            assert!((norm - value).abs() < 1e-12, "{g}: {norm} vs {value}");
            assert!(value > 1e-3, "{g}: a real mismatch");
        }
        assert_eq!(
            goal_residual(&Goal::Area { ratio: None }, &r).unwrap(),
            None
        );
        let area = goal_residual(&Goal::Area { ratio: Some(1.6) }, &r).unwrap();
        assert_eq!(area, Some(vec![r.max_area_ratio - 1.6]));
        let t = Target::parse("lock(0.1,0.25) + 4*lock-f(1.1,0.05,-0.02,1.3)").unwrap();
        let s = score(&t, &r).unwrap();
        let res = s.residual.expect("all goals match");
        assert_eq!(res.len(), 2 + 3);
        let stacked = res.iter().map(|v| v * v).sum::<Real>();
        let want = s.terms[0].powi(2) + 4.0 * s.terms[1].powi(2);
        assert!((stacked - want).abs() < 1e-12);
        assert!(score(&Target::parse("lock(0.1,0.2) + area").unwrap(), &r)
            .unwrap()
            .residual
            .is_none());
    }

    #[test]
    fn weighted_sum_and_unmet_goals() {
        let mut r = rotating_squares();
        let t = Target::parse("2*area + 3*poisson(0)").unwrap();
        let s = score(&t, &r).unwrap();
        assert_eq!(s.terms.len(), 2);
        assert!((s.objective - (2.0 * s.terms[0] + 3.0 * s.terms[1])).abs() < 1e-12);
        r.end_reason = EndReason::MaxSteps;
        let lock = Target::parse("lock(0.1,0.2)").unwrap();
        assert_eq!(
            score(&lock, &r).unwrap_err(),
            Unmet::NoContactLimit {
                end_reason: "max_steps".into()
            }
        );
        for f in &mut r.frames {
            f.measures.max_expansion = -0.01;
        }
        r.max_expansion = -0.01;
        r.poisson = Some(None);
        assert_eq!(
            goal_value(&Goal::Poisson { nu: -1.0 }, &r).unwrap_err(),
            Unmet::NeverOpens
        );
        r.frames.clear();
        assert_eq!(
            goal_value(&Goal::Area { ratio: None }, &r).unwrap_err(),
            Unmet::NoFrames
        );
    }

    #[test]
    fn area_reads_every_step_not_the_frames() {
        let mut r = rotating_squares();
        // A peak between frames (as a coarse frame count misses it) still counts.
        r.max_area_ratio = 2.5;
        assert!((goal_value(&Goal::Area { ratio: None }, &r).unwrap() + 1.5).abs() < 1e-12);
    }

    #[test]
    fn lock_with_direction_compares_the_whole_stretch() {
        let mut r = rotating_squares();
        // Make the end state a pure stretch of 30 % along 20°, 5 % across.
        let want = rotation(20f64.to_radians())
            * Mat2::new(1.3, 0.0, 0.0, 1.05)
            * rotation(20f64.to_radians()).transpose();
        let end = &mut r.frames.last_mut().unwrap().measures;
        end.u = [[want[(0, 0)], want[(0, 1)]], [want[(1, 0)], want[(1, 1)]]];
        end.min_expansion = 0.05;
        end.max_expansion = 0.3;
        let at = |deg: Real| {
            goal_value(
                &Goal::Lock {
                    min: 0.05,
                    max: 0.3,
                    angle_deg: Some(deg),
                },
                &r,
            )
            .unwrap()
        };
        assert!(at(20.0) < 1e-12);
        assert!(at(200.0) < 1e-12, "directions are axes");
        assert!(at(65.0) > 0.1);
    }
}

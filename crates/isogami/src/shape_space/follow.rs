//! Moving one shape parameter while keeping one degree of freedom.
//!
//! A generic design just takes the new value (checked). A special design is moved by
//! continuation along its special set: in steps of at most the settings' radius (scaled
//! units), a predictor along the tangent direction that moves the parameter by the step
//! (e_i projected off the constraint normals), then the corrector ([`super::correct`])
//! along the normals with their i-th component removed, so the parameter lands exactly on
//! its value while the others adjust. Every step is checked for a well-shaped tile and one
//! DOF.

use super::classify::{classify, normals, pinned, shape_problem, ShapeClass};
use super::correct::correct;
use super::error::ShapeError;
use super::jacobian::{moved, param_scales};
use super::kernel::dof;
use super::ShapeSettings;
use crate::math::{DVec, Real};
use crate::topology::Design;
use serde::Serialize;

/// The result of [`follow`].
#[derive(Debug, Clone, Serialize)]
pub struct Followed {
    /// The moved design (one DOF, well-shaped tile).
    #[serde(skip)]
    pub design: Design,
    /// Its spec.
    pub spec: String,
    /// The class of the starting design.
    pub class: ShapeClass,
    /// Continuation steps taken (0 for a generic design).
    pub steps: usize,
    /// How far each other parameter moved, in units of its scale.
    pub adjusted: Vec<Real>,
}

/// Gram–Schmidt on `vectors`, dropping those that are (nearly) dependent.
fn orthonormal(vectors: Vec<DVec>) -> Vec<DVec> {
    let mut out: Vec<DVec> = Vec::new();
    for mut v in vectors {
        for b in &out {
            let d = b.dot(&v);
            v.axpy(-d, b, 1.0);
        }
        let n = v.norm();
        if n > 1e-8 {
            out.push(v / n);
        }
    }
    out
}

/// `design` with parameter `index` moved to `value`, its other parameters adjusted so that it
/// keeps one DOF (see the module documentation).
pub fn follow(
    design: &Design,
    index: usize,
    value: Real,
    settings: &ShapeSettings,
) -> Result<Followed, ShapeError> {
    let count = design.params.len();
    if index >= count {
        return Err(ShapeError::NoSuchParameter { index, count });
    }
    if !value.is_finite() {
        return Err(ShapeError::NotFinite { value });
    }
    let class = classify(design, settings)?.class;
    let scales = param_scales(design.family);
    let leaves = |d: &Design| {
        shape_problem(d).map(|problem| ShapeError::LeavesShapes {
            index,
            value,
            problem,
        })
    };
    let finish = |moved: Design, steps: usize| -> Result<Followed, ShapeError> {
        // The answer is a canonical design, so that following back to a stored shape finds it.
        let moved = moved.at_params(&moved.params);
        if let Some(e) = leaves(&moved) {
            return Err(e);
        }
        let (n, ratio) = dof(&moved, settings.mobility)?;
        if n != 1 {
            return Err(ShapeError::Lost {
                index,
                value,
                residual: ratio,
            });
        }
        let adjusted = (0..count)
            .map(|k| (moved.params[k] - design.params[k]) / scales[k])
            .collect();
        Ok(Followed {
            spec: moved.to_string(),
            design: moved,
            class,
            steps,
            adjusted,
        })
    };
    if class != ShapeClass::Special {
        let mut d = design.clone();
        d.params[index] = value;
        return finish(d, 0);
    }
    let delta = (value - design.params[index]) / scales[index];
    let steps = ((delta.abs() / settings.radius).ceil() as usize).max(1);
    let h = delta / steps as Real;
    let mut cur = design.clone();
    for step in 1..=steps {
        let normals = normals(&cur, settings)?;
        if pinned(&normals, count).contains(&index) {
            return Err(ShapeError::Pinned { index });
        }
        let mut tangent = DVec::zeros(count);
        tangent[index] = 1.0;
        for n in &normals {
            tangent.axpy(-n[index], n, 1.0);
        }
        if tangent[index] < 1e-9 {
            return Err(ShapeError::Pinned { index });
        }
        let along = tangent[index];
        let dir: Vec<Real> = tangent.iter().map(|t| t / along).collect();
        let mut predicted = moved(&cur, &dir, h);
        predicted.params[index] = design.params[index] + h * step as Real * scales[index];
        if step == steps {
            predicted.params[index] = value;
        }
        if let Some(e) = leaves(&predicted) {
            return Err(e);
        }
        let basis = orthonormal(
            normals
                .into_iter()
                .map(|mut n| {
                    n[index] = 0.0;
                    n
                })
                .collect(),
        );
        cur = match correct(&predicted, &basis, settings.mobility)? {
            Some(d) => d,
            None => {
                return Err(ShapeError::Lost {
                    index,
                    value: predicted.params[index],
                    residual: dof(&predicted, settings.mobility)?.1,
                })
            }
        };
    }
    finish(cur, steps)
}

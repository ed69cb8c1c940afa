//! Generic or special: does one degree of freedom survive every small change of the tile
//! shape, or only changes along a sub-manifold?
//!
//! Degrees of freedom can only fall near a shape (rank is lower semicontinuous), so a design
//! with one DOF is generic exactly when nearby shapes keep it. The test deforms the shape to
//! up to `samples` quasi-random points (a Halton sequence, deterministic, pushed out to the
//! surface of the box of relative half-width `radius` in scaled coordinates), keeps the well-shaped ones and counts their
//! DOF. For a special design it also returns its first-order shape constraints
//! ([`super::kernel`]) and the free directions along which a shape can move and keep one
//! DOF.

use super::error::ShapeError;
use super::jacobian::moved;
use super::kernel::{constraint_basis, dof, Kernel};
use super::ShapeSettings;
use crate::math::{DVec, Real};
use crate::tiling::{shape_quality_problem, Tiling};
use crate::topology::Design;
use serde::Serialize;

/// How a design's one degree of freedom depends on the tile shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ShapeClass {
    /// The family has no shape parameters: there is nothing to move.
    FixedShape,
    /// One DOF at every nearby well-shaped tile.
    Generic,
    /// One DOF only on a subset of shapes: nearby shapes off it are rigid.
    Special,
}

/// The result of [`classify`].
#[derive(Debug, Clone, Serialize)]
pub struct ShapeMobility {
    /// The design's spec.
    pub design: String,
    /// Generic, special or fixed shape.
    pub class: ShapeClass,
    /// Well-shaped nearby shapes tested.
    pub samples: usize,
    /// Of those, how many kept one DOF.
    pub samples_one_dof: usize,
    /// Self-stresses of the closed state.
    pub self_stresses: usize,
    /// Independent first-order shape constraints (0 for a generic design), each a unit
    /// normal in parameter space: a shape change δp keeps one DOF to first order when
    /// n·δp = 0 for every normal n.
    pub constraints: Vec<Vec<Real>>,
    /// Parameters that cannot move at all while the constraints hold.
    pub pinned: Vec<usize>,
}

/// The k-th point of the Halton sequence in `dims` dimensions, each coordinate in (0, 1).
pub(crate) fn halton_point(k: usize, dims: usize) -> Vec<Real> {
    const PRIMES: [usize; 12] = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37];
    (0..dims)
        .map(|d| {
            let base = PRIMES[d % PRIMES.len()];
            let (mut f, mut r, mut i) = (1.0, 0.0, k + 1);
            while i > 0 {
                f /= base as Real;
                r += f * (i % base) as Real;
                i /= base;
            }
            r
        })
        .collect()
}

/// True when the design's tile is valid and well shaped.
pub(crate) fn shape_problem(design: &Design) -> Option<String> {
    match Tiling::new(design.family, &design.params) {
        Ok(t) => shape_quality_problem(t.prototile()),
        Err(e) => Some(e.to_string()),
    }
}

/// Unit normals converted from scaled coordinates to parameter space.
fn in_parameter_space(design: &Design, normals: &[DVec]) -> Vec<Vec<Real>> {
    let scales = super::jacobian::param_scales(design.family);
    normals
        .iter()
        .map(|n| {
            let v: Vec<Real> = n.iter().zip(&scales).map(|(x, s)| x / s).collect();
            let norm = v.iter().map(|x| x * x).sum::<Real>().sqrt();
            v.iter().map(|x| x / norm).collect()
        })
        .collect()
}

/// Parameters i with e_i inside the span of the constraint normals (scaled coordinates):
/// no tangent direction moves them.
pub(crate) fn pinned(normals: &[DVec], params: usize) -> Vec<usize> {
    (0..params)
        .filter(|&i| {
            let along: Real = normals.iter().map(|n| n[i] * n[i]).sum();
            along > 1.0 - 1e-9
        })
        .collect()
}

/// Classifies `design` (which must have one DOF at its shape).
pub fn classify(design: &Design, settings: &ShapeSettings) -> Result<ShapeMobility, ShapeError> {
    settings.validate()?;
    let kernel = Kernel::of(design, settings.mobility)?;
    let p = design.params.len();
    let mut out = ShapeMobility {
        design: design.to_string(),
        class: ShapeClass::FixedShape,
        samples: 0,
        samples_one_dof: 0,
        self_stresses: kernel.stresses.ncols(),
        constraints: Vec::new(),
        pinned: Vec::new(),
    };
    if p == 0 {
        return Ok(out);
    }
    for k in 0..settings.samples {
        // On the surface of the box (max-norm 1), never at the design itself.
        let mut dir: Vec<Real> = halton_point(k, p).iter().map(|u| 2.0 * u - 1.0).collect();
        let size = dir.iter().fold(0.0, |m: Real, x| m.max(x.abs()));
        if size < 1e-9 {
            continue;
        }
        dir.iter_mut().for_each(|x| *x /= size);
        let nearby = moved(design, &dir, settings.radius);
        if shape_problem(&nearby).is_some() {
            continue;
        }
        out.samples += 1;
        if dof(&nearby, settings.mobility)?.0 >= 1 {
            out.samples_one_dof += 1;
        }
    }
    if out.samples == out.samples_one_dof {
        out.class = ShapeClass::Generic;
        return Ok(out);
    }
    out.class = ShapeClass::Special;
    let normals = constraint_basis(&kernel.pairing(design)?);
    out.pinned = pinned(&normals, p);
    out.constraints = in_parameter_space(design, &normals);
    Ok(out)
}

/// The constraint normals (scaled coordinates, orthonormal) of a design with one DOF; none
/// for a generic one.
pub(crate) fn normals(design: &Design, settings: &ShapeSettings) -> Result<Vec<DVec>, ShapeError> {
    let kernel = Kernel::of(design, settings.mobility)?;
    Ok(constraint_basis(&kernel.pairing(design)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halton_points_fill_the_box() {
        let pts: Vec<Vec<Real>> = (0..64).map(|k| halton_point(k, 3)).collect();
        for d in 0..3 {
            let below = pts.iter().filter(|p| p[d] < 0.5).count();
            assert!(
                (28..=36).contains(&below),
                "dimension {d}: {below} of 64 below 0.5"
            );
            assert!(pts.iter().all(|p| p[d] > 0.0 && p[d] < 1.0));
        }
    }
}

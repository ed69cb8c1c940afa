//! The reduced constraint Jacobian J(p) of a design's closed state as a function of its shape
//! parameters p, and its derivatives along directions of the (scaled) shape space.
//!
//! J is the mechanism's joint-constraint Jacobian at its rest state with tile 0's three
//! columns removed (as in [`crate::mobility::reduced_hessian`], H = JᵀJ). It is
//! non-dimensional (lengths in units of the mean edge), so its entries are O(1) at every
//! shape. Shape directions are given in scaled coordinates x_i = p_i / s_i with
//! s_i = max(|Kaplan default_i|, 0.25), the exploration's sampling scale, so that a unit step
//! is comparable across parameters.

use crate::kinematics::Mechanism;
use crate::math::{DMat, Real};
use crate::tiling::Family;
use crate::topology::Design;

/// Relative step of the central differences of J, in scaled coordinates.
pub const DIFF_STEP: Real = 1e-6;

/// The sampling scale s_i of every parameter of `family`.
pub fn param_scales(family: Family) -> Vec<Real> {
    family
        .default_params()
        .iter()
        .map(|d| d.abs().max(0.25))
        .collect()
}

/// `design` with parameters p + Σ step·s_i·dir_i.
pub fn moved(design: &Design, dir: &[Real], step: Real) -> Design {
    let scales = param_scales(design.family);
    let mut d = design.clone();
    for ((p, s), x) in d.params.iter_mut().zip(&scales).zip(dir) {
        *p += step * s * x;
    }
    d
}

/// The reduced Jacobian of `design` at its closed state.
pub fn reduced_jacobian(design: &Design) -> crate::Result<DMat> {
    let cell = design.cell()?;
    let mech = Mechanism::new(&cell, &design.joints)?;
    let j = mech.jacobian(&mech.rest);
    Ok(j.columns(3, j.ncols() - 3).into_owned())
}

/// dJ/dx along the scaled direction `dir` at `design`: central differences of step
/// [`DIFF_STEP`]. J is smooth in the shape: the cell's edge table is the same at every shape
/// of the family (`cell` places every tile at a lattice translate fixed per family), so no
/// difference straddles a change of tile representative.
pub fn derivative(design: &Design, dir: &[Real]) -> crate::Result<DMat> {
    let plus = reduced_jacobian(&moved(design, dir, DIFF_STEP))?;
    let minus = reduced_jacobian(&moved(design, dir, -DIFF_STEP))?;
    Ok((plus - minus) / (2.0 * DIFF_STEP))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::resolve_design;

    #[test]
    fn the_jacobian_is_continuous_where_the_tile_representative_used_to_jump() {
        // IH46 at p0 = 0.5 (its default): the cell builder used to place tile 0 at another
        // lattice translate for p0 > 0.5, so J jumped by O(1) there. Now both sides agree to
        // first order and the central difference matches a coarser one-sided difference.
        let d = resolve_design("IH46:0.5,0.230769230769,0.5,0.5:1x1:aaaa").unwrap();
        let dir = [1.0, 0.0, 0.0, 0.0];
        let j0 = reduced_jacobian(&d).unwrap();
        let up = reduced_jacobian(&moved(&d, &dir, DIFF_STEP)).unwrap();
        assert!((up - &j0).amax() < 1e-4, "no jump above p0 = 0.5");
        let fine = derivative(&d, &dir).unwrap();
        let h = 1e-4;
        let above = (reduced_jacobian(&moved(&d, &dir, h)).unwrap() - &j0) / h;
        assert!((fine - above).amax() < 1e-3);
    }

    #[test]
    fn the_derivative_is_consistent_across_step_sizes() {
        // Central differences at two steps agree to O(h²): the Jacobian is smooth in the
        // shape and the step is well inside its resolution.
        let d = resolve_design("IH28:0.6,0.35:1x1:a--a-b-bbb").unwrap();
        let dir = [0.6, -0.8];
        let fine = derivative(&d, &dir).unwrap();
        let h = 1e-4;
        let coarse = (reduced_jacobian(&moved(&d, &dir, h)).unwrap()
            - reduced_jacobian(&moved(&d, &dir, -h)).unwrap())
            / (2.0 * h);
        let scale = fine.norm().max(1.0);
        assert!(fine.norm() > 1e-3, "the shape changes the constraints");
        assert!((fine - coarse).norm() < 1e-6 * scale);
    }
}

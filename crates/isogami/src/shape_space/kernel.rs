//! The first-order picture at one shape: the motion v (J v = 0), the self-stresses w
//! (Jᵀ w = 0), and the shape constraints they give.
//!
//! A shape change δx keeps a first-order motion when J(x + δx) has a null vector near v,
//! i.e. when (dJ·δx) v lies in the range of J. The range of J is the orthogonal complement
//! of its self-stresses, so the condition is wᵀ (dJ·δx) v = 0 for every self-stress w: one
//! linear constraint on δx per self-stress, with normal n_w = [wᵀ (∂J/∂x_i) v]_i. Stresses
//! present at every nearby shape give zero normals (moving the shape never breaks them);
//! the others are the constraints of a special design. This is the classical pairing of
//! self-stresses and mechanisms of rigidity theory, applied to the shape instead of the
//! configuration.

use super::error::ShapeError;
use super::jacobian::{derivative, reduced_jacobian};
use crate::math::{symmetric_eigen, DMat, DVec, Real};
use crate::mobility::MobilitySettings;
use crate::topology::Design;

/// A constraint normal counts when its singular value is above this fraction of the
/// largest entry scale (central differences leave about 1e-8 in a zero normal).
const NORMAL_REL_TOL: Real = 1e-5;

/// The motion and self-stresses of a design with one degree of freedom.
#[derive(Debug, Clone)]
pub struct Kernel {
    /// The unit first-order motion.
    pub motion: DVec,
    /// The self-stresses, one unit column each.
    pub stresses: DMat,
}

/// The ratio λ_min / max(λ_max, 1) of H = JᵀJ and the number of eigenvalues under the
/// mobility threshold, with the eigen-decomposition.
fn spectrum(j: &DMat, settings: MobilitySettings) -> Result<(Real, usize, DMat), ShapeError> {
    let h = j.transpose() * j;
    let spec = symmetric_eigen(h).ok_or_else(|| {
        ShapeError::Library("the eigen-solver did not converge on JᵀJ".to_string())
    })?;
    let lmax = spec.values.last().copied().unwrap_or(0.0).max(1.0);
    let threshold = settings.rel_tol * lmax;
    let dof = spec.values.iter().take_while(|&&l| l < threshold).count();
    Ok((spec.values[0] / lmax, dof, spec.vectors))
}

/// Degrees of freedom of `design` at its closed state (as the mobility analysis counts them)
/// and its eigenvalue ratio.
pub fn dof(design: &Design, settings: MobilitySettings) -> Result<(usize, Real), ShapeError> {
    let j = reduced_jacobian(design)?;
    let (ratio, dof, _) = spectrum(&j, settings)?;
    Ok((dof, ratio))
}

/// The smallest right singular vector of J (unit): the motion, or its best approximation at
/// a shape next to the special set.
pub fn softest_motion(j: &DMat, settings: MobilitySettings) -> Result<(DVec, Real), ShapeError> {
    let (ratio, _, vectors) = spectrum(j, settings)?;
    Ok((vectors.column(0).into_owned(), ratio))
}

impl Kernel {
    /// The kernel of `design`, which must have exactly one degree of freedom.
    pub fn of(design: &Design, settings: MobilitySettings) -> Result<Kernel, ShapeError> {
        let j = reduced_jacobian(design)?;
        let (_, dof, vectors) = spectrum(&j, settings)?;
        if dof != 1 {
            return Err(ShapeError::NotOneDof { dof });
        }
        let motion = vectors.column(0).into_owned();
        let g = &j * j.transpose();
        let gspec = symmetric_eigen(g).ok_or_else(|| {
            ShapeError::Library("the eigen-solver did not converge on JJᵀ".to_string())
        })?;
        let threshold = settings.rel_tol * gspec.values.last().copied().unwrap_or(0.0).max(1.0);
        let s = gspec.values.iter().take_while(|&&l| l < threshold).count();
        let stresses = gspec.vectors.columns(0, s).into_owned();
        Ok(Kernel { motion, stresses })
    }

    /// The shape-constraint matrix: one row per self-stress w, column i = wᵀ (∂J/∂x_i) v.
    pub fn pairing(&self, design: &Design) -> Result<DMat, ShapeError> {
        let p = design.params.len();
        let dirs: Vec<Vec<Real>> = (0..p)
            .map(|i| {
                let mut e = vec![0.0; p];
                e[i] = 1.0;
                e
            })
            .collect();
        pairing(design, &self.motion, &self.stresses, &dirs)
    }
}

/// Rows wᵀ (∂J/∂dir_j) v for every column w of `stresses` and every direction.
pub fn pairing(
    design: &Design,
    motion: &DVec,
    stresses: &DMat,
    dirs: &[Vec<Real>],
) -> Result<DMat, ShapeError> {
    let mut n = DMat::zeros(stresses.ncols(), dirs.len());
    for (i, dir) in dirs.iter().enumerate() {
        let dv = derivative(design, dir)? * motion;
        for k in 0..stresses.ncols() {
            n[(k, i)] = stresses.column(k).dot(&dv);
        }
    }
    Ok(n)
}

/// The softest motion v of J and the m − n + 1 left singular vectors of its smallest
/// singular values: the self-stresses J has when it loses one rank, and the one that pairs
/// with v when it has not (wᵀ J v = ±σ_min for that one, 0 for the others).
pub fn softest_pair(j: &DMat, settings: MobilitySettings) -> Result<(DVec, DMat), ShapeError> {
    let (v, _) = softest_motion(j, settings)?;
    let (m, n) = j.shape();
    let s = (m + 1).saturating_sub(n).max(1).min(m);
    let spec = symmetric_eigen(j * j.transpose()).ok_or_else(|| {
        ShapeError::Library("the eigen-solver did not converge on JJᵀ".to_string())
    })?;
    Ok((v, spec.vectors.columns(0, s).into_owned()))
}

/// An orthonormal basis (rows) of the row space of `pairing`: the independent first-order
/// shape constraints, in scaled coordinates.
pub fn constraint_basis(pairing: &DMat) -> Vec<DVec> {
    let p = pairing.ncols();
    if pairing.nrows() == 0 || p == 0 {
        return Vec::new();
    }
    let scale = pairing.amax().max(1.0);
    // The row space of N is the eigenspace of NᵀN (p × p) with non-zero eigenvalues.
    let Some(spec) = symmetric_eigen(pairing.transpose() * pairing) else {
        return Vec::new();
    };
    let cut = (NORMAL_REL_TOL * scale).powi(2);
    (0..p)
        .filter(|&k| spec.values[k] > cut)
        .map(|k| spec.vectors.column(k).into_owned())
        .collect()
}

//! Kinematic mobility (paper §3.2): the spectrum of H = JᵀJ with tile 0's three degrees of
//! freedom eliminated. Zero eigenvalues are counted against a relative tolerance on the
//! non-dimensional model and the spectral gap is reported, so that a count is never decided
//! by a hair. The zero-eigenvalue eigenvectors are the first-order motions. No deployment here.

mod error;

pub use error::MobilityError;

use crate::kinematics::Mechanism;
use crate::math::{cross, symmetric_eigen, DMat, DVec, Real, Vec2};
use serde::Serialize;

/// Settings of the mobility analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MobilitySettings {
    /// An eigenvalue counts as zero when below `rel_tol · max(λ_max, 1)` (non-dimensional H).
    pub rel_tol: Real,
}

impl Default for MobilitySettings {
    fn default() -> Self {
        MobilitySettings { rel_tol: 1e-9 }
    }
}

impl MobilitySettings {
    /// Checks the tolerance: a relative tolerance lies in (0, 1) (at 1 or above every
    /// eigenvalue would count as zero, and a huge one overflows the threshold to ∞).
    pub fn validate(&self) -> Result<(), crate::settings_error::SettingsError> {
        let t = self.rel_tol;
        if t.is_finite() && t > 0.0 && t < 1.0 {
            Ok(())
        } else {
            Err(crate::settings_error::SettingsError::new(
                "mobility tolerance",
                t,
                crate::settings_error::Requirement::Within {
                    low: 0.0,
                    high: 1.0,
                    open_low: true,
                    open_high: true,
                },
            ))
        }
    }
}

/// First-order velocity of one tile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct TileVelocity {
    /// ẋ (units of L).
    pub vx: Real,
    /// ẏ (units of L).
    pub vy: Real,
    /// θ̇ (radians).
    pub omega: Real,
}

/// One first-order motion: a unit vector of the non-dimensional state space.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct Motion {
    /// Velocity of every tile (tile 0 is held fixed).
    pub tiles: Vec<TileVelocity>,
    /// u̇.
    pub u: [Real; 2],
    /// ẇ.
    pub w: [Real; 2],
    /// Rate of change of the cell area |det[u w]| along this motion (positive: opening). The
    /// magnitude, not the signed determinant: families whose tiling vectors are clockwise
    /// (t1 × t2 < 0) have det[u w] < 0, and there a growing signed determinant closes the sheet.
    pub area_rate: Real,
    /// The whole vector in state order.
    #[serde(skip)]
    pub vector: DVec,
}

/// The result of a mobility analysis.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct Mobility {
    /// Degrees of freedom: the number of zero eigenvalues.
    pub dof: usize,
    /// All eigenvalues of the reduced H, ascending.
    pub eigenvalues: Vec<Real>,
    /// The zero threshold used.
    pub threshold: Real,
    /// Largest eigenvalue counted as zero (None if dof = 0).
    pub largest_zero: Option<Real>,
    /// Smallest eigenvalue counted as non-zero (None if all are zero).
    pub smallest_nonzero: Option<Real>,
    /// log10(smallest_nonzero / largest_zero): how many decades separate the two groups
    /// (None when one group is empty; capped at 300).
    pub gap_decades: Option<Real>,
    /// The deployment direction (None if rigid): for one degree of freedom the null vector,
    /// signed to open the sheet (|det[u w]| grows); for several, the unit combination of all
    /// first-order motions that increases the cell area fastest (the projection of
    /// ∇|det[u w]| on the null space),
    /// which, unlike any single basis vector of a degenerate eigenspace, does not depend on
    /// how the eigen-solver picked the basis. When no first-order motion changes the area, the
    /// first mode.
    pub motion: Option<Motion>,
    /// A basis of all first-order motions (dof vectors).
    pub modes: Vec<Motion>,
}

/// The reduced Hessian H = JᵀJ without tile 0's columns, at state q.
pub fn reduced_hessian(mech: &Mechanism, q: &DVec) -> DMat {
    let jac = mech.jacobian(q);
    let jr = jac.columns(3, jac.ncols() - 3);
    jr.transpose() * jr
}

/// Mobility of `mech` at state q.
pub fn analyze(
    mech: &Mechanism,
    q: &DVec,
    settings: MobilitySettings,
) -> Result<Mobility, MobilityError> {
    if q.iter().any(|x| !x.is_finite()) {
        return Err(MobilityError::NonFiniteState);
    }
    let h = reduced_hessian(mech, q);
    let spec = symmetric_eigen(h).ok_or(MobilityError::Eigen)?;
    let lmax = spec.values.last().copied().unwrap_or(0.0);
    let threshold = settings.rel_tol * lmax.max(1.0);
    let dof = spec.values.iter().take_while(|&&l| l < threshold).count();
    let largest_zero = dof.checked_sub(1).map(|k| spec.values[k]);
    let smallest_nonzero = spec.values.get(dof).copied();
    let gap_decades = match (largest_zero, smallest_nonzero) {
        (Some(z), Some(nz)) => Some((nz / z.abs().max(1e-300)).log10().min(300.0)),
        _ => None,
    };
    let modes: Vec<Motion> = (0..dof)
        .map(|k| {
            let mut v = DVec::zeros(mech.layout.len());
            v.rows_mut(3, v.len() - 3)
                .copy_from(&spec.vectors.column(k));
            to_motion(mech, q, v)
        })
        .collect();
    let motion = match modes.len() {
        0 | 1 => modes.first().cloned(),
        _ => Some(fastest_opening(mech, q, &modes)),
    };
    Ok(Mobility {
        dof,
        eigenvalues: spec.values,
        threshold,
        largest_zero,
        smallest_nonzero,
        gap_decades,
        motion,
        modes,
    })
}

/// The unit combination of `modes` (orthonormal) along which the cell area |det[u w]| grows
/// fastest: the area rate is linear in the velocity, g·v with g = ∇|det[u w]| (see
/// [`area_rate`]), so the best unit v in their span is the normalised projection
/// Σ (g·m_k) m_k. Falls back to the first mode when every mode leaves the area unchanged to
/// first order.
fn fastest_opening(mech: &Mechanism, q: &DVec, modes: &[Motion]) -> Motion {
    let mut v = DVec::zeros(mech.layout.len());
    for m in modes {
        v.axpy(area_rate(mech, q, &m.vector), &m.vector, 1.0);
    }
    if v.norm() <= 1e-9 {
        return modes[0].clone();
    }
    to_motion(mech, q, v)
}

/// Rate of change of the cell area |det[u w]| along v: sign(det[u w]) · d det[u w]/ds.
///
/// The magnitude is what opens or closes a sheet. The signed determinant is negative for the
/// families whose translation vectors are clockwise (t1 × t2 < 0, e.g. IH23), and there its
/// growth means the cell shrinks: signing a motion by d det/ds would make it close the sheet.
/// A state with det[u w] = 0 (a collapsed lattice, never an accepted state) gives d det/ds.
pub fn area_rate(mech: &Mechanism, q: &DVec, v: &DVec) -> Real {
    let (u, w) = mech.lattice(q);
    let (iu, iw) = (mech.layout.u(), mech.layout.w());
    let du = Vec2::new(v[iu], v[iu + 1]);
    let dw = Vec2::new(v[iw], v[iw + 1]);
    let rate = cross(&du, &w) + cross(&u, &dw);
    if cross(&u, &w) < 0.0 {
        -rate
    } else {
        rate
    }
}

/// Signs a unit vector so that it opens the sheet, |det[u w]| growing (or, when the area
/// does not change to first order, so that its largest component is positive) and splits it
/// per tile.
fn to_motion(mech: &Mechanism, q: &DVec, mut v: DVec) -> Motion {
    let norm = v.norm();
    if norm > 0.0 {
        v /= norm;
    }
    let mut rate = area_rate(mech, q, &v);
    let flip = if rate.abs() > 1e-9 {
        rate < 0.0
    } else {
        let k = v.iamax();
        v[k] < 0.0
    };
    if flip {
        v = -v;
        rate = -rate;
    }
    let l = mech.layout;
    Motion {
        tiles: (0..l.tiles)
            .map(|i| TileVelocity {
                vx: v[l.tile(i)],
                vy: v[l.tile(i) + 1],
                omega: v[l.tile(i) + 2],
            })
            .collect(),
        u: [v[l.u()], v[l.u() + 1]],
        w: [v[l.w()], v[l.w() + 1]],
        area_rate: rate,
        vector: v,
    }
}

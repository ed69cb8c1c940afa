//! How far apart tiles of the sheet stay along a step, for every lattice translate at once.
//!
//! A step Δ moves the reference point of tile i by |Δp_i|, any point of its collision polygon
//! by at most m_i = |Δp_i| + |Δθ_i|·r_i (r_i its extent), and its copy in cell k by a further
//! |k_u||Δu| + |k_w||Δw| ≤ ‖k‖·δ, δ = √(|Δu|² + |Δw|²). Far translates move fastest, but they
//! are also far: |k_u·u + k_w·w| ≥ σ·‖k‖ with σ the smallest singular value of [u w], so a
//! pair's centre distance D and its offset obey ‖k‖ ≤ (D + d_max)/σ, d_max the largest
//! distance between two reference points of one cell. These two facts give closed-form
//! bounds that hold for every pair of the infinite sheet, with no list of cells.

use super::placement::Placement;
use crate::kinematics::StateLayout;
use crate::math::{DVec, Real, Vec2};

/// Geometry of a placement that bounds where translates can be.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Spread {
    /// Smallest singular value of [u w].
    pub(crate) sigma: Real,
    /// Upper bound on the distance between two reference points of the cell.
    pub(crate) dmax: Real,
    /// Largest extent of a collision polygon about its reference point.
    pub(crate) rmax: Real,
}

impl Spread {
    /// The spread of `placed`, or `None` when its lattice is degenerate.
    pub(crate) fn of(placed: &Placement, extents: &[Real]) -> Option<Spread> {
        let sigma = placed.sigma_min().ok()?;
        let n = placed.tiles.len() as Real;
        let mean = placed.tiles.iter().fold(Vec2::zeros(), |s, t| s + t.centre) / n;
        let far = placed
            .tiles
            .iter()
            .map(|t| (t.centre - mean).norm())
            .fold(0.0, Real::max);
        Some(Spread {
            sigma,
            dmax: 2.0 * far,
            rmax: extents.iter().copied().fold(0.0, Real::max),
        })
    }
}

/// Per unit step: bounds of how fast things move along a direction Δ.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rates {
    /// max |Δp_i|: reference points.
    pub(crate) centre: Real,
    /// max |Δp_i| + |Δθ_i|·r_i: any point of a collision polygon in the centre cell.
    pub(crate) point: Real,
    /// √(|Δu|² + |Δw|²): the lattice.
    pub(crate) lattice: Real,
}

impl Rates {
    /// The rates of direction `dq` (which must have the layout's length).
    pub(crate) fn of(layout: StateLayout, extents: &[Real], dq: &DVec) -> Rates {
        let (mut centre, mut point) = (0.0, 0.0);
        for (i, r) in extents.iter().enumerate() {
            let k = layout.tile(i);
            let p = Vec2::new(dq[k], dq[k + 1]).norm();
            centre = Real::max(centre, p);
            point = Real::max(point, p + dq[k + 2].abs() * r);
        }
        let (iu, iw) = (layout.u(), layout.w());
        let lattice =
            (dq[iu].powi(2) + dq[iu + 1].powi(2) + dq[iw].powi(2) + dq[iw + 1].powi(2)).sqrt();
        Rates {
            centre,
            point,
            lattice,
        }
    }
}

/// Fraction of the skin that pairs beyond it always keep (see [`far_limit`]).
pub(crate) const FAR_KEEP: Real = 0.1;

/// The largest s such that along s·Δ every pair whose bounding circles are more than `skin`
/// apart at s = 0 keeps its polygons at least `FAR_KEEP · skin` apart (+∞ when nothing
/// moves).
///
/// For such a pair D(0) > r_a + r_b + skin and D(s) ≥ D(0) − s(2·centre + ‖k‖δ) with
/// ‖k‖ ≤ (D(0) + d_max)/σ, so its polygon gap is at least
/// skin − s·[2·centre + (δ/σ)(2·r_max + skin + d_max)].
pub(crate) fn far_limit(spread: &Spread, rates: &Rates, skin: Real) -> Real {
    let speed = 2.0 * rates.centre
        + rates.lattice / spread.sigma * (2.0 * spread.rmax + skin + spread.dmax);
    if speed > 0.0 {
        (1.0 - FAR_KEEP) * skin / speed
    } else {
        Real::INFINITY
    }
}

/// Smallest skin used by conservative advancement (units of L).
pub(crate) const MIN_SKIN: Real = 0.25;
/// Largest skin: a step that needs more is shortened by [`far_limit`] instead.
pub(crate) const MAX_SKIN: Real = 4.0;

/// A skin in [MIN_SKIN, MAX_SKIN] for which [`far_limit`] is at least 1 when possible.
pub(crate) fn skin_for(spread: &Spread, rates: &Rates) -> Real {
    let rel = rates.lattice / spread.sigma;
    let keep = 1.0 - FAR_KEEP;
    if rel >= keep {
        return MAX_SKIN;
    }
    let need = (2.0 * rates.centre + rel * (2.0 * spread.rmax + spread.dmax)) / (keep - rel);
    (1.01 * need).clamp(MIN_SKIN, MAX_SKIN)
}

/// A bound b such that a step s·Δ with s·δ < σ lowers the clearance of every pair of the
/// sheet by at most s·b, given that `clearance` bounds every pair's polygon gap from below.
///
/// A pair's gap is at least max(c, σ‖k‖ − e) (e = d_max + 2·r_max) and it shrinks by at most
/// s(2·point + ‖k‖δ); the smallest difference over all ‖k‖ is at the kink ‖k‖ = (c + e)/σ.
/// `None` when the lattice moves too fast for the bound (0.9·σ ≤ δ).
pub(crate) fn clearance_drop_rate(spread: &Spread, rates: &Rates, clearance: Real) -> Option<Real> {
    if rates.lattice >= 0.9 * spread.sigma {
        return None;
    }
    let e = spread.dmax + 2.0 * spread.rmax;
    Some(2.0 * rates.point + rates.lattice * (clearance + e) / spread.sigma)
}

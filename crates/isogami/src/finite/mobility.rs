//! A finite sheet's mobility with a free boundary, and the floppy parts that make it more
//! than one degree of freedom.
//!
//! The periodic sheet's motion, restricted to the sheet's tiles, is always a motion of the
//! sheet (every joint of the sheet is a joint of the periodic sheet). The sheet's other
//! first-order motions, once the three rigid motions and that restriction are taken out,
//! are its extra modes. They are reported in a local basis (each mode is one at a state
//! coordinate where the others are zero, chosen greedily by size), so that a flap that spins
//! on its own pin is one mode naming that flap, and the tiles that move in a mode are those
//! whose velocity (relative to the best rigid fit of the whole sheet) is a noticeable part of
//! the mode's largest.

use super::error::FiniteError;
use super::kernel::{sheet_kernel, SheetKernel};
use super::sheet::FiniteSheet;
use crate::kinematics::Mechanism;
use crate::math::{DMat, DVec, Real, Vec2};
use crate::stop::KeepGoing;
use serde::Serialize;

/// A tile moves in a mode when its velocity is above this fraction of the mode's largest.
pub const MOVER_FRACTION: Real = 0.05;

/// One extra mode of a finite sheet.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct FloppyMode {
    /// Indices (in [`FiniteSheet::tiles`]) of the tiles that move in it, ascending.
    pub tiles: Vec<usize>,
    /// Of them, the tiles moving at least half as fast as the fastest: the flap itself.
    pub leading: Vec<usize>,
}

/// The mobility of a finite sheet at one state.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct SheetMobility {
    /// Tiles.
    pub tiles: usize,
    /// Pins.
    pub joints: usize,
    /// Pieces the joints hold together (1 for a sheet in one piece).
    pub pieces: usize,
    /// Degrees of freedom of the largest piece plus three per other piece (each other piece
    /// moves freely).
    pub dof: usize,
    /// The rounding floor on eigenvalues of H (non-dimensional): below it an eigenvalue is
    /// zero whatever the spectrum (the zeros are decided by its largest gap, see
    /// [`super::kernel`]).
    pub threshold: Real,
    /// Largest eigenvalue counted as zero.
    pub largest_zero: Option<Real>,
    /// Smallest eigenvalue counted as non-zero.
    pub smallest_nonzero: Option<Real>,
    /// log10(smallest non-zero / largest zero).
    pub gap_decades: Option<Real>,
    /// The periodic sheet's motion, restricted to these tiles, is a first-order motion of the
    /// sheet at this state and not a rigid one: the sheet opens when the periodic sheet does.
    pub follows_periodic: bool,
    /// The extra modes (every motion but the periodic one and rigid motions), most local
    /// first.
    pub floppy: Vec<FloppyMode>,
    /// Tiles held by fewer than two pins (they spin or fall out).
    pub loose_tiles: Vec<usize>,
    /// Per tile, its share of the extra modes (the diagonal of the projector onto them,
    /// over the tile's x, y and weighted θ; 0 for a tile no extra mode moves). Sums to the
    /// number of extra modes.
    pub leverage: Vec<Real>,
}

impl SheetMobility {
    /// Every tile that moves in some extra mode, ascending.
    pub fn floppy_tiles(&self) -> Vec<usize> {
        let mut all: Vec<usize> = self.floppy.iter().flat_map(|m| m.tiles.clone()).collect();
        all.sort_unstable();
        all.dedup();
        all
    }
}

/// The velocity of every sheet tile in the periodic motion `motion` (a state-space vector of
/// `mech`, as [`crate::mobility::Motion::vector`]): tile k's velocity plus its cell's
/// lattice translate's rate. Full sheet coordinates (x, y, θ per tile).
pub fn periodic_velocity(sheet: &FiniteSheet, mech: &Mechanism, motion: &DVec) -> DVec {
    let layout = mech.layout;
    let du = Vec2::new(motion[layout.u()], motion[layout.u() + 1]);
    let dw = Vec2::new(motion[layout.w()], motion[layout.w() + 1]);
    let mut v = DVec::zeros(3 * sheet.len());
    for (i, t) in sheet.tiles.iter().enumerate() {
        let k = layout.tile(t.tile);
        let lin = Vec2::new(motion[k], motion[k + 1])
            + du * Real::from(t.cell[0])
            + dw * Real::from(t.cell[1]);
        v[3 * i] = lin.x;
        v[3 * i + 1] = lin.y;
        v[3 * i + 2] = motion[k + 2];
    }
    v
}

/// The mobility of `sheet` at tile poses `poses`; `periodic` is the periodic motion's
/// velocity of the sheet's tiles ([`periodic_velocity`]) at the same state, or `None` when
/// there is none to compare (the extra modes are then every non-rigid motion but one).
/// `keep_going` is polled through the work (the solver's solves, the modes' localisation):
/// `false` ends it with [`FiniteError::Cancelled`].
pub fn sheet_mobility(
    sheet: &FiniteSheet,
    mech: &Mechanism,
    poses: &[(Vec2, Real)],
    periodic: Option<&DVec>,
    keep_going: KeepGoing<'_>,
) -> Result<SheetMobility, FiniteError> {
    let kernel = sheet_kernel(sheet, mech, poses, keep_going)?;
    let (_, pieces) = sheet.pieces();
    let pins = sheet.pins();
    let weights = rotation_weights(sheet, mech);
    let (follows_periodic, floppy, leverage) =
        extra_modes(&kernel, poses, periodic, &weights, keep_going)?;
    Ok(SheetMobility {
        tiles: sheet.len(),
        joints: sheet.joints.len(),
        pieces,
        dof: kernel.dof,
        threshold: kernel.threshold,
        largest_zero: kernel.largest_zero,
        smallest_nonzero: kernel.smallest_nonzero,
        gap_decades: kernel.gap_decades(),
        follows_periodic,
        floppy,
        loose_tiles: (0..sheet.len()).filter(|&t| pins[t] < 2).collect(),
        leverage,
    })
}

/// Per tile, the lever that turns an angular velocity into a length rate: the tile's root
/// mean square vertex distance from its centroid (units of L).
fn rotation_weights(sheet: &FiniteSheet, mech: &Mechanism) -> Vec<Real> {
    sheet
        .tiles
        .iter()
        .map(|t| {
            let s = &mech.tile_shapes[t.tile];
            (s.iter().map(|v| v.norm_squared()).sum::<Real>() / s.len() as Real).sqrt()
        })
        .collect()
}

/// Whether the periodic motion is a non-rigid motion of the sheet, and the extra modes.
fn extra_modes(
    kernel: &SheetKernel,
    poses: &[(Vec2, Real)],
    periodic: Option<&DVec>,
    weights: &[Real],
    keep_going: KeepGoing<'_>,
) -> Result<(bool, Vec<FloppyMode>, Vec<Real>), FiniteError> {
    let n = poses.len();
    let weigh = |v: &mut DVec| {
        for (t, w) in weights.iter().enumerate() {
            v[3 * t + 2] *= w;
        }
    };
    // The rigid motions, weighted, orthonormalised.
    let mut known: Vec<DVec> = Vec::new();
    let push = |mut v: DVec, known: &mut Vec<DVec>| -> bool {
        weigh(&mut v);
        let size = v.norm();
        for q in known.iter() {
            let c = q.dot(&v);
            v -= q * c;
        }
        let left = v.norm();
        if size > 0.0 && left > 1e-6 * size {
            known.push(v / left);
            true
        } else {
            false
        }
    };
    let mut tx = DVec::zeros(3 * n);
    let mut ty = DVec::zeros(3 * n);
    let mut rot = DVec::zeros(3 * n);
    for (t, (p, _)) in poses.iter().enumerate() {
        tx[3 * t] = 1.0;
        ty[3 * t + 1] = 1.0;
        rot[3 * t] = -p.y;
        rot[3 * t + 1] = p.x;
        rot[3 * t + 2] = 1.0;
    }
    for v in [tx, ty, rot] {
        push(v, &mut known);
    }
    // The kernel (weighted, with the rigid motions of the reference piece added back) less
    // the rigid motions, as an orthonormal basis.
    let nothing = Ok((false, Vec::new(), vec![0.0; n]));
    let d = kernel.vectors.ncols();
    let mut rest = DMat::zeros(3 * n, d);
    for k in 0..d {
        let mut v: DVec = kernel.vectors.column(k).into_owned();
        weigh(&mut v);
        for q in &known {
            let c = q.dot(&v);
            v -= q * c;
        }
        rest.set_column(k, &v);
    }
    let Some(motions) = orthonormal_span(&rest) else {
        return nothing;
    };
    // The periodic motion counts when it is a non-rigid motion of the sheet and lies in the
    // kernel (it always does at the state it was computed at; not at another).
    let mut follows = false;
    let mut basis = motions.clone();
    if let Some(v) = periodic {
        let mut p = v.clone();
        weigh(&mut p);
        let size = p.norm();
        for q in &known {
            let c = q.dot(&p);
            p -= q * c;
        }
        let left = p.norm();
        if size > 0.0 && left > 1e-6 * size && motions.ncols() > 0 {
            let inside = &motions * (motions.transpose() * &p);
            if (&p - &inside).norm() < 1e-3 * left {
                follows = true;
                let dir = inside.normalize();
                let mut others = motions.clone();
                for k in 0..others.ncols() {
                    let c = others.column(k).dot(&dir);
                    let col = others.column(k) - &dir * c;
                    others.set_column(k, &col);
                }
                basis = match orthonormal_span(&others) {
                    Some(b) => b,
                    None => return nothing,
                };
            }
        }
    }
    if basis.ncols() == 0 {
        return Ok((follows, Vec::new(), vec![0.0; n]));
    }
    if !keep_going() {
        return Err(FiniteError::Cancelled);
    }
    // Each tile's share of the extra modes: the diagonal of the projector onto them, summed
    // over the tile's three coordinates (independent of the basis chosen).
    let leverage = (0..n)
        .map(|t| (0..3).map(|d| basis.row(3 * t + d).norm_squared()).sum())
        .collect();
    Ok((follows, localise(&basis, n, keep_going)?, leverage))
}

/// An orthonormal basis of the span of `m`'s columns: the eigenvectors of its Gram matrix
/// with eigenvalues (squared singular values) above rounding. The columns given are unit
/// vectors with known directions taken out, so what is left of one is either most of it or
/// rounding. None when the eigen-solver fails.
fn orthonormal_span(m: &DMat) -> Option<DMat> {
    let d = m.ncols();
    let spec = crate::math::symmetric_eigen(m.transpose() * m)?;
    let kept: Vec<usize> = (0..d).rev().filter(|&k| spec.values[k] > 1e-8).collect();
    let mut basis = DMat::zeros(m.nrows(), kept.len());
    for (c, &k) in kept.iter().enumerate() {
        let v = m * spec.vectors.column(k) / spec.values[k].sqrt();
        basis.set_column(c, &v);
    }
    Some(basis)
}

/// The modes of `basis` (orthonormal columns) in a local basis, each with the tiles that move
/// in it; most local first. `keep_going` is polled before every pivot.
fn localise(
    basis: &DMat,
    n: usize,
    keep_going: KeepGoing<'_>,
) -> Result<Vec<FloppyMode>, FiniteError> {
    let e = basis.ncols();
    // Greedy row pivots: the largest remaining row, then every row projected off it.
    let mut residual = basis.clone();
    let mut pivots = Vec::with_capacity(e);
    for _ in 0..e {
        if !keep_going() {
            return Err(FiniteError::Cancelled);
        }
        let (best, norm) = (0..residual.nrows())
            .map(|r| (r, residual.row(r).norm()))
            .fold((0, 0.0), |acc, x| if x.1 > acc.1 { x } else { acc });
        if norm <= 0.0 {
            break;
        }
        pivots.push(best);
        let dir = residual.row(best).transpose() / norm;
        for r in 0..residual.nrows() {
            let c = residual.row(r).dot(&dir.transpose());
            let new = residual.row(r) - dir.transpose() * c;
            residual.set_row(r, &new);
        }
    }
    let square = DMat::from_fn(pivots.len(), e, |r, c| basis[(pivots[r], c)]);
    let local = match square.try_inverse() {
        Some(inv) if pivots.len() == e => basis * inv,
        _ => basis.clone(),
    };
    let mut modes: Vec<FloppyMode> = (0..local.ncols())
        .map(|k| {
            let amp: Vec<Real> = (0..n)
                .map(|t| {
                    (0..3)
                        .map(|d| local[(3 * t + d, k)].powi(2))
                        .sum::<Real>()
                        .sqrt()
                })
                .collect();
            let top = amp.iter().copied().fold(0.0, Real::max);
            FloppyMode {
                tiles: (0..n).filter(|&t| amp[t] > MOVER_FRACTION * top).collect(),
                leading: (0..n).filter(|&t| amp[t] >= 0.5 * top).collect(),
            }
        })
        .collect();
    modes.sort_by(|a, b| {
        a.tiles
            .len()
            .cmp(&b.tiles.len())
            .then(a.tiles.cmp(&b.tiles))
    });
    Ok(modes)
}

//! Boundary completion: from a requested region to a sheet that opens with exactly the
//! periodic sheet's one motion.
//!
//! Two candidates are made and the one covering more of the region is kept (the pruned one
//! on a tie, since it adds nothing):
//!
//! - **prune**: repeatedly drop tiles held by fewer than two pins, keep the largest piece,
//!   and drop the tiles that move in extra modes (every mode moving at most half the sheet,
//!   or else the most local one), until the sheet's only motion is the periodic one;
//! - **grow, then prune**: first add the ring of tiles pinned to the region from outside
//!   (they close the linkage loops the region's boundary cut open), then prune.
//!
//! A region that counting tiles and pins alone shows to hold no such sheet is refused before
//! either candidate is tried ([`refusal_by_count`]).
//!
//! The covered fraction is the area of the requested tiles kept over the area of all
//! requested tiles.

use super::error::FiniteError;
use super::mobility::{periodic_velocity, sheet_mobility, SheetMobility};
use super::sheet::{FiniteSheet, SheetTile};
use crate::cell::UnitCell;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};
use crate::stop::KeepGoing;
use serde::Serialize;
use std::collections::HashSet;

/// What completion did.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct CompletionReport {
    /// Tiles the region asked for.
    pub requested: usize,
    /// Of them, tiles kept.
    pub kept: usize,
    /// Requested tiles left out.
    pub removed: Vec<SheetTile>,
    /// Tiles from outside the region added.
    pub added: Vec<SheetTile>,
    /// Area of the requested tiles kept over the area of all requested tiles.
    pub covered_fraction: Real,
    /// True when the kept candidate grew the ring first.
    pub grown: bool,
}

/// A completed sheet and its mobility (one degree of freedom, the periodic motion).
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct Completion {
    /// The completed sheet.
    pub sheet: FiniteSheet,
    /// Its mobility at the state completion was decided at.
    pub mobility: SheetMobility,
    /// What was kept, removed and added.
    pub report: CompletionReport,
}

/// Everything completion needs about the design and the state it decides at.
pub struct Context<'a> {
    /// The design's cell.
    pub cell: &'a UnitCell,
    /// Its mechanism.
    pub mech: &'a Mechanism,
    /// A generic opened state of the periodic sheet.
    pub q: &'a DVec,
    /// The periodic motion at `q` (a state-space vector of `mech`).
    pub motion: &'a DVec,
    /// Smallest covered fraction accepted: a completion that keeps less of the region is
    /// refused (a lone linkage loop is a one-DOF sheet, but not the sheet that was asked for).
    pub min_covered: Real,
    /// Polled before every pruning round and through every count: `false` stops completion with
    /// [`FiniteError::Cancelled`] ([`crate::stop::NEVER`] never stops it).
    pub keep_going: KeepGoing<'a>,
}

impl Context<'_> {
    /// The mobility of `sheet` at the context's state.
    pub fn mobility(&self, sheet: &FiniteSheet) -> Result<SheetMobility, FiniteError> {
        let poses = sheet.poses(self.mech, self.q);
        let periodic = periodic_velocity(sheet, self.mech, self.motion);
        sheet_mobility(sheet, self.mech, &poses, Some(&periodic), self.keep_going)
    }
}

/// Completes the region `requested` (see the module documentation).
pub fn complete(ctx: &Context<'_>, requested: &FiniteSheet) -> Result<Completion, FiniteError> {
    if requested.is_empty() {
        return Err(FiniteError::EmptySheet);
    }
    if let Some(refusal) = refusal_by_count(ctx.cell, ctx.mech, requested, ctx.min_covered) {
        return Err(refusal);
    }
    // The two candidates are independent: made side by side.
    let (pruned, grown) = rayon::join(
        || prune(ctx, requested, requested.clone()),
        || prune(ctx, requested, grow(ctx.cell, ctx.mech, requested)),
    );
    // A stopped candidate stops the whole (the other alone would make the result depend on
    // when the stop came).
    if [&pruned, &grown]
        .iter()
        .any(|c| matches!(c, Err(FiniteError::Cancelled)))
    {
        return Err(FiniteError::Cancelled);
    }
    let chosen = match (pruned, grown) {
        (Ok(p), Ok(g)) => {
            if covered(ctx, requested, &g.0) > covered(ctx, requested, &p.0) {
                (g, true)
            } else {
                (p, false)
            }
        }
        (Ok(p), Err(_)) => (p, false),
        (Err(_), Ok(g)) => (g, true),
        (Err(e), Err(_)) => return Err(explain(ctx.mech, e)),
    };
    let ((sheet, mobility), grown) = chosen;
    let fraction = covered(ctx, requested, &sheet);
    if fraction < ctx.min_covered {
        return Err(explain(
            ctx.mech,
            FiniteError::NoOneDofSheet {
                reason: format!(
                    "the best one-DOF sheet keeps {} of {} tiles ({:.1} % of the region's area, \
                     below the {:.0} % asked for): its boundary keeps flopping as it is pruned",
                    sheet.len(),
                    requested.len(),
                    // Rounded down, so that a share just below the bound never reads as it.
                    (1000.0 * fraction).floor() / 10.0,
                    100.0 * ctx.min_covered
                ),
            },
        ));
    }
    let inside: HashSet<SheetTile> = requested.tiles.iter().copied().collect();
    let kept: HashSet<SheetTile> = sheet.tiles.iter().copied().collect();
    let report = CompletionReport {
        requested: requested.len(),
        kept: sheet.tiles.iter().filter(|t| inside.contains(t)).count(),
        removed: requested
            .tiles
            .iter()
            .filter(|t| !kept.contains(t))
            .copied()
            .collect(),
        added: sheet
            .tiles
            .iter()
            .filter(|t| !inside.contains(t))
            .copied()
            .collect(),
        covered_fraction: fraction,
        grown,
    };
    Ok(Completion {
        sheet,
        mobility,
        report,
    })
}

/// [`complete`] given the region's own mobility at the context's state: a region that already
/// is a one-DOF sheet moving with the periodic sheet (one piece, every tile held by two pins)
/// is its own completion — what [`complete`] would keep, since its pruned candidate covers all
/// of the region and the grown one can only tie — without counting it, or its grown ring,
/// again.
pub fn complete_counted(
    ctx: &Context<'_>,
    requested: &FiniteSheet,
    mobility: &SheetMobility,
) -> Result<Completion, FiniteError> {
    let whole = mobility.dof == 1
        && mobility.follows_periodic
        && mobility.floppy.is_empty()
        && mobility.loose_tiles.is_empty()
        && mobility.pieces == 1
        && !requested.is_empty();
    if !whole {
        return complete(ctx, requested);
    }
    Ok(Completion {
        sheet: requested.clone(),
        mobility: mobility.clone(),
        report: CompletionReport {
            requested: requested.len(),
            kept: requested.len(),
            removed: Vec::new(),
            added: Vec::new(),
            covered_fraction: 1.0,
            grown: false,
        },
    })
}

/// `e` with the design's bulk count added to a refusal when it explains it: a cell whose
/// tiles have as many degrees of freedom as its pins remove (3n = 2p) is isostatic, and
/// every finite sheet of it flops along its boundary.
fn explain(mech: &Mechanism, e: FiniteError) -> FiniteError {
    let FiniteError::NoOneDofSheet { reason } = e else {
        return e;
    };
    let (n, p) = (mech.tile_count(), mech.joints.len());
    let count = 3 * n as i64 - 2 * p as i64;
    let reason = if count >= 0 {
        format!(
            "{reason}; the design's cell has {n} tiles and {p} pins (3n − 2p = {count}: \
             nothing in the bulk is redundant, so every finite sheet flops along its boundary)"
        )
    } else {
        reason
    };
    FiniteError::NoOneDofSheet { reason }
}

/// Area of `requested`'s tiles that `sheet` keeps over the area of all of them.
fn covered(ctx: &Context<'_>, requested: &FiniteSheet, sheet: &FiniteSheet) -> Real {
    let kept: HashSet<SheetTile> = sheet.tiles.iter().copied().collect();
    let areas = requested.areas(ctx.mech);
    let total: Real = areas.iter().sum();
    let inside: Real = requested
        .tiles
        .iter()
        .zip(&areas)
        .filter(|(t, _)| kept.contains(t))
        .map(|(_, a)| a)
        .sum();
    if total > 0.0 {
        inside / total
    } else {
        0.0
    }
}

/// `sheet` with the ring of tiles pinned to it from outside.
fn grow(cell: &UnitCell, mech: &Mechanism, sheet: &FiniteSheet) -> FiniteSheet {
    let inside: HashSet<SheetTile> = sheet.tiles.iter().copied().collect();
    let mut ring = Vec::new();
    for t in &sheet.tiles {
        for joint in &mech.joints {
            let o = cell.edges[joint.edge].offset;
            let partner = if joint.tile_a == t.tile {
                SheetTile {
                    cell: [t.cell[0] + o[0], t.cell[1] + o[1]],
                    tile: joint.tile_b,
                }
            } else if joint.tile_b == t.tile {
                SheetTile {
                    cell: [t.cell[0] - o[0], t.cell[1] - o[1]],
                    tile: joint.tile_a,
                }
            } else {
                continue;
            };
            if !inside.contains(&partner) {
                ring.push(partner);
            }
        }
    }
    FiniteSheet::new(cell, mech, sheet.tiles.iter().copied().chain(ring))
}

/// The refusal of completing `requested` that counting alone proves (no factorisation; see
/// [`super::counting`]): no set of its tiles and the ring around them that keeps
/// `min_covered` of its area has few enough degrees of freedom. Tried only for cells
/// whose bulk has no redundant pin (3n − 2p ≥ 0), where a sheet's free boundary adds
/// degrees of freedom faster than pruning can take them away; elsewhere a large sheet has
/// pins to spare and counting refuses nothing that pruning would not refuse as fast.
pub fn refusal_by_count(
    cell: &UnitCell,
    mech: &Mechanism,
    requested: &FiniteSheet,
    min_covered: Real,
) -> Option<FiniteError> {
    let (n, p) = (mech.tile_count(), mech.joints.len());
    if 3 * n < 2 * p || requested.is_empty() {
        return None;
    }
    let universe = grow(cell, mech, requested);
    let inside: HashSet<SheetTile> = requested.tiles.iter().copied().collect();
    let areas: Vec<Real> = universe
        .areas(mech)
        .into_iter()
        .zip(&universe.tiles)
        .map(|(a, t)| if inside.contains(t) { a } else { 0.0 })
        .collect();
    let total: Real = requested.areas(mech).iter().sum();
    let pins: Vec<(usize, usize)> = universe.joints.iter().map(|j| (j.a, j.b)).collect();
    let least = super::counting::least_dof(&areas, &pins, min_covered * total)?;
    Some(explain(
        mech,
        FiniteError::NoOneDofSheet {
            reason: format!(
                "counting tiles and pins, every sheet of the region and its ring keeping {:.0} % of \
                 it has at least {least} DOF",
                100.0 * min_covered
            ),
        },
    ))
}

/// Prunes `sheet` until its only motion is the periodic one.
///
/// Pruning only removes tiles, so the share of `requested` covered only falls: once it is
/// below the context's smallest accepted share the candidate is given up without pruning on
/// (an isostatic cell's patch would otherwise be peeled round after round down to nothing).
fn prune(
    ctx: &Context<'_>,
    requested: &FiniteSheet,
    mut sheet: FiniteSheet,
) -> Result<(FiniteSheet, SheetMobility), FiniteError> {
    loop {
        if !(ctx.keep_going)() {
            return Err(FiniteError::Cancelled);
        }
        sheet = drop_loose(ctx, sheet);
        if sheet.len() < 2 {
            return Err(FiniteError::NoOneDofSheet {
                reason: "pruning the floppy boundary leaves no tile held by two pins".into(),
            });
        }
        let share = covered(ctx, requested, &sheet);
        if share < ctx.min_covered {
            return Err(FiniteError::NoOneDofSheet {
                reason: format!(
                    "pruning the floppy boundary leaves {} tiles covering {:.1} % of the \
                     region's area, below the {:.0} % asked for, and they still flop",
                    sheet.len(),
                    // Rounded down, so that a share just below the bound never reads as it.
                    (1000.0 * share).floor() / 10.0,
                    100.0 * ctx.min_covered
                ),
            });
        }
        let mobility = ctx.mobility(&sheet)?;
        if !mobility.follows_periodic {
            return Err(FiniteError::NoOneDofSheet {
                reason: format!(
                    "the {} tiles left move rigidly in the periodic motion",
                    sheet.len()
                ),
            });
        }
        if mobility.floppy.is_empty() && mobility.dof == 1 {
            return Ok((sheet, mobility));
        }
        let keep: Vec<bool> = flaps(&mobility).iter().map(|&drop| !drop).collect();
        sheet = sheet.keep(ctx.cell, ctx.mech, &keep);
    }
}

/// The tiles one pruning round drops (flagged per tile): those taking the largest share of
/// the extra modes (ties within 10 %, e.g. the symmetric corners of a rectangle, go
/// together), and with them the flap of every other local extra mode (moving at most half
/// the sheet) whose moving tiles are apart from every mode already taken: its tiles taking
/// the largest share of the extra modes within it (ties within 10 %).
///
/// A round that took only the global top peels one flap at a time, each round a fresh
/// factorisation; where several flaps that share no moving tile are floppy at once they go
/// together (IH44's 10×10 completion: 70 → 37 ms). Flaps apart are independent to first
/// order; over the default exploration's 792 designs the catalogue's 6×6 figures are the same
/// as with one flap per round (587 complete, 410 of them whole, worst share 0.792).
fn flaps(mobility: &SheetMobility) -> Vec<bool> {
    let leverage = &mobility.leverage;
    let n = leverage.len();
    let top = leverage.iter().copied().fold(0.0, Real::max);
    let mut drop: Vec<bool> = leverage
        .iter()
        .map(|&l| top > 0.0 && l >= 0.9 * top)
        .collect();
    // Tiles moving in a mode already taken.
    let mut taken = vec![false; n];
    for mode in &mobility.floppy {
        if mode.tiles.iter().any(|&t| drop[t]) {
            for &t in &mode.tiles {
                taken[t] = true;
            }
        }
    }
    for mode in &mobility.floppy {
        if 2 * mode.tiles.len() > n || mode.tiles.iter().any(|&t| taken[t]) {
            continue;
        }
        let local = mode.tiles.iter().map(|&t| leverage[t]).fold(0.0, Real::max);
        for &t in &mode.tiles {
            taken[t] = true;
            if local > 0.0 && leverage[t] >= 0.9 * local {
                drop[t] = true;
            }
        }
    }
    drop
}

/// `sheet` without tiles held by fewer than two pins (repeatedly) and without every piece
/// but the largest.
fn drop_loose(ctx: &Context<'_>, mut sheet: FiniteSheet) -> FiniteSheet {
    loop {
        let pins = sheet.pins();
        let largest = sheet.in_largest_piece();
        let keep: Vec<bool> = (0..sheet.len())
            .map(|t| pins[t] >= 2 && largest[t])
            .collect();
        if keep.iter().all(|&k| k) {
            return sheet;
        }
        sheet = sheet.keep(ctx.cell, ctx.mech, &keep);
    }
}

//! The smallest patch that keeps a refused print's promises. Every size a printed sheet
//! promises (gap, hinge width, lamella) is fixed in millimetres, while the patch's tiles
//! scale with its mean edge `edge_mm`; so a sheet refused because a slab does not fit on its
//! edge or comes within the gap of another tile or slab fits again at some larger scale. The
//! search lays the sheet out at growing scales (steps of 5 %), then bisects to 0.001 mm of
//! `edge_mm`; it looks only at the plan, never builds a mesh.

use super::error::PrintError;
use super::layout::print_layout;
use super::settings::PrintSettings;
use crate::export::Patch;
use crate::math::Real;
use crate::stop::{KeepGoing, NEVER};

/// Scales tried before giving up: 1.05^60 ≈ 19.
const GROW_STEPS: usize = 60;

/// The smallest `edge_mm` (rounded up to 0.001, from `start` upwards) at which `patch` lays
/// out with `settings`, or `None` when none up to ~19× its size does.
pub fn smallest_edge_mm(patch: &Patch, settings: &PrintSettings, start: Real) -> Option<Real> {
    search(patch, settings, start, NEVER).unwrap_or(None)
}

/// [`smallest_edge_mm`] polling `keep_going` before every layout: `Err(Cancelled)` once it
/// says stop.
fn search(
    patch: &Patch,
    settings: &PrintSettings,
    start: Real,
    keep_going: KeepGoing<'_>,
) -> Result<Option<Real>, PrintError> {
    let base = patch.edge_mm;
    if !(base > 0.0 && start.is_finite()) {
        return Ok(None);
    }
    let fits = |edge: Real| -> Result<bool, PrintError> {
        if !keep_going() {
            return Err(PrintError::Cancelled);
        }
        Ok(print_layout(&scaled(patch, edge / base), settings).is_ok())
    };
    let round = |e: Real| (e * 1000.0).ceil() / 1000.0;
    let mut lo = base;
    let mut hi = round(start.max(base));
    let mut steps = 0;
    while !fits(hi)? {
        steps += 1;
        if steps > GROW_STEPS {
            return Ok(None);
        }
        lo = hi;
        hi = round(hi * 1.05);
    }
    while hi - lo > 1.5e-3 {
        let mid = round(0.5 * (lo + hi));
        if mid >= hi {
            break;
        }
        if fits(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(Some(hi))
}

/// `patch` with every length scaled by `k` (without its deployment frames).
fn scaled(patch: &Patch, k: Real) -> Patch {
    let mut p = patch.clone();
    p.states.clear();
    let scale = |poly: &mut Vec<[Real; 2]>| {
        for v in poly.iter_mut() {
            *v = [v[0] * k, v[1] * k];
        }
    };
    for t in &mut p.tiles {
        scale(&mut t.polygon_mm);
    }
    p.closed_polygons_mm.iter_mut().for_each(scale);
    p.outline_mm.iter_mut().for_each(scale);
    p.edge_mm *= k;
    p.mm_per_unit *= k;
    p.size_mm = [p.size_mm[0] * k, p.size_mm[1] * k];
    p
}

/// `e` with the smallest edge_mm that fits filled in (clashes and slabs too long for their
/// edges); other refusals unchanged; [`PrintError::Cancelled`] when `keep_going` stops the
/// search.
pub(super) fn with_smallest(
    e: PrintError,
    patch: &Patch,
    settings: &PrintSettings,
    keep_going: KeepGoing<'_>,
) -> PrintError {
    let smallest = |start: Real| search(patch, settings, start, keep_going);
    match e {
        PrintError::PatchTooSmall {
            hinge_mm,
            edge_mm,
            min_edge_mm,
            len_mm,
            needed_mm,
            tiles,
        } => match smallest(min_edge_mm) {
            Ok(found) => PrintError::PatchTooSmall {
                hinge_mm,
                edge_mm,
                min_edge_mm: found.unwrap_or(min_edge_mm),
                len_mm,
                needed_mm,
                tiles,
            },
            Err(stopped) => stopped,
        },
        PrintError::HingeClash { tiles, other, .. } => match smallest(patch.edge_mm * 1.05) {
            Ok(min_edge_mm) => PrintError::HingeClash {
                tiles,
                other,
                min_edge_mm,
            },
            Err(stopped) => stopped,
        },
        e => e,
    }
}

//! The last check of a print plan: every lamella slab keeps the gap from every tile but
//! its two and from every other slab, or the plan is refused (never printed fused). Slabs
//! of one pin point (a tile pinned to two others at one vertex) may meet, and may come near
//! every tile pinned there: those tiles turn about that point, so they print as one lamella.

use super::error::PrintError;
use super::separate::{bbox, boxes_within, polygon_distance};
use crate::math::{Real, Vec2};

/// Refuses a slab closer than `gap` to a printed tile other than those pinned at its pin
/// point, or overlapping another slab (closer than `gap` when that slab joins other tiles at
/// another pin point). `pins` numbers every slab's pin point.
pub(super) fn check_clearances(
    tiles: &[Vec<Vec2>],
    hinges: &[(Vec<Vec2>, [usize; 2])],
    pins: &[usize],
    ids: &[usize],
    gap: Real,
) -> Result<(), PrintError> {
    // The tiles pinned at each pin point, collected once.
    let mut at: std::collections::HashMap<usize, Vec<usize>> = std::collections::HashMap::new();
    for ((_, pair), &pin) in hinges.iter().zip(pins) {
        at.entry(pin).or_default().extend(pair);
    }
    // Above the 1e-8 mm grid of the booleans that may have trimmed a tile (`separate`).
    let tol = 1e-7 * (1.0 + gap);
    let tile_boxes: Vec<[Real; 4]> = tiles.iter().map(|p| bbox(p)).collect();
    let hinge_boxes: Vec<[Real; 4]> = hinges.iter().map(|(p, _)| bbox(p)).collect();
    for (h, (slab, pair)) in hinges.iter().enumerate() {
        let at_pin = &at[&pins[h]];
        let near = |b: &[Real; 4]| boxes_within(&hinge_boxes[h], b, gap);
        let clash = |other: String| PrintError::HingeClash {
            tiles: pair.map(|t| ids[t]),
            other,
            min_edge_mm: None,
        };
        for (t, tile) in tiles.iter().enumerate() {
            if at_pin.contains(&t) || !near(&tile_boxes[t]) {
                continue;
            }
            if polygon_distance(slab, tile) < gap - tol {
                return Err(clash(format!("tile {}", ids[t])));
            }
        }
        for (k, (other, other_pair)) in hinges.iter().enumerate().skip(h + 1) {
            if !near(&hinge_boxes[k]) || (pins[k] == pins[h] && other_pair != pair) {
                continue;
            }
            let same_pair = other_pair == pair || *other_pair == [pair[1], pair[0]];
            let limit = if same_pair { tol } else { gap - tol };
            if polygon_distance(slab, other) < limit {
                let named = other_pair.map(|t| ids[t]);
                return Err(clash(format!("the hinge between tiles {named:?}")));
            }
        }
    }
    Ok(())
}

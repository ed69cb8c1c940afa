//! Keeping every two printed tiles at least the gap apart, wherever they are.
//!
//! The per-edge inset ([`super::offset`]) makes two tiles that share an edge exactly `gap`
//! apart along it, but not where the edge ends on the outline at a reflex or slanted
//! stretch: the outline edges stay, so the two tiles' outline edges close in on each other
//! across the narrow notch (issue 23 item 10 measured 0.114–0.233 mm for a 0.4 mm gap,
//! closed). In an opened state, tiles also meet where they never shared an edge, at the
//! contact limit of the deployment (0.12–0.30 mm, item 11). Such pairs fuse in print.
//!
//! So after the inset, tiles are taken in order and each loses what lies within `gap` of an
//! earlier (final) tile closer than `gap`: the earlier tile grown by `gap` (round joins, the
//! arcs' chords pushed out to the full radius) is cut away with a polygon boolean
//! (`manifold-rust`'s Clipper2 cross sections). Every pair then ends at least `gap` apart;
//! tiles that already keep the gap are left exactly as the inset made them. A tile that the
//! cut splits keeps its largest part; one that vanishes is refused.

use super::error::PrintError;
pub(super) use crate::contact::polygon_distance;
use crate::math::{Real, Vec2};
use manifold_rust::cross_section::CrossSection;
use manifold_rust::linalg::Vec2 as MVec2;

/// Segments of the full circle in the grown cutters' round joins.
const ARC_SEGMENTS: i32 = 48;

/// Relative slack: pairs closer than `gap (1 - SLACK)` are separated, and the cutters reach
/// `gap (1 + SLACK)` beyond their arcs' chords.
const SLACK: Real = 1e-7;

/// `tiles` (counter-clockwise, mm; `ids` their patch ids, for messages) with every two at
/// least `gap` apart. Returns how many tiles were cut.
pub fn separate_tiles(
    tiles: &mut [Vec<Vec2>],
    ids: &[usize],
    gap: Real,
) -> Result<usize, PrintError> {
    let boxes: Vec<[Real; 4]> = tiles.iter().map(|p| bbox(p)).collect();
    let limit = gap * (1.0 - SLACK);
    let mut cut = 0;
    for i in 0..tiles.len() {
        let near: Vec<usize> = (0..i)
            .filter(|&j| boxes_within(&boxes[i], &boxes[j], gap))
            .filter(|&j| polygon_distance(&tiles[i], &tiles[j]) < limit)
            .collect();
        if near.is_empty() {
            continue;
        }
        // The chords of a round join of radius r lie r cos(π/n) from the corner.
        let grow = gap * (1.0 + SLACK) / (std::f64::consts::PI / ARC_SEGMENTS as Real).cos();
        let cutters = near.iter().fold(CrossSection::default(), |acc, &j| {
            acc.union(&section(&tiles[j]).offset_with_params(grow, 1, 2.0, ARC_SEGMENTS))
        });
        let rest = section(&tiles[i]).difference(&cutters);
        let gone = |problem: &str| PrintError::GapTooWide {
            gap_mm: gap,
            tile: ids[i],
            problem: problem.to_string(),
        };
        let part = rest
            .decompose()
            .into_iter()
            .filter(|p| !p.is_empty())
            .max_by(|a, b| a.area().total_cmp(&b.area()))
            .ok_or_else(|| gone("it vanishes where other tiles come within the gap"))?;
        let contours = part.to_polygons();
        if contours.len() != 1 {
            return Err(gone("keeping the gap to other tiles would hole it"));
        }
        // The booleans snap to a 1e-8 mm grid: vertices the cut left are put back exactly.
        let snap = 1e-7 * (1.0 + gap);
        let old = std::mem::take(&mut tiles[i]);
        let mut poly: Vec<Vec2> = Vec::with_capacity(contours[0].len());
        for p in &contours[0] {
            let p = Vec2::new(p.x, p.y);
            let p = old
                .iter()
                .copied()
                .find(|q| (q - p).norm() <= snap)
                .unwrap_or(p);
            if poly.last().is_none_or(|q| (q - p).norm() > snap) {
                poly.push(p);
            }
        }
        while poly.len() > 1 && (poly[0] - poly[poly.len() - 1]).norm() <= snap {
            poly.pop();
        }
        if poly.len() < 3 {
            return Err(gone("it vanishes where other tiles come within the gap"));
        }
        tiles[i] = poly;
        cut += 1;
    }
    Ok(cut)
}

fn section(poly: &[Vec2]) -> CrossSection {
    CrossSection::new(vec![poly.iter().map(|p| MVec2::new(p.x, p.y)).collect()])
}

/// [min x, min y, max x, max y].
pub(super) fn bbox(p: &[Vec2]) -> [Real; 4] {
    p.iter().fold(
        [
            Real::INFINITY,
            Real::INFINITY,
            Real::NEG_INFINITY,
            Real::NEG_INFINITY,
        ],
        |b, v| [b[0].min(v.x), b[1].min(v.y), b[2].max(v.x), b[3].max(v.y)],
    )
}

/// Boxes `a` and `b` come within `d` of each other.
pub(super) fn boxes_within(a: &[Real; 4], b: &[Real; 4], d: Real) -> bool {
    a[0] <= b[2] + d && b[0] <= a[2] + d && a[1] <= b[3] + d && b[1] <= a[3] + d
}

#[cfg(test)]
mod tests {
    use super::super::offset::inset_edges;
    use super::*;
    use crate::geometry::signed_area;
    use crate::math::vec2;

    /// The notch of issue 23 item 10: tiles A (103° at V) and B (221°, reflex) share the
    /// edge below V on the outline, their outline edges 36° apart. B's outline edge runs on
    /// through V after the inset, so A's inset corner is only 0.121 mm from it (gap 0.4).
    #[test]
    fn a_notch_at_a_reflex_outline_corner_is_opened_to_the_gap() {
        let dir = |deg: Real| vec2(deg.to_radians().cos(), deg.to_radians().sin()) * 10.0;
        let a = vec![
            vec2(-10.0, -10.0),
            vec2(0.0, -10.0),
            vec2(0.0, 0.0),
            dir(167.0),
        ];
        let b = vec![
            vec2(0.0, 0.0),
            vec2(0.0, -10.0),
            vec2(10.0, -10.0),
            vec2(10.0, 10.0),
            dir(131.0),
        ];
        let a = inset_edges(&a, &[0.0, 0.2, 0.0, 0.0]).unwrap();
        let b = inset_edges(&b, &[0.2, 0.0, 0.0, 0.0, 0.0]).unwrap();
        let before = polygon_distance(&a, &b);
        assert!((before - 0.121).abs() < 2e-3, "{before}");
        let mut tiles = vec![a.clone(), b.clone()];
        assert_eq!(separate_tiles(&mut tiles, &[0, 1], 0.4).unwrap(), 1);
        assert_eq!(tiles[0], a, "the first tile stays");
        let after = polygon_distance(&tiles[0], &tiles[1]);
        assert!(after >= 0.4 * (1.0 - 1e-6), "{after}");
        // Only a sliver near the notch goes: the far side of the slot keeps its gap exactly.
        assert!(signed_area(&tiles[1]) > signed_area(&b) - 1.0);
        assert!(after < 0.4 * (1.0 + 1e-3), "{after}");
    }

    #[test]
    fn tiles_a_gap_apart_are_left_alone() {
        let sq = |x: Real| {
            vec![
                vec2(x, 0.0),
                vec2(x + 1.0, 0.0),
                vec2(x + 1.0, 1.0),
                vec2(x, 1.0),
            ]
        };
        let mut tiles = vec![sq(0.0), sq(1.4)];
        assert_eq!(separate_tiles(&mut tiles, &[0, 1], 0.4).unwrap(), 0);
        assert_eq!(tiles[1], sq(1.4));
        let mut close = vec![sq(0.0), sq(1.1)];
        assert_eq!(separate_tiles(&mut close, &[0, 1], 0.4).unwrap(), 1);
        assert!(polygon_distance(&close[0], &close[1]) >= 0.4 * (1.0 - 1e-6));
    }
}

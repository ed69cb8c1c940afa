//! How near a graded sheet comes to its target, measured over its whole opened boundary.
//!
//! The fit ([`super::problem`]) pulls one corner per boundary tile (its *tip*) onto the target;
//! these measures judge the whole outline instead:
//!
//! - the sheet's **outline** is the polygon through the tips in the order the closed sheet's
//!   outer boundary meets them (what the eye sees as the opened sheet's edge: the bays between
//!   two tiles' tips, where the pattern itself opens, are bridged);
//! - its distance to the target is taken both ways, every outline segment against the target
//!   and every stretch of the target against the outline; the length-weighted mean of the
//!   outline's is the **mean**;
//! - **outside** is the farthest any material of the sheet (every edge of its outer boundary,
//!   not only tips) lies outside the target; **inside** the deepest the outline lies inside;
//! - the **Hausdorff** distance is the largest of all of these: the outline either way, and
//!   any material outside;
//! - every figure is relative to the target's equivalent radius, √(area/π).
//!
//! A field target is judged by its cells' area ratios beside the whole sheet's opening (its
//! outer boundary's opened area over its closed area).

use super::model::GradedSheet;
use crate::geometry::{point_in_polygon_strict, point_segment_distance, signed_area};
use crate::math::{cross, Real, Vec2};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// Points per outline or target segment, at least: distances are taken at these.
const SAMPLES_PER_SEGMENT: usize = 8;

/// The opened outline against the target outline (relative to the target's equivalent
/// radius).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OutlineFit {
    /// Largest distance between the outline and the target, either way, or of any material
    /// outside the target.
    pub hausdorff: Real,
    /// Mean distance of the outline from the target, weighted by length.
    pub mean: Real,
    /// Deepest the outline lies inside the target.
    pub inside: Real,
    /// Farthest any boundary edge of the opened sheet lies outside the target.
    pub outside: Real,
    /// The target's equivalent radius √(area/π), in the sheet's length units.
    pub radius: Real,
    /// Where the Hausdorff distance is reached (the opened sheet's units): the outline or
    /// boundary point farthest from the target, or the target point farthest from the
    /// outline.
    pub worst: [Real; 2],
}

/// The closed sheet's outer boundary, walked with the sheet on its left: every boundary edge
/// as (tile, corner index of its start). At a node where the sheet touches itself the walk
/// takes the rightmost turn, so it stays on the outside; of several boundary cycles (a sheet
/// with holes) the one enclosing the most area.
pub fn outer_boundary(sheet: &GradedSheet) -> Vec<(usize, usize)> {
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for t in &sheet.tiles {
        let m = t.nodes.len();
        for v in 0..m {
            let (p, q) = (t.nodes[v], t.nodes[(v + 1) % m]);
            *count.entry((p.min(q), p.max(q))).or_default() += 1;
        }
    }
    let mut edges: Vec<(usize, usize)> = Vec::new();
    let mut from: HashMap<usize, Vec<usize>> = HashMap::new();
    for (i, t) in sheet.tiles.iter().enumerate() {
        let m = t.nodes.len();
        for v in 0..m {
            let (p, q) = (t.nodes[v], t.nodes[(v + 1) % m]);
            if count[&(p.min(q), p.max(q))] == 1 {
                from.entry(p).or_default().push(edges.len());
                edges.push((i, v));
            }
        }
    }
    let ends = |e: usize| {
        let (i, v) = edges[e];
        let t = &sheet.tiles[i].nodes;
        (t[v], t[(v + 1) % t.len()])
    };
    let mut used = vec![false; edges.len()];
    let mut best: (Real, Vec<(usize, usize)>) = (Real::NEG_INFINITY, Vec::new());
    for first in 0..edges.len() {
        if used[first] {
            continue;
        }
        let mut cycle = Vec::new();
        let mut e = first;
        while !used[e] {
            used[e] = true;
            cycle.push(edges[e]);
            let (p, q) = ends(e);
            let incoming = sheet.node(q) - sheet.node(p);
            let next = from.get(&q).and_then(|out| {
                out.iter()
                    .copied()
                    .filter(|&o| !used[o] || o == first)
                    .min_by(|&a, &b| {
                        let turn = |o: usize| {
                            let d = sheet.node(ends(o).1) - sheet.node(q);
                            cross(&incoming, &d).atan2(incoming.dot(&d))
                        };
                        turn(a).total_cmp(&turn(b))
                    })
            });
            match next {
                Some(o) => e = o,
                None => break,
            }
        }
        let poly: Vec<Vec2> = cycle
            .iter()
            .map(|&(i, v)| sheet.node(sheet.tiles[i].nodes[v]))
            .collect();
        let area = signed_area(&poly);
        if area > best.0 {
            best = (area, cycle);
        }
    }
    best.1
}

/// The outline through `tips` (tile, node) in the order of the outer boundary `cycle`, opened:
/// tips not on the outer boundary are left out.
pub fn tip_outline(
    sheet: &GradedSheet,
    cycle: &[(usize, usize)],
    tips: &[(usize, usize)],
) -> Vec<Vec2> {
    let tip_of: HashMap<(usize, usize), ()> = tips.iter().map(|&t| (t, ())).collect();
    let mut out: Vec<Vec2> = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for &(i, v) in cycle {
        let t = &sheet.tiles[i].nodes;
        for n in [t[v], t[(v + 1) % t.len()]] {
            if tip_of.contains_key(&(i, n)) && seen.insert((i, n)) {
                out.push(sheet.opened_corner(i, n));
            }
        }
    }
    out
}

/// The opened outer boundary: every edge of `cycle` at its tile's opened pose (consecutive
/// edges of two tiles that part as the sheet opens are joined by a straight bridge).
pub fn opened_boundary(sheet: &GradedSheet, cycle: &[(usize, usize)]) -> Vec<Vec2> {
    let mut out = Vec::with_capacity(2 * cycle.len());
    for &(i, v) in cycle {
        let t = &sheet.tiles[i].nodes;
        out.push(sheet.opened_corner(i, t[v]));
        out.push(sheet.opened_corner(i, t[(v + 1) % t.len()]));
    }
    out
}

/// The whole sheet's opening: the area its opened outer boundary encloses over the area of
/// the closed one.
pub fn sheet_opening(sheet: &GradedSheet, cycle: &[(usize, usize)]) -> Real {
    let closed: Vec<Vec2> = cycle
        .iter()
        .map(|&(i, v)| sheet.node(sheet.tiles[i].nodes[v]))
        .collect();
    signed_area(&opened_boundary(sheet, cycle)) / signed_area(&closed)
}

/// Points along every segment of the closed polygon `poly`, with the length each stands for.
fn samples(poly: &[Vec2], step: Real) -> Vec<(Vec2, Real)> {
    let n = poly.len();
    let mut out = Vec::new();
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        let len = (b - a).norm();
        let pieces = ((len / step).ceil() as usize).clamp(SAMPLES_PER_SEGMENT, 10_000);
        for s in 0..pieces {
            out.push((
                a + (b - a) * (s as Real / pieces as Real),
                len / pieces as Real,
            ));
        }
    }
    out
}

/// Distance from `p` to the boundary of the closed polygon `poly`.
fn distance_to(p: &Vec2, poly: &[Vec2]) -> Real {
    let n = poly.len();
    (0..n)
        .map(|k| point_segment_distance(p, &poly[k], &poly[(k + 1) % n]))
        .fold(Real::INFINITY, Real::min)
}

/// Signed distance from `p` to the boundary of `poly`: positive outside.
fn signed_distance(p: &Vec2, poly: &[Vec2]) -> Real {
    let d = distance_to(p, poly);
    if point_in_polygon_strict(p, poly, 0.0) {
        -d
    } else {
        d
    }
}

/// `outline` (the tip outline) and the opened `boundary` measured against `target` (all in
/// the sheet's units, the same centre); None when either outline has fewer than three points.
pub fn outline_fit(outline: &[Vec2], boundary: &[Vec2], target: &[Vec2]) -> Option<OutlineFit> {
    if outline.len() < 3 || target.len() < 3 {
        return None;
    }
    let radius = (signed_area(target).abs() / std::f64::consts::PI).sqrt();
    let step = radius / 200.0;
    let mut sum = 0.0;
    let mut length = 0.0;
    let (mut inside, mut outward): (Real, Real) = (0.0, 0.0);
    let mut worst = (0.0, outline[0]);
    let mut farther = |d: Real, p: Vec2| {
        if d > worst.0 {
            worst = (d, p);
        }
    };
    for (p, w) in samples(outline, step) {
        let d = signed_distance(&p, target);
        sum += d.abs() * w;
        length += w;
        inside = inside.max(-d);
        outward = outward.max(d);
        farther(d.abs(), p);
    }
    for (p, _) in samples(target, step) {
        farther(distance_to(&p, outline), p);
    }
    let mut outside: Real = 0.0;
    for (p, _) in samples(boundary, step) {
        let d = signed_distance(&p, target);
        outside = outside.max(d);
        farther(d, p);
    }
    Some(OutlineFit {
        hausdorff: worst.0 / radius,
        mean: sum / length.max(1e-300) / radius,
        inside: inside / radius,
        outside: outside / radius,
        radius,
        worst: [worst.1.x, worst.1.y],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle(r: Real, n: usize, phase: Real) -> Vec<Vec2> {
        (0..n)
            .map(|k| {
                let a = phase + std::f64::consts::TAU * k as Real / n as Real;
                Vec2::new(r * a.cos(), r * a.sin())
            })
            .collect()
    }

    /// A circle measured against itself is 0 off; against one 10 % larger, 10 % inside
    /// both ways (Hausdorff and mean, to the polygons' sagitta); a square's corners poke out
    /// of its inscribed circle by √2 − 1 of its radius.
    #[test]
    fn known_outlines_measure_their_known_distances() {
        let target = circle(1.0, 512, 0.0);
        let same = outline_fit(&target, &target, &target).unwrap();
        assert!(same.hausdorff < 1e-12 && same.mean < 1e-12 && same.outside < 1e-12);
        let small = circle(1.0 / 1.1, 512, 0.0);
        let fit = outline_fit(&small, &small, &target).unwrap();
        let want = 1.0 - 1.0 / 1.1;
        assert!((fit.hausdorff - want).abs() < 1e-3, "{fit:?}");
        assert!((fit.mean - want).abs() < 1e-3 && (fit.inside - want).abs() < 1e-3);
        assert_eq!(fit.outside, 0.0);
        let square = circle(2f64.sqrt(), 4, std::f64::consts::FRAC_PI_4);
        let fit = outline_fit(&square, &square, &target).unwrap();
        let radius = (signed_area(&target) / std::f64::consts::PI).sqrt();
        let out = (2f64.sqrt() - 1.0) / radius;
        assert!((fit.outside - out).abs() < 1e-3, "{fit:?}");
        assert!((fit.hausdorff - out).abs() < 1e-3, "{fit:?}");
    }

    /// A target with a thin spike, against the square it grows from: every point of the
    /// square lies within the spike's half-width of the target, but the spike's tip is its
    /// length away from the square. Only the target-to-outline direction sees what no tip
    /// reaches.
    #[test]
    fn a_target_left_uncovered_is_measured_from_the_target() {
        let (w, len) = (0.01, 1.0);
        let pts = |v: &[(Real, Real)]| v.iter().map(|&(x, y)| Vec2::new(x, y)).collect::<Vec<_>>();
        let target = pts(&[
            (-1.0, -1.0),
            (1.0, -1.0),
            (1.0, 1.0),
            (w, 1.0),
            (w, 1.0 + len),
            (-w, 1.0 + len),
            (-w, 1.0),
            (-1.0, 1.0),
        ]);
        let square = pts(&[(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]);
        let fit = outline_fit(&square, &square, &target).unwrap();
        let radius = (signed_area(&target) / std::f64::consts::PI).sqrt();
        assert!(
            fit.inside * radius <= w * (1.0 + 1e-9) && fit.outside < 1e-12,
            "{fit:?}"
        );
        assert!((fit.hausdorff * radius - len).abs() < 1e-9, "{fit:?}");
    }
}

//! The linkages of a design over its closed sheet (paper Fig. 6): the 3×3 patch of cells drawn
//! faintly, one unit cell of linkages drawn as closed loops through their joints and coloured
//! by bar count, with a legend.

use super::svg::SvgDoc;
use crate::cell::UnitCell;
use crate::linkage::{Linkage, LinkageAnalysis};
use crate::math::{Real, Vec2};
use crate::topology::JointChoice;
use std::collections::BTreeMap;

/// Colour of a linkage with `bars` bars, as in the paper's Fig. 6 (others grey).
pub fn linkage_colour(bars: usize) -> &'static str {
    match bars {
        4 => "#7b2cbf",
        5 => "#e9c400",
        6 => "#f77f00",
        8 => "#2b9348",
        10 => "#1d6fd6",
        _ => "#7f7f7f",
    }
}

/// SVG of the linkages in `analysis` (computed for `cell` and `joints`) over the closed sheet.
/// Pins of the design are marked as small dots; an inconsistent `joints` list only loses them.
pub fn linkage_svg(cell: &UnitCell, joints: &[JointChoice], analysis: &LinkageAnalysis) -> String {
    let l = cell.mean_edge_length();
    let mut doc = SvgDoc::default();
    let (mut lo, mut hi) = (
        Vec2::repeat(Real::INFINITY),
        Vec2::repeat(Real::NEG_INFINITY),
    );
    for ku in -1..=1 {
        for kw in -1..=1 {
            for i in 0..cell.tiles.len() {
                let poly = cell.tile_polygon_at(i, [ku, kw]);
                for p in &poly {
                    lo = lo.inf(p);
                    hi = hi.sup(p);
                }
                let opacity = if ku == 0 && kw == 0 { 0.9 } else { 0.45 };
                doc.polygon(
                    &poly,
                    &format!(
                        r##"fill="#ececec" fill-opacity="{opacity}" stroke="#9a9a9a" stroke-width="{:.5}""##,
                        0.012 * l
                    ),
                );
            }
            for (k, choice) in joints.iter().enumerate().take(cell.edges.len()) {
                for &end in choice.ends() {
                    let p = cell.endpoint(k, end) + cell.offset_vector([ku, kw]);
                    doc.circle(&p, 0.035 * l, r##"fill="#555""##);
                }
            }
        }
    }
    for linkage in &analysis.linkages {
        draw_linkage(&mut doc, cell, linkage, l);
    }
    if lo.x.is_finite() {
        legend(&mut doc, analysis, lo, hi, l);
    }
    let title = format!(
        "{} {:?} cell {}: {}",
        cell.family, cell.params, cell.dims, analysis.signature
    );
    doc.finish(0.3 * l, 900.0, &title)
}

/// One linkage: a translucent star through tile centroids and joints, and the loop of bars
/// through its joints.
fn draw_linkage(doc: &mut SvgDoc, cell: &UnitCell, linkage: &Linkage, l: Real) {
    let colour = linkage_colour(linkage.bars);
    let valid = linkage.nodes.iter().all(|n| n.0 < cell.tiles.len())
        && linkage.joints.iter().all(|j| j.edge < cell.edges.len());
    if !valid || linkage.nodes.len() != linkage.joints.len() {
        return;
    }
    let joint_pts: Vec<Vec2> = linkage
        .joints
        .iter()
        .map(|j| cell.endpoint(j.edge, j.end) + cell.offset_vector(j.cell))
        .collect();
    let k = joint_pts.len();
    let star: Vec<Vec2> = (0..k)
        .flat_map(|i| {
            let (t, c) = linkage.nodes[(i + 1) % k];
            [joint_pts[i], cell.tiles[t].centroid + cell.offset_vector(c)]
        })
        .collect();
    doc.polygon(
        &star,
        &format!(r#"fill="{colour}" fill-opacity="0.22" stroke="none""#),
    );
    doc.polygon(
        &joint_pts,
        &format!(
            r#"fill="none" stroke="{colour}" stroke-width="{:.5}" stroke-linejoin="round""#,
            0.06 * l
        ),
    );
    for p in &joint_pts {
        doc.circle(
            p,
            0.07 * l,
            &format!(
                r#"fill="{colour}" stroke="black" stroke-width="{:.5}""#,
                0.01 * l
            ),
        );
    }
}

/// Swatches with "n× k-bar" below the patch.
fn legend(doc: &mut SvgDoc, analysis: &LinkageAnalysis, lo: Vec2, hi: Vec2, l: Real) {
    let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
    for lk in &analysis.linkages {
        *counts.entry(lk.bars).or_insert(0) += 1;
    }
    let size = 0.35 * l * ((hi.x - lo.x) / (6.0 * l)).clamp(1.0, 4.0);
    let y = lo.y - 1.2 * size;
    let mut x = lo.x;
    if counts.is_empty() {
        doc.text(
            &Vec2::new(x + 3.0 * size, y),
            size,
            "no linkages",
            r##"fill="#333""##,
        );
        return;
    }
    for (bars, n) in counts {
        let colour = linkage_colour(bars);
        doc.polygon(
            &[
                Vec2::new(x, y - 0.4 * size),
                Vec2::new(x + 0.8 * size, y - 0.4 * size),
                Vec2::new(x + 0.8 * size, y + 0.4 * size),
                Vec2::new(x, y + 0.4 * size),
            ],
            &format!(
                r#"fill="{colour}" stroke="black" stroke-width="{:.5}""#,
                0.02 * l
            ),
        );
        let label = format!("{n}× {bars}-bar");
        let width = 0.6 * size * label.chars().count() as Real;
        doc.text(
            &Vec2::new(x + size + 0.5 * width, y),
            size,
            &label,
            r##"fill="#222""##,
        );
        x += 1.6 * size + width;
    }
}

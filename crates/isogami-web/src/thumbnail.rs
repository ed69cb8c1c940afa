//! Catalogue thumbnails: a small patch of the sheet closed (left) and at its largest opening
//! (right), as SVG, drawn from a design view's geometry and report frames.

use crate::view::DesignView;
use isogami::api::SheetGeometry;
use isogami::deploy::FrameReport;
use std::fmt::Write;

/// Cells per side of the thumbnail patch.
const PATCH: i32 = 3;
/// Size of one panel in pixels.
const PANEL: f64 = 120.0;
/// Gap between and around the panels.
const PAD: f64 = 6.0;
/// Tile fills, one per tile of the cell (cycled).
const FILLS: [&str; 6] = [
    "#8ecae6", "#ffb703", "#90be6d", "#f4a3a8", "#cdb4db", "#a8dadc",
];

/// Every tile polygon of a `PATCH`×`PATCH` patch at `frame`, with its tile index.
pub fn patch_polygons(
    g: &SheetGeometry,
    frame: &FrameReport,
    n: i32,
) -> Vec<(usize, Vec<[f64; 2]>)> {
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (fi, fj) = (f64::from(i), f64::from(j));
            let sx = fi * frame.u[0] + fj * frame.w[0];
            let sy = fi * frame.u[1] + fj * frame.w[1];
            for (k, (shape, pose)) in g.tiles.iter().zip(&frame.tiles).enumerate() {
                let (s, c) = pose.theta.sin_cos();
                let poly = shape
                    .iter()
                    .map(|p| {
                        [
                            pose.x + c * p[0] - s * p[1] + sx,
                            pose.y + s * p[0] + c * p[1] + sy,
                        ]
                    })
                    .collect();
                out.push((k, poly));
            }
        }
    }
    out
}

/// The frame with the largest area ratio (the last one on a tie).
fn most_open(frames: &[FrameReport]) -> Option<&FrameReport> {
    frames
        .iter()
        .rev()
        .max_by(|a, b| a.measures.area_ratio.total_cmp(&b.measures.area_ratio))
}

/// The thumbnail SVG of a design view.
pub fn thumbnail_svg(view: &DesignView) -> String {
    let frames = &view.report.frames;
    let width = 2.0 * PANEL + 3.0 * PAD;
    let height = PANEL + 2.0 * PAD;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {width} {height}\">\
         <title>{}</title><rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>",
        escape(&view.spec)
    );
    let panels = [frames.first(), most_open(frames)];
    for (p, frame) in panels.iter().enumerate() {
        let Some(frame) = frame else { continue };
        let polys = patch_polygons(&view.geometry, frame, PATCH);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (_, poly) in &polys {
            for v in poly {
                for d in 0..2 {
                    lo[d] = lo[d].min(v[d]);
                    hi[d] = hi[d].max(v[d]);
                }
            }
        }
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if !(span.is_finite() && span > 0.0) {
            continue;
        }
        let scale = PANEL / span;
        let x0 = PAD + p as f64 * (PANEL + PAD) + 0.5 * (PANEL - scale * (hi[0] - lo[0]));
        let y0 = PAD + 0.5 * (PANEL + scale * (hi[1] - lo[1]));
        for (k, poly) in &polys {
            let _ = write!(
                svg,
                "<polygon fill=\"{}\" stroke=\"#333\" stroke-width=\"0.6\" points=\"",
                FILLS[k % FILLS.len()]
            );
            for v in poly {
                let _ = write!(
                    svg,
                    "{:.2},{:.2} ",
                    x0 + scale * (v[0] - lo[0]),
                    y0 - scale * (v[1] - lo[1])
                );
            }
            svg.push_str("\"/>");
        }
    }
    svg.push_str("</svg>");
    svg
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

//! Plots of expansion measures as SVG text (plotters' SVG backend, no system libraries).
//!
//! Inputs are checked first: a NaN or infinity is an error naming the series and sample,
//! never a broken SVG.

use super::error::{RenderError, RenderResult};
use crate::math::Real;
use plotters::prelude::*;
use std::f64::consts::TAU;

const MAX_COLOUR: RGBColor = RGBColor(0xd6, 0x28, 0x28);
const MIN_COLOUR: RGBColor = RGBColor(0x00, 0x77, 0xb6);
const CURVES: [RGBColor; 6] = [
    RGBColor(0xd6, 0x28, 0x28),
    RGBColor(0x00, 0x77, 0xb6),
    RGBColor(0x2a, 0x9d, 0x48),
    RGBColor(0xe0, 0x8e, 0x0b),
    RGBColor(0x7b, 0x2c, 0xbf),
    RGBColor(0x44, 0x44, 0x44),
];
const FONT: &str = "sans-serif";

/// plotters rounds coordinates to whole backend pixels; drawing on a canvas SS times larger
/// and declaring the nominal size (the viewBox keeps the drawing) hides the rounding wobble.
const SS: u32 = 4;

/// `v` nominal pixels in backend pixels.
fn px(v: u32) -> u32 {
    v * SS
}

/// Declares the nominal size `w`×`h` for a canvas drawn SS times larger.
fn nominal_size(svg: String, w: u32, h: u32) -> String {
    let big = format!(r#"<svg width="{}" height="{}" "#, px(w), px(h));
    let small = format!(r#"<svg width="{w}" height="{h}" "#);
    svg.replacen(&big, &small, 1)
}

fn plot_err<E: std::fmt::Display>(e: E) -> RenderError {
    RenderError::Plot(e.to_string())
}

fn check_finite(series: &'static str, values: &[Real]) -> RenderResult<()> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(RenderError::NotFinite {
            series,
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

fn finish(svg: String, w: u32, h: u32) -> Result<String, RenderError> {
    let svg = nominal_size(svg, w, h);
    if !svg.starts_with(&format!(r#"<svg width="{w}" height="{h}" "#)) {
        return Err(plot_err("unexpected SVG header from plotters"));
    }
    // Belt and braces: inputs are checked, but a non-finite coordinate must never escape.
    if svg.contains("NaN") || svg.contains("=\"inf") || svg.contains("=\"-inf") {
        return Err(plot_err("a non-finite coordinate in the SVG"));
    }
    Ok(svg)
}

/// Range `lo..hi` padded by 8% (at least ±0.05 around a flat series).
fn padded(lo: Real, hi: Real) -> (Real, Real) {
    let span = (hi - lo).max(0.1);
    let mid = 0.5 * (hi + lo);
    let half = 0.5 * span * 1.08;
    (mid - half, mid + half)
}

/// Minimum and maximum principal expansion versus the deployment parameter t, 800×500 px.
///
/// `t`, `min` and `max` must have the same, non-zero length and hold finite numbers. The
/// t axis spans [0, 1] (wider if some t lies outside); the expansion axis includes 0.
pub fn expansion_plot_svg(
    t: &[Real],
    min: &[Real],
    max: &[Real],
    title: &str,
) -> Result<String, RenderError> {
    if t.is_empty() || t.len() != min.len() || t.len() != max.len() {
        return Err(RenderError::SeriesLengths {
            t: t.len(),
            min: min.len(),
            max: max.len(),
        });
    }
    check_finite("t", t)?;
    check_finite("min", min)?;
    check_finite("max", max)?;
    let fold =
        |v: &[Real], lo: Real, hi: Real| v.iter().fold((lo, hi), |(a, b), &x| (a.min(x), b.max(x)));
    let (t0, t1) = fold(t, 0.0, 1.0);
    let (y0, y1) = fold(max, 0.0, 0.0);
    let (y0, y1) = fold(min, y0, y1);
    let (y0, y1) = padded(y0, y1);

    const W: u32 = 800;
    const H: u32 = 500;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (px(W), px(H))).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, (FONT, px(24)))
            .margin(px(18))
            .x_label_area_size(px(50))
            .y_label_area_size(px(70))
            .build_cartesian_2d(t0..t1, y0..y1)
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .x_desc("deployment parameter t")
            .y_desc("principal expansion ε")
            .axis_desc_style((FONT, px(18)))
            .label_style((FONT, px(14)))
            .light_line_style(RGBColor(0xee, 0xee, 0xee).stroke_width(px(1)))
            .bold_line_style(RGBColor(0xcc, 0xcc, 0xcc).stroke_width(px(1)))
            .max_light_lines(4)
            .axis_style(BLACK.stroke_width(px(1)))
            .set_all_tick_mark_size(px(5))
            .draw()
            .map_err(plot_err)?;
        chart
            .draw_series(LineSeries::new(
                [(t0, 0.0), (t1, 0.0)],
                BLACK.mix(0.4).stroke_width(px(1)),
            ))
            .map_err(plot_err)?;
        // The max curve is drawn wider and first, so that both stay visible where they
        // coincide (isotropic sheets).
        for (values, colour, width, label) in [
            (max, MAX_COLOUR, px(5), "max expansion ε_max"),
            (min, MIN_COLOUR, px(2), "min expansion ε_min"),
        ] {
            let points = t.iter().copied().zip(values.iter().copied());
            chart
                .draw_series(LineSeries::new(points, colour.stroke_width(width)))
                .map_err(plot_err)?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(
                        vec![(x, y), (x + px(24) as i32, y)],
                        colour.stroke_width(width),
                    )
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .margin(px(12))
            .legend_area_size(px(30))
            .label_font((FONT, px(16)))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.5).stroke_width(px(1)))
            .draw()
            .map_err(plot_err)?;
        root.present().map_err(plot_err)?;
    }
    finish(svg, W, H)
}

/// Polar plot of directional expansion profiles: for each `(label, [(θ, ε(θ))])` the curve
/// at radius r(θ) = 1 + ε(θ) (closed), with the unit circle (the closed sheet) for
/// reference, a polar grid, equal aspect ratio, 640×640 px. Every θ and ε must be finite,
/// every profile non-empty and every radius 1 + ε non-negative.
pub fn polar_plot_svg<S: AsRef<str>>(
    profiles: &[(S, Vec<(Real, Real)>)],
) -> Result<String, RenderError> {
    let mut curves = Vec::with_capacity(profiles.len());
    let mut r_max: Real = 1.0;
    for (label, samples) in profiles {
        let label = label.as_ref();
        if samples.is_empty() {
            return Err(RenderError::EmptyProfile {
                label: label.to_string(),
            });
        }
        let mut pts = Vec::with_capacity(samples.len() + 1);
        for (i, &(theta, eps)) in samples.iter().enumerate() {
            if !theta.is_finite() || !eps.is_finite() {
                return Err(RenderError::ProfileNotFinite {
                    label: label.to_string(),
                    index: i,
                    theta,
                    eps,
                });
            }
            let r = 1.0 + eps;
            if r < 0.0 {
                return Err(RenderError::NegativeRadius {
                    label: label.to_string(),
                    index: i,
                    radius: r,
                });
            }
            r_max = r_max.max(r);
            pts.push((r * theta.cos(), r * theta.sin()));
        }
        pts.push(pts[0]);
        curves.push((label.to_string(), pts));
    }
    let step = grid_step(r_max);
    let extent = 1.12 * r_max;

    const W: u32 = 640;
    const H: u32 = 640;
    let mut svg = String::new();
    {
        // Square canvas, equal margins and label areas on both axes: the plotting area is
        // square and both axes span the same range, so circles stay circles.
        let root = SVGBackend::with_string(&mut svg, (px(W), px(H))).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        let mut chart = ChartBuilder::on(&root)
            .margin(px(16))
            .x_label_area_size(px(48))
            .y_label_area_size(px(48))
            .build_cartesian_2d(-extent..extent, -extent..extent)
            .map_err(plot_err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .axis_style(BLACK.stroke_width(px(1)))
            .set_all_tick_mark_size(px(5))
            .x_desc("r cos θ")
            .y_desc("r sin θ")
            .axis_desc_style((FONT, px(16)))
            .label_style((FONT, px(13)))
            .draw()
            .map_err(plot_err)?;
        // Polar grid: circles every `step`, spokes every 30°.
        let grey = RGBColor(0xcc, 0xcc, 0xcc);
        let mut radius = step;
        while radius <= extent {
            chart
                .draw_series(LineSeries::new(circle(radius), grey.stroke_width(px(1))))
                .map_err(plot_err)?;
            radius += step;
        }
        for k in 0..12 {
            let a = TAU * Real::from(k) / 12.0;
            chart
                .draw_series(LineSeries::new(
                    [(0.0, 0.0), (r_max * 1.05 * a.cos(), r_max * 1.05 * a.sin())],
                    grey.stroke_width(px(1)),
                ))
                .map_err(plot_err)?;
        }
        chart
            .draw_series(LineSeries::new(
                circle(1.0),
                BLACK.mix(0.6).stroke_width(px(2)),
            ))
            .map_err(plot_err)?
            .label("unit circle (closed, r = 1)")
            .legend(|(x, y)| {
                PathElement::new(
                    vec![(x, y), (x + px(24) as i32, y)],
                    BLACK.mix(0.6).stroke_width(px(2)),
                )
            });
        for (k, (label, pts)) in curves.into_iter().enumerate() {
            let colour = CURVES[k % CURVES.len()];
            chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(px(3))))
                .map_err(plot_err)?
                .label(format!("{label}: r = 1 + ε(θ)"))
                .legend(move |(x, y)| {
                    PathElement::new(
                        vec![(x, y), (x + px(24) as i32, y)],
                        colour.stroke_width(px(3)),
                    )
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .margin(px(12))
            .legend_area_size(px(30))
            .label_font((FONT, px(14)))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.5).stroke_width(px(1)))
            .draw()
            .map_err(plot_err)?;
        root.present().map_err(plot_err)?;
    }
    finish(svg, W, H)
}

/// A "nice" grid spacing (0.25, 0.5, 1, 2, …) giving 2–8 circles up to `r`.
fn grid_step(r: Real) -> Real {
    let mut step = 0.25;
    while r / step > 8.0 {
        step *= 2.0;
    }
    step
}

fn circle(r: Real) -> Vec<(Real, Real)> {
    (0..=180)
        .map(|k| {
            let a = TAU * Real::from(k) / 180.0;
            (r * a.cos(), r * a.sin())
        })
        .collect()
}

//! A tiny SVG document builder (y axis flipped so that +y points up).

use crate::math::{Real, Vec2};
use std::fmt::Write;

/// Accumulates SVG elements in world coordinates and frames them at the end.
#[derive(Debug, Default)]
pub(crate) struct SvgDoc {
    body: String,
    min: Option<Vec2>,
    max: Option<Vec2>,
}

fn fmt_pt(p: &Vec2) -> String {
    format!("{:.5},{:.5}", p.x, -p.y)
}

impl SvgDoc {
    fn grow(&mut self, p: &Vec2) {
        self.min = Some(self.min.map_or(*p, |m| m.inf(p)));
        self.max = Some(self.max.map_or(*p, |m| m.sup(p)));
    }

    /// A closed polygon.
    pub fn polygon(&mut self, pts: &[Vec2], style: &str) {
        pts.iter().for_each(|p| self.grow(p));
        let d: Vec<String> = pts.iter().map(fmt_pt).collect();
        let _ = writeln!(self.body, r#"<polygon points="{}" {style}/>"#, d.join(" "));
    }

    /// A line segment.
    pub fn line(&mut self, a: &Vec2, b: &Vec2, style: &str) {
        self.grow(a);
        self.grow(b);
        let _ = writeln!(
            self.body,
            r#"<line x1="{:.5}" y1="{:.5}" x2="{:.5}" y2="{:.5}" {style}/>"#,
            a.x, -a.y, b.x, -b.y
        );
    }

    /// A circle.
    pub fn circle(&mut self, c: &Vec2, r: Real, style: &str) {
        self.grow(c);
        let _ = writeln!(
            self.body,
            r#"<circle cx="{:.5}" cy="{:.5}" r="{r:.5}" {style}/>"#,
            c.x, -c.y
        );
    }

    /// Centered text of height `size`.
    pub fn text(&mut self, at: &Vec2, size: Real, text: &str, style: &str) {
        let _ = writeln!(
            self.body,
            r#"<text x="{:.5}" y="{:.5}" font-size="{size:.5}" text-anchor="middle" dominant-baseline="middle" font-family="sans-serif" {style}>{}</text>"#,
            at.x,
            -at.y,
            escape(text)
        );
    }

    /// The finished document, framed with a margin, `width_px` wide.
    pub fn finish(self, margin: Real, width_px: Real, title: &str) -> String {
        let (min, max) = (self.min.unwrap_or_default(), self.max.unwrap_or_default());
        let (x0, y0) = (min.x - margin, -max.y - margin);
        let (w, h) = (max.x - min.x + 2.0 * margin, max.y - min.y + 2.0 * margin);
        let height_px = width_px * h / w.max(1e-12);
        format!(
            r#"<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="{width_px:.0}" height="{height_px:.0}" viewBox="{x0:.5} {y0:.5} {w:.5} {h:.5}">
<title>{}</title>
<rect x="{x0:.5}" y="{y0:.5}" width="{w:.5}" height="{h:.5}" fill="white"/>
{}</svg>
"#,
            escape(title),
            self.body
        )
    }
}

/// Escapes text for XML.
pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

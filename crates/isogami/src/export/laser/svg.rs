//! The laser sheet as SVG: page size and viewBox in millimetres (one user unit = 1 mm; user
//! coordinates are the patch's (x, -y)), one
//! group per operation (cut, score, engrave) with its colour, hairline strokes, one path per
//! cut and per outline loop, and the metadata in `<desc>`.

use super::fmt_mm;
use super::place::{labels, Placement};
use super::LaserSheet;
use std::fmt::Write;

/// The SVG text of `sheet`.
pub fn laser_svg(sheet: &LaserSheet) -> String {
    let s = &sheet.settings;
    let place = Placement::new(&sheet.layout, s.margin_mm);
    let (w, h) = place.size();
    let o = place.view_origin();
    let n = fmt_mm;
    let mut out = String::new();
    let _ = writeln!(out, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{}mm" height="{}mm" viewBox="{} {} {} {}">"#,
        n(w),
        n(h),
        n(o.x),
        n(o.y),
        n(w),
        n(h)
    );
    let _ = writeln!(out, "<title>isogami laser sheet</title>");
    let desc: Vec<String> = sheet
        .meta_lines()
        .iter()
        .map(|(k, v)| format!("{}: {}", escape(k), escape(v)))
        .collect();
    let _ = writeln!(out, "<desc>{}</desc>", desc.join("\n"));
    let stroke = n(s.stroke_mm);
    let _ = writeln!(
        out,
        r#"<g id="cut" fill="none" stroke="{}" stroke-width="{stroke}" stroke-linecap="round" stroke-linejoin="miter">"#,
        s.colours.cut
    );
    for (i, lp) in sheet.layout.outline.iter().enumerate() {
        let mut d = String::new();
        for (k, p) in lp.iter().enumerate() {
            let q = place.y_down(p);
            let _ = write!(
                d,
                "{}{} {} ",
                if k == 0 { "M" } else { "L" },
                n(q.x),
                n(q.y)
            );
        }
        d.push('Z');
        let _ = writeln!(out, r#"<path id="outline-{i}" d="{d}"/>"#);
    }
    for (i, c) in sheet.layout.cuts.iter().enumerate() {
        let (a, b) = (place.y_down(&c.a), place.y_down(&c.b));
        let _ = writeln!(
            out,
            r#"<path id="cut-{i}" d="M{} {} L{} {}"/>"#,
            n(a.x),
            n(a.y),
            n(b.x),
            n(b.y)
        );
    }
    let _ = writeln!(out, "</g>");
    let _ = writeln!(
        out,
        r#"<g id="score" fill="none" stroke="{}" stroke-width="{stroke}"/>"#,
        s.colours.score
    );
    let _ = writeln!(
        out,
        r#"<g id="engrave" fill="{}" stroke="none" font-family="sans-serif" text-anchor="middle">"#,
        s.colours.engrave
    );
    if s.labels {
        for (&i, (c, size)) in sheet.tile_ids.iter().zip(labels(&sheet.tiles).iter()) {
            let q = place.y_down(c);
            // Baseline a third of the height below the centre: the digits sit centred.
            let _ = writeln!(
                out,
                r#"<text x="{}" y="{}" font-size="{}">{i}</text>"#,
                n(q.x),
                n(q.y + size / 3.0),
                n(*size)
            );
        }
    }
    let _ = writeln!(out, "</g>");
    out.push_str("</svg>\n");
    out
}

/// Text with `&`, `<`, `>` and `"` escaped for XML.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

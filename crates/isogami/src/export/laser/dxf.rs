//! The laser sheet as ASCII DXF (R12, AC1009, millimetres, the patch's own coordinates): layers CUT (cuts between tiles),
//! OUTLINE (the outline cut, closed polylines), SCORE (empty: kirigami sheets need no folds)
//! and ENGRAVE (tile labels, when asked). Metadata as 999 comments at the top.

use super::place::{labels, Placement};
use super::settings::rgb;
use super::LaserSheet;
use crate::math::{Real, Vec2};
use std::fmt::Write;

/// The DXF text of `sheet`.
pub fn laser_dxf(sheet: &LaserSheet) -> String {
    let s = &sheet.settings;
    let place = Placement::new(&sheet.layout, s.margin_mm);
    let (lo, hi) = place.extents();
    let mut d = Dxf::default();
    for (k, v) in sheet.meta_lines() {
        let line = format!("{k}: {v}").replace(['\r', '\n'], " ");
        d.pair(999, &line);
    }
    d.pair(0, "SECTION");
    d.pair(2, "HEADER");
    d.pair(9, "$ACADVER");
    d.pair(1, "AC1009");
    d.pair(9, "$INSUNITS");
    d.pair(70, "4");
    d.pair(9, "$MEASUREMENT");
    d.pair(70, "1");
    d.pair(9, "$EXTMIN");
    d.point(10, &lo);
    d.pair(9, "$EXTMAX");
    d.point(10, &hi);
    d.pair(0, "ENDSEC");

    let layers = [
        ("CUT", &s.colours.cut),
        ("OUTLINE", &s.colours.cut),
        ("SCORE", &s.colours.score),
        ("ENGRAVE", &s.colours.engrave),
    ];
    d.pair(0, "SECTION");
    d.pair(2, "TABLES");
    d.pair(0, "TABLE");
    d.pair(2, "LTYPE");
    d.pair(70, "1");
    d.pair(0, "LTYPE");
    d.pair(2, "CONTINUOUS");
    d.pair(70, "0");
    d.pair(3, "Solid line");
    d.pair(72, "65");
    d.pair(73, "0");
    d.pair(40, "0.0");
    d.pair(0, "ENDTAB");
    d.pair(0, "TABLE");
    d.pair(2, "LAYER");
    d.pair(70, &layers.len().to_string());
    for (name, colour) in layers {
        d.pair(0, "LAYER");
        d.pair(2, name);
        d.pair(70, "0");
        d.pair(62, &aci(colour).to_string());
        d.pair(6, "CONTINUOUS");
    }
    d.pair(0, "ENDTAB");
    d.pair(0, "ENDSEC");

    d.pair(0, "SECTION");
    d.pair(2, "ENTITIES");
    for c in &sheet.layout.cuts {
        d.pair(0, "LINE");
        d.pair(8, "CUT");
        d.point(10, &c.a);
        d.point(11, &c.b);
    }
    for lp in &sheet.layout.outline {
        d.pair(0, "POLYLINE");
        d.pair(8, "OUTLINE");
        d.pair(66, "1");
        d.pair(70, "1");
        d.point(10, &Vec2::zeros());
        for p in lp {
            d.pair(0, "VERTEX");
            d.pair(8, "OUTLINE");
            d.point(10, p);
        }
        d.pair(0, "SEQEND");
        d.pair(8, "OUTLINE");
    }
    if s.labels {
        for (&i, (c, size)) in sheet.tile_ids.iter().zip(labels(&sheet.tiles).iter()) {
            let q = *c;
            d.pair(0, "TEXT");
            d.pair(8, "ENGRAVE");
            d.point(10, &q);
            d.pair(40, &num(*size));
            d.pair(1, &i.to_string());
            // Centred on the alignment point (11/21), middle of the text height.
            d.pair(72, "1");
            d.pair(73, "2");
            d.point(11, &q);
        }
    }
    d.pair(0, "ENDSEC");
    d.pair(0, "EOF");
    d.text
}

/// DXF text under construction: group code / value pairs, one per line each.
#[derive(Default)]
struct Dxf {
    text: String,
}

impl Dxf {
    fn pair(&mut self, code: u16, value: &str) {
        let _ = write!(self.text, "{code:>3}\n{value}\n");
    }

    /// A 3D point with z = 0 at codes `code`, `code + 10`, `code + 20`.
    fn point(&mut self, code: u16, p: &Vec2) {
        self.pair(code, &num(p.x));
        self.pair(code + 10, &num(p.y));
        self.pair(code + 20, "0.0");
    }
}

/// A coordinate with six decimals (1 nm).
fn num(x: Real) -> String {
    format!("{x:.6}")
}

/// The AutoCAD colour index nearest to `#rrggbb` among the seven basic colours (7 is black
/// on white paper).
fn aci(colour: &str) -> u8 {
    const BASIC: [(u8, [i32; 3]); 8] = [
        (1, [255, 0, 0]),
        (2, [255, 255, 0]),
        (3, [0, 255, 0]),
        (4, [0, 255, 255]),
        (5, [0, 0, 255]),
        (6, [255, 0, 255]),
        (7, [0, 0, 0]),
        (7, [255, 255, 255]),
    ];
    let c = rgb(colour).map(i32::from);
    BASIC
        .iter()
        .min_by_key(|(_, b)| (0..3).map(|i| (c[i] - b[i]).pow(2)).sum::<i32>())
        .map_or(7, |(i, _)| *i)
}

#[cfg(test)]
mod tests {
    use super::aci;

    #[test]
    fn default_colours_map_to_their_aci_indices() {
        assert_eq!(aci("#000000"), 7);
        assert_eq!(aci("#0000ff"), 5);
        assert_eq!(aci("#ff0000"), 1);
        assert_eq!(aci("#e01010"), 1);
    }
}

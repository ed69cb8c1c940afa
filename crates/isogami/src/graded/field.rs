//! A target field of area ratio over the sheet: how much each part of the sheet should open
//! (e.g. 1.2× at one end, 1.8× at the other) instead of an outline.
//!
//! The area ratio *of a cell* is measured on the quadrilateral of four neighbouring cells'
//! reference points (the first corner of each cell's tile 0): its opened area over its
//! closed area. On a periodic sheet every such quadrilateral maps by the deformation
//! gradient F, so the measure is the periodic sheet's det F; on a graded sheet it varies
//! from cell to cell, and that is what the field asks for. The quadrilaterals are found from
//! the tiles' cell indices (combinatorial), never from positions.

use super::error::GradedError;
use super::model::GradedSheet;
use crate::geometry::signed_area;
use crate::math::{Real, Vec2};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// A linear ramp of area ratio across the sheet.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AreaField {
    /// Area ratio at the start of the ramp (the sheet's far end against `direction`).
    pub from: Real,
    /// Area ratio at its end.
    pub to: Real,
    /// Direction of the ramp, degrees counter-clockwise from +x.
    pub direction_degrees: Real,
}

impl AreaField {
    /// Checks the field: finite ratios above 1 (a sheet that opens), a finite direction.
    pub fn validated(self) -> Result<AreaField, GradedError> {
        let ok = |r: Real| r.is_finite() && r > 1.0;
        if !ok(self.from) || !ok(self.to) {
            return Err(GradedError::BadTarget(format!(
                "a field's area ratios must be finite and above 1 (the sheet opens), not {} and {}",
                self.from, self.to
            )));
        }
        if !self.direction_degrees.is_finite() {
            return Err(GradedError::BadTarget(
                "a field's direction must be a finite angle in degrees".into(),
            ));
        }
        Ok(self)
    }

    /// Mean of the ramp's two ends.
    pub fn mean(&self) -> Real {
        0.5 * (self.from + self.to)
    }
}

/// Reads `field:FROM,TO` (a ramp along +x) or `field:FROM,TO,DEGREES`.
pub fn parse_field(text: &str) -> Result<AreaField, GradedError> {
    let bad = || {
        GradedError::BadTarget(format!(
            "{text:?} is not field:FROM,TO[,DEGREES] (area ratios at the two ends of a ramp, e.g. field:1.2,1.8)"
        ))
    };
    let body = text.trim().strip_prefix("field:").ok_or_else(bad)?;
    let numbers: Vec<Real> = body
        .split(',')
        .map(|s| s.trim().parse::<Real>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    let field = match numbers[..] {
        [from, to] => AreaField {
            from,
            to,
            direction_degrees: 0.0,
        },
        [from, to, direction_degrees] => AreaField {
            from,
            to,
            direction_degrees,
        },
        _ => return Err(bad()),
    };
    field.validated()
}

/// What the opened sheet should match: an outline, or a field of area ratio.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// An outline ([`super::Outline`]).
    Outline(super::Outline),
    /// A field of area ratio.
    Field(AreaField),
}

/// Reads a target: `field:FROM,TO[,DEGREES]`, or an outline as [`super::parse_outline`]
/// reads it (disc, ellipse:A,B, polygon:x,y;…).
pub fn parse_target(text: &str) -> Result<Target, GradedError> {
    if text.trim().starts_with("field:") {
        parse_field(text).map(Target::Field)
    } else {
        super::parse_outline(text).map(Target::Outline)
    }
}

/// One measured cell: four reference corners (tile, node), counter-clockwise in the closed
/// sheet, and the ratio the field asks of it.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldCell {
    /// The quadrilateral's corners: (tile index, node index).
    pub corners: [(usize, usize); 4],
    /// The target area ratio.
    pub target: Real,
    /// Its closed area at the start (the residual's unit).
    pub start_area: Real,
    /// Its closed centre at the start (where the ramp is read).
    pub centre: Vec2,
}

/// The measured cells of `sheet` and their targets from `field`.
pub fn field_cells(sheet: &GradedSheet, field: &AreaField) -> Vec<FieldCell> {
    let reference: HashMap<[i32; 2], usize> = sheet
        .tiles
        .iter()
        .enumerate()
        .filter(|(_, t)| t.tile == 0)
        .map(|(i, t)| (t.cell, i))
        .collect();
    let mut cells: Vec<[i32; 2]> = reference.keys().copied().collect();
    cells.sort();
    let mut out = Vec::new();
    for c in cells {
        let quad =
            [[0, 0], [1, 0], [1, 1], [0, 1]].map(|d| reference.get(&[c[0] + d[0], c[1] + d[1]]));
        let [Some(&a), Some(&b), Some(&cc), Some(&d)] = quad else {
            continue;
        };
        let mut corners = [a, b, cc, d].map(|i| (i, sheet.tiles[i].nodes[0]));
        let mut points: Vec<Vec2> = corners.iter().map(|&(_, n)| sheet.node(n)).collect();
        let mut area = signed_area(&points);
        if area < 0.0 {
            corners.reverse();
            points.reverse();
            area = -area;
        }
        let centre = points.iter().sum::<Vec2>() / 4.0;
        out.push(FieldCell {
            corners,
            target: 0.0,
            start_area: area,
            centre,
        });
    }
    let angle = field.direction_degrees.to_radians();
    let dir = Vec2::new(angle.cos(), angle.sin());
    let along: Vec<Real> = out.iter().map(|c| c.centre.dot(&dir)).collect();
    let lo = along.iter().copied().fold(Real::INFINITY, Real::min);
    let hi = along.iter().copied().fold(Real::NEG_INFINITY, Real::max);
    for (cell, s) in out.iter_mut().zip(along) {
        let f = if hi > lo { (s - lo) / (hi - lo) } else { 0.5 };
        cell.target = field.from + f * (field.to - field.from);
    }
    out
}

/// Area ratio of every measured cell of `sheet` in its opened state.
pub fn cell_ratios(sheet: &GradedSheet, cells: &[FieldCell]) -> Vec<Real> {
    cells
        .iter()
        .map(|c| {
            let closed: Vec<Vec2> = c.corners.iter().map(|&(_, n)| sheet.node(n)).collect();
            let opened: Vec<Vec2> = c
                .corners
                .iter()
                .map(|&(i, n)| sheet.opened_corner(i, n))
                .collect();
            signed_area(&opened) / signed_area(&closed)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn targets_are_outlines_or_fields() {
        assert!(matches!(parse_target("disc"), Ok(Target::Outline(_))));
        assert!(matches!(
            parse_target("field:1.2,1.8"),
            Ok(Target::Field(_))
        ));
        assert!(parse_target("field:1").is_err());
    }

    #[test]
    fn fields_parse_or_say_why() {
        let f = parse_field("field:1.2,1.8").unwrap();
        assert_eq!((f.from, f.to, f.direction_degrees), (1.2, 1.8, 0.0));
        assert_eq!(
            parse_field("field:1.5,1.2,90").unwrap().direction_degrees,
            90.0
        );
        for bad in [
            "field:1.2",
            "field:0.5,1.5",
            "field:a,b",
            "field:1.2,NaN",
            "ramp:1,2",
        ] {
            let e = parse_field(bad).unwrap_err().to_string();
            assert!(e.starts_with("bad target"), "{bad}: {e}");
            assert!(!e.contains('\n'), "{e}");
        }
    }
}

//! Where the sheet lands in the file. Coordinates are the patch's own millimetres (SVG flips
//! y, which points down there), so a file can be laid over the design without a shift; the
//! page (SVG viewBox, DXF extents) is the bounding box of everything cut plus the margin.

use super::cuts::CutLayout;
use crate::math::{Real, Vec2};

/// The drawing's frame in the file (mm).
#[derive(Debug, Clone, Copy)]
pub(super) struct Placement {
    min: Vec2,
    max: Vec2,
    margin: Real,
}

impl Placement {
    /// The frame of `layout` with `margin` on every side.
    pub fn new(layout: &CutLayout, margin: Real) -> Placement {
        let mut min = Vec2::new(Real::INFINITY, Real::INFINITY);
        let mut max = -min;
        let pts = layout
            .outline
            .iter()
            .flatten()
            .chain(layout.cuts.iter().flat_map(|c| [&c.a, &c.b]));
        for p in pts {
            min = min.inf(p);
            max = max.sup(p);
        }
        if !(min.x <= max.x && min.y <= max.y) {
            min = Vec2::zeros();
            max = Vec2::zeros();
        }
        Placement { min, max, margin }
    }

    /// Width and height of the file's page.
    pub fn size(&self) -> (Real, Real) {
        let d = self.max - self.min;
        (d.x + 2.0 * self.margin, d.y + 2.0 * self.margin)
    }

    /// Lower-left and upper-right corners of the page with y up (DXF extents).
    pub fn extents(&self) -> (Vec2, Vec2) {
        let m = Vec2::new(self.margin, self.margin);
        (self.min - m, self.max + m)
    }

    /// Top-left corner of the page with y down (SVG viewBox origin).
    pub fn view_origin(&self) -> Vec2 {
        Vec2::new(self.min.x - self.margin, -self.max.y - self.margin)
    }

    /// A point in the SVG frame (y down): the sheet seen from the same side.
    pub fn y_down(&self, p: &Vec2) -> Vec2 {
        Vec2::new(p.x, -p.y)
    }
}

/// Label position and size for each tile: its vertex area centroid and a height of a fifth of
/// the square root of its area.
pub(super) fn labels(tiles: &[Vec<[Real; 2]>]) -> Vec<(Vec2, Real)> {
    tiles
        .iter()
        .map(|poly| {
            let pts: Vec<Vec2> = poly.iter().map(|p| Vec2::new(p[0], p[1])).collect();
            let c = crate::geometry::centroid(&pts);
            let area = crate::geometry::signed_area(&pts).abs();
            (c, 0.2 * area.sqrt())
        })
        .collect()
}

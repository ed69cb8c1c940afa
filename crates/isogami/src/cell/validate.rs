//! Whole-cell geometric checks: the cell must tile the plane without gaps or overlaps.

use super::build::UnitCell;
use super::error::{CellError, GeometryProblem};
use crate::geometry::{interiors_overlap, signed_area};
use crate::math::{cross, Real};

impl UnitCell {
    /// Checks that the tiles' areas sum to |det[u w]| and that no tile of the cell overlaps
    /// another tile of any cell it can reach (at least the 3×3 block; more for tiles longer
    /// than the cell). With every tile edge matched to exactly one partner (guaranteed by
    /// construction) this means the cell tiles the plane.
    pub fn check_geometry(&self) -> Result<(), CellError> {
        let scale = self.mean_edge_length();
        let lattice = cross(&self.u, &self.w).abs();
        let area: Real = self.tiles.iter().map(|t| signed_area(&t.polygon)).sum();
        if (area - lattice).abs() > 1e-9 * lattice {
            return Err(CellError::Geometry(GeometryProblem::AreaMismatch {
                tiles: area,
                cell: lattice,
            }));
        }
        if let Some(t) = self
            .tiles
            .iter()
            .position(|t| signed_area(&t.polygon) <= 0.0)
        {
            return Err(CellError::Geometry(GeometryProblem::Clockwise { tile: t }));
        }
        let tol = 1e-7 * scale;
        let [ru, rw] = self.reach();
        for i in 0..self.tiles.len() {
            for j in 0..self.tiles.len() {
                for ku in -ru..=ru {
                    for kw in -rw..=rw {
                        if i == j && ku == 0 && kw == 0 {
                            continue;
                        }
                        let q = self.tile_polygon_at(j, [ku, kw]);
                        if interiors_overlap(&self.tiles[i].polygon, &q, tol) {
                            return Err(CellError::Geometry(GeometryProblem::Overlap {
                                a: i,
                                b: j,
                                offset: [ku, kw],
                            }));
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// How many cells (along u, along w) a tile of this cell can reach: the spread of all
    /// tile vertices in lattice coordinates, rounded up, and at least 1.
    pub fn reach(&self) -> [i32; 2] {
        let det = cross(&self.u, &self.w);
        let (mut lo, mut hi) = ([Real::INFINITY; 2], [Real::NEG_INFINITY; 2]);
        for p in self.tiles.iter().flat_map(|t| t.polygon.iter()) {
            let c = [cross(p, &self.w) / det, cross(&self.u, p) / det];
            for k in 0..2 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
        [0, 1].map(|k| ((hi[k] - lo[k]).ceil() as i32).clamp(1, 64))
    }
}

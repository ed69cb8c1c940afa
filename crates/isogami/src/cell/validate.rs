//! Whole-cell geometric checks: the cell must tile the plane without gaps or overlaps.

use super::build::UnitCell;
use crate::error::{Error, Result};
use crate::geometry::{interiors_overlap, signed_area};
use crate::math::{cross, Real};

impl UnitCell {
    /// Checks that the tiles' areas sum to |det[u w]| and that no tile of the cell overlaps
    /// another tile anywhere in the 3×3 block of cells around it. With every tile edge matched
    /// to exactly one partner (guaranteed by construction) this means the cell tiles the plane.
    pub fn check_geometry(&self) -> Result<()> {
        let scale = self.mean_edge_length();
        let lattice = cross(&self.u, &self.w).abs();
        let area: Real = self.tiles.iter().map(|t| signed_area(&t.polygon)).sum();
        if (area - lattice).abs() > 1e-9 * lattice {
            return Err(Error::CellGeometry(format!(
                "tile areas sum to {area} but the cell has area {lattice}"
            )));
        }
        if let Some(t) = self
            .tiles
            .iter()
            .position(|t| signed_area(&t.polygon) <= 0.0)
        {
            return Err(Error::CellGeometry(format!(
                "tile {t} is not counter-clockwise"
            )));
        }
        let tol = 1e-7 * scale;
        for i in 0..self.tiles.len() {
            for j in 0..self.tiles.len() {
                for ku in -1..=1 {
                    for kw in -1..=1 {
                        if i == j && ku == 0 && kw == 0 {
                            continue;
                        }
                        let q = self.tile_polygon_at(j, [ku, kw]);
                        if interiors_overlap(&self.tiles[i].polygon, &q, tol) {
                            return Err(Error::CellGeometry(format!(
                                "tile {i} overlaps tile {j} of cell ({ku}, {kw})"
                            )));
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

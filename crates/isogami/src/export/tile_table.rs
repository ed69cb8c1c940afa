//! The tile table of a patch, in CSV and JSON: one row per tile with its id, cell offset,
//! tile index, polygon in mm, pose at the exported state (centroid x, y in mm and rotation
//! θ from the closed state), interior angles, and the tiles it is pinned to (one entry per
//! joint, so two tiles pinned twice list each other twice).
//!
//! CSV columns: `id,cell_i,cell_j,tile,x_mm,y_mm,theta_rad,rotation_deg,vertices,polygon_mm,
//! interior_angles_deg,neighbours`; the list fields hold numbers separated by spaces
//! (`polygon_mm` as `x0 y0 x1 y1 …`), so no field needs quoting.

use super::patch::Patch;
use crate::math::Real;
use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// One row of the tile table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TileRow {
    /// Tile id in the patch.
    pub id: usize,
    /// Cell [i, j] (multiples of u and w).
    pub cell: [i32; 2],
    /// Tile index in the cell.
    pub tile: usize,
    /// Vertices, counter-clockwise, mm.
    pub polygon_mm: Vec<[Real; 2]>,
    /// Centroid and rotation at the exported state.
    pub pose: Pose,
    /// Rotation from the closed state, degrees.
    pub rotation_deg: Real,
    /// Interior angle at each vertex, degrees (above 180 at a reflex vertex).
    pub interior_angles_deg: Vec<Real>,
    /// Ids of the tiles pinned to this one, one per joint, ascending.
    pub neighbours: Vec<usize>,
}

/// A tile's pose.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Centroid x, mm.
    pub x: Real,
    /// Centroid y, mm.
    pub y: Real,
    /// Rotation from the closed state, radians.
    pub theta: Real,
}

/// The tile table as JSON data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TileTable {
    /// Design spec string.
    pub design: String,
    /// Always "mm".
    pub unit: String,
    /// t of the state.
    pub t: Real,
    /// Mean edge length, mm.
    pub edge_mm: Real,
    /// Cells along w and along u.
    pub rows: usize,
    /// Cells along u.
    pub cols: usize,
    /// One row per tile, by id.
    pub tiles: Vec<TileRow>,
}

/// The rows of a patch's tile table.
pub fn tile_table(patch: &Patch) -> TileTable {
    let mut neighbours = vec![Vec::new(); patch.tiles.len()];
    for j in &patch.joints {
        neighbours[j.a].push(j.b);
        neighbours[j.b].push(j.a);
    }
    let tiles = patch
        .tiles
        .iter()
        .zip(neighbours)
        .map(|(t, mut nb)| {
            nb.sort_unstable();
            TileRow {
                id: t.id,
                cell: t.cell,
                tile: t.tile,
                polygon_mm: t.polygon_mm.clone(),
                pose: Pose {
                    x: t.centroid_mm[0],
                    y: t.centroid_mm[1],
                    theta: t.rotation,
                },
                rotation_deg: t.rotation.to_degrees(),
                interior_angles_deg: interior_angles(&t.polygon_mm),
                neighbours: nb,
            }
        })
        .collect();
    TileTable {
        design: patch.design.clone(),
        unit: "mm".into(),
        t: patch.t,
        edge_mm: patch.edge_mm,
        rows: patch.rows,
        cols: patch.cols,
        tiles,
    }
}

/// Interior angles of a counter-clockwise polygon, degrees.
fn interior_angles(poly: &[[Real; 2]]) -> Vec<Real> {
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (a, b, c) = (poly[(k + n - 1) % n], poly[k], poly[(k + 1) % n]);
            let (u, v) = ([a[0] - b[0], a[1] - b[1]], [c[0] - b[0], c[1] - b[1]]);
            // Angle from the next edge to the previous one, counter-clockwise: the interior.
            let ang = (v[0] * u[1] - v[1] * u[0]).atan2(v[0] * u[0] + v[1] * u[1]);
            let ang = if ang < 0.0 {
                ang + std::f64::consts::TAU
            } else {
                ang
            };
            ang.to_degrees()
        })
        .collect()
}

/// The CSV header line.
pub const TILE_CSV_HEADER: &str = "id,cell_i,cell_j,tile,x_mm,y_mm,theta_rad,rotation_deg,vertices,polygon_mm,interior_angles_deg,neighbours";

/// The tile table as CSV text (header line first).
pub fn tile_csv(table: &TileTable) -> String {
    let mut out = String::from(TILE_CSV_HEADER);
    out.push('\n');
    let join = |xs: &mut dyn Iterator<Item = String>| xs.collect::<Vec<_>>().join(" ");
    for r in &table.tiles {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            r.id,
            r.cell[0],
            r.cell[1],
            r.tile,
            r.pose.x,
            r.pose.y,
            r.pose.theta,
            r.rotation_deg,
            r.polygon_mm.len(),
            join(&mut r.polygon_mm.iter().flatten().map(|x| x.to_string())),
            join(&mut r.interior_angles_deg.iter().map(|x| x.to_string())),
            join(&mut r.neighbours.iter().map(|x| x.to_string())),
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::interior_angles;

    #[test]
    fn interior_angles_of_a_dart_include_one_reflex_angle() {
        // Counter-clockwise dart: reflex vertex at (0, 1).
        let dart = [[0.0, 0.0], [2.0, 2.0], [0.0, 1.0], [-2.0, 2.0]];
        let a = interior_angles(&dart);
        let sum: f64 = a.iter().sum();
        assert!((sum - 360.0).abs() < 1e-9, "{a:?}");
        assert!(a[2] > 180.0 && a.iter().filter(|&&x| x > 180.0).count() == 1);
        let square = interior_angles(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        assert!(square.iter().all(|x| (x - 90.0).abs() < 1e-12));
    }
}

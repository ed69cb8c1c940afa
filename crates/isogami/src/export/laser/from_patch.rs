//! A laser sheet from an export [`Patch`]: always its closed state (the flat sheet a laser
//! cuts), restricted to the largest piece that its joints hold together. A rectangle of
//! cells can hold border tiles whose joints all lead out of the patch; cut free they would
//! fall out of the sheet, so they are left off the sheet and counted in its metadata.

use super::{fmt_mm, min_edge_mm, JointAt, LaserError, LaserSettings, LaserSheet};
use crate::export::Patch;
use crate::math::Real;

/// The laser sheet of `patch` with `settings`.
pub fn laser_sheet(patch: &Patch, settings: LaserSettings) -> Result<LaserSheet, LaserError> {
    let polys = &patch.closed_polygons_mm;
    let mut joints = Vec::with_capacity(patch.joints.len());
    for (j, joint) in patch.joints.iter().enumerate() {
        let point = polys
            .get(joint.a)
            .and_then(|p| p.get(joint.vertex_a))
            .ok_or(LaserError::NoSuchTile {
                joint: j,
                tile: joint.a,
                tiles: polys.len(),
            })?;
        joints.push(JointAt {
            tiles: [joint.a, joint.b],
            point: *point,
        });
    }
    let (tiles, joints, ids) = largest_piece(polys, &joints)?;
    let kept = ids.len();
    let dropped = polys.len() - tiles.len();
    let meta = vec![
        ("spec".to_string(), patch.design.clone()),
        (
            "patch".to_string(),
            format!("{}x{} cells", patch.rows, patch.cols),
        ),
        ("edge_mm".to_string(), fmt_mm(patch.edge_mm)),
        ("state".to_string(), "closed (t = 0)".to_string()),
        (
            "tiles".to_string(),
            format!(
                "{} of {} (left off: {dropped} not held by joints)",
                kept,
                polys.len()
            ),
        ),
    ];
    // Labels are the tiles' ids in the patch's other files, not their places among the kept.
    let labels = ids
        .iter()
        .map(|&k| patch.tiles.get(k).map_or(k, |t| t.id))
        .collect();
    let sheet = LaserSheet::new(tiles, &joints, settings, meta).map_err(|e| match e {
        LaserError::HingeTooWide {
            hinge_mm,
            edge_mm: len_mm,
            needed_mm,
            tiles,
        } if needed_mm.is_finite() && len_mm > 0.0 => LaserError::PatchTooSmall {
            hinge_mm,
            edge_mm: patch.edge_mm,
            min_edge_mm: min_edge_mm(patch.edge_mm, needed_mm, len_mm),
            len_mm,
            needed_mm,
            tiles: tiles.map(|k| {
                ids.get(k)
                    .and_then(|&t| patch.tiles.get(t))
                    .map_or(k, |t| t.id)
            }),
        },
        e => e,
    })?;
    Ok(sheet.with_tile_ids(labels))
}

/// The kept tiles, their joints (renumbered) and the kept tiles' indices among the given.
type Piece = (Vec<Vec<[Real; 2]>>, Vec<JointAt>, Vec<usize>);

/// The tiles and joints of the largest connected piece of the tile/joint graph (see
/// `export::piece`), tiles renumbered in their order.
fn largest_piece(tiles: &[Vec<[Real; 2]>], joints: &[JointAt]) -> Result<Piece, LaserError> {
    let n = tiles.len();
    for (j, joint) in joints.iter().enumerate() {
        if let Some(&t) = joint.tiles.iter().find(|&&t| t >= n) {
            return Err(LaserError::NoSuchTile {
                joint: j,
                tile: t,
                tiles: n,
            });
        }
    }
    let ids = crate::export::piece::largest_piece(n, joints.iter().map(|j| j.tiles));
    if ids.is_empty() {
        return Err(LaserError::NoTiles);
    }
    let mut index = vec![usize::MAX; n];
    for (k, &t) in ids.iter().enumerate() {
        index[t] = k;
    }
    let kept: Vec<Vec<[Real; 2]>> = ids.iter().map(|&t| tiles[t].clone()).collect();
    let joints = joints
        .iter()
        .filter(|j| index[j.tiles[0]] != usize::MAX)
        .map(|j| JointAt {
            tiles: j.tiles.map(|t| index[t]),
            point: j.point,
        })
        .collect();
    Ok((kept, joints, ids))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_joint_connected_piece_is_kept() {
        let sq = |x: Real| vec![[x, 0.0], [x + 1.0, 0.0], [x + 1.0, 1.0], [x, 1.0]];
        let tiles = vec![sq(0.0), sq(1.0), sq(2.0), sq(3.0)];
        let j = |a, b, x| JointAt {
            tiles: [a, b],
            point: [x, 1.0],
        };
        // 1–2–3 held together, 0 loose.
        let joints = [j(1, 2, 2.0), j(2, 3, 3.0)];
        let (kept, joints, ids) = largest_piece(&tiles, &joints).unwrap();
        assert_eq!(
            ids,
            [1, 2, 3],
            "the kept tiles' own indices, for their labels"
        );
        assert_eq!(kept[0], sq(1.0));
        assert_eq!(joints[0].tiles, [0, 1]);
        assert_eq!(joints[1].tiles, [1, 2]);
    }
}

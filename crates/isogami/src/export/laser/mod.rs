//! Laser-cutting sheets of a patch: one sheet of material, cut along every tile edge except
//! a bridge of material at each joint, and cut out along the patch outline, compensated
//! for the kerf. Written as SVG (groups per operation, in mm) or ASCII DXF (layers CUT,
//! SCORE, OUTLINE, ENGRAVE, mm units).
//!
//! The input is plain: closed-state tile polygons in millimetres (counter-clockwise) and
//! the joints as pairs of tiles with the tiling vertex they share; [`laser_sheet`] takes
//! them from an export [`Patch`](crate::export::Patch). [`cuts`] holds the
//! geometry (and documents the kerf and bridge layout); [`svg`] and [`dxf`] only write it.

pub mod cuts;
mod dxf;
mod error;
mod from_patch;
pub(crate) mod graph;
pub mod material;
mod outline;
mod place;
mod settings;
mod svg;

pub use cuts::{layout_cuts, Bridge, Cut, CutLayout};
pub use dxf::laser_dxf;
pub use error::LaserError;
pub use from_patch::laser_sheet;
pub use material::{Material, MaterialNumbers};
pub use settings::{LaserColours, LaserSettings};
pub use svg::laser_svg;

use crate::math::Real;

/// A joint of a patch: its two tiles and the tiling vertex (mm) where they are pinned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointAt {
    /// Indices of the two tiles.
    pub tiles: [usize; 2],
    /// The joint point.
    pub point: [Real; 2],
}

/// A labelled value for the files' metadata (design spec, patch size, scale, state...).
pub type MetaItem = (String, String);

/// A laid-out sheet ready to write: the cut layout, the tile polygons (for labels) and the
/// metadata lines.
#[derive(Debug, Clone)]
pub struct LaserSheet {
    /// Cuts, outline and bridges.
    pub layout: CutLayout,
    /// Tile polygons (mm).
    pub tiles: Vec<Vec<[Real; 2]>>,
    /// The number engraved on each tile (with `labels`): its id in the patch's other files
    /// (tile table, FOLD, OBJ, kirigami_sim), so a tile left off does not shift the others.
    pub tile_ids: Vec<usize>,
    /// Settings it was laid out with.
    pub settings: LaserSettings,
    /// Metadata written into the file besides the settings and the tool version.
    pub meta: Vec<MetaItem>,
}

impl LaserSheet {
    /// Validates `settings` and lays out the cuts of `tiles` with bridges at `joints`.
    pub fn new(
        tiles: Vec<Vec<[Real; 2]>>,
        joints: &[JointAt],
        settings: LaserSettings,
        meta: Vec<MetaItem>,
    ) -> Result<LaserSheet, LaserError> {
        settings.validate()?;
        let layout = layout_cuts(&tiles, joints, settings.hinge_mm, settings.kerf_mm)?;
        check_kerf(&tiles, settings.kerf_mm)?;
        Ok(LaserSheet {
            layout,
            tile_ids: (0..tiles.len()).collect(),
            tiles,
            settings,
            meta,
        })
    }

    /// The same sheet with tile `k` numbered `ids[k]` (one id per tile).
    pub fn with_tile_ids(self, ids: Vec<usize>) -> LaserSheet {
        debug_assert_eq!(ids.len(), self.tiles.len());
        LaserSheet {
            tile_ids: ids,
            ..self
        }
    }

    /// The metadata lines: the caller's, then the settings and the tool version.
    pub fn meta_lines(&self) -> Vec<MetaItem> {
        let s = &self.settings;
        let mut out = self.meta.clone();
        let mut push = |k: &str, v: String| out.push((k.to_string(), v));
        push("units", "mm".into());
        push("hinge_mm", fmt_mm(s.hinge_mm));
        push("kerf_mm", fmt_mm(s.kerf_mm));
        push(
            "kerf_compensation",
            "cuts between tiles on the design edges (each tile loses kerf/2), cut ends kerf/2 \
             short of bridges, outline offset kerf/2 outwards"
                .into(),
        );
        push("thickness_mm", fmt_mm(s.thickness_mm));
        push(
            "material",
            s.material.map_or("custom".into(), |m| m.name().into()),
        );
        push("bridges", self.layout.bridges.len().to_string());
        push("tool", format!("isogami {}", env!("CARGO_PKG_VERSION")));
        out
    }
}

/// Refuses a kerf that would take a whole edge (or more) off a tile: each tile must survive
/// as its kerf/2 inset.
fn check_kerf(tiles: &[Vec<[Real; 2]>], kerf: Real) -> Result<(), LaserError> {
    for (tile, poly) in tiles.iter().enumerate() {
        let pts: Vec<crate::math::Vec2> = poly
            .iter()
            .map(|p| crate::math::Vec2::new(p[0], p[1]))
            .collect();
        if let Err(problem) = crate::contact::inset_polygon(&pts, 0.5 * kerf) {
            return Err(LaserError::KerfTooWide {
                kerf_mm: kerf,
                tile,
                problem: problem.to_string(),
            });
        }
    }
    Ok(())
}

/// A length in mm with up to four decimals, trailing zeros dropped.
pub(crate) fn fmt_mm(x: Real) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// The smallest mean edge length (rounded up to 0.001 mm) at which an edge of `len_mm` at
/// `edge_mm` grows to `needed_mm`: lengths scale with the patch, the needs do not.
pub(crate) fn min_edge_mm(edge_mm: Real, needed_mm: Real, len_mm: Real) -> Real {
    let exact = edge_mm * needed_mm / len_mm;
    // A hair above the exact value, so the rounded size fits with the layout's own slack.
    ((exact * (1.0 + 1e-9)) * 1000.0).ceil() / 1000.0
}

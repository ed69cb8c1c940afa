//! Which tiles of the periodic sheet a requested region holds.
//!
//! A region is R×C cells (the patch every export has always written) or a shape in
//! millimetres — a rectangle, a disc or any simple polygon — laid on the closed sheet with
//! the mean edge length L at `edge_mm` and the origin at the centre of cell [0, 0] (the mean
//! of its tiles' centroids). A tile is in a shape when its closed-state centroid is.

use super::error::FiniteError;
use super::sheet::SheetTile;
use crate::geometry::{point_in_polygon_strict, signed_area};
use crate::kinematics::Mechanism;
use crate::math::{cross, Real, Vec2};
use serde::{Deserialize, Serialize};

/// Largest region: this many cells along either lattice direction.
pub const MAX_REGION_CELLS: usize = 40;

/// A requested region of the sheet.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Region {
    /// Cells [i, j], i in 0..cols (along u), j in 0..rows (along w).
    Cells {
        /// Cells along w.
        rows: usize,
        /// Cells along u.
        cols: usize,
    },
    /// An axis-aligned rectangle centred on the origin, mm.
    Rect {
        /// Width, mm.
        width_mm: Real,
        /// Height, mm.
        height_mm: Real,
    },
    /// A disc centred on the origin, mm.
    Disc {
        /// Radius, mm.
        radius_mm: Real,
    },
    /// A simple polygon, mm (either orientation).
    Polygon {
        /// Vertices, mm.
        points_mm: Vec<[Real; 2]>,
    },
}

impl Region {
    /// The region as a polygon in units of L (None for cells), checked.
    fn outline(&self, edge_mm: Real) -> Result<Option<Vec<Vec2>>, FiniteError> {
        let bad = |what: String| Err(FiniteError::BadRegion(what));
        if !(edge_mm.is_finite() && edge_mm > 0.0) {
            return bad(format!(
                "edge length {edge_mm} mm must be a finite number above 0"
            ));
        }
        let positive = |name: &str, v: Real| -> Result<Real, FiniteError> {
            if v.is_finite() && v > 0.0 {
                Ok(v / edge_mm)
            } else {
                Err(FiniteError::BadRegion(format!(
                    "{name} {v} mm must be a finite number above 0"
                )))
            }
        };
        let poly = match self {
            Region::Cells { rows, cols } => {
                if *rows == 0 || *cols == 0 || *rows > MAX_REGION_CELLS || *cols > MAX_REGION_CELLS
                {
                    return bad(format!(
                        "{rows}x{cols} cells: rows and columns must be 1..={MAX_REGION_CELLS}"
                    ));
                }
                return Ok(None);
            }
            Region::Rect {
                width_mm,
                height_mm,
            } => {
                let (w, h) = (
                    positive("width", *width_mm)?,
                    positive("height", *height_mm)?,
                );
                vec![
                    Vec2::new(-w / 2.0, -h / 2.0),
                    Vec2::new(w / 2.0, -h / 2.0),
                    Vec2::new(w / 2.0, h / 2.0),
                    Vec2::new(-w / 2.0, h / 2.0),
                ]
            }
            Region::Disc { radius_mm } => {
                let r = positive("radius", *radius_mm)?;
                (0..128)
                    .map(|k| {
                        let a = std::f64::consts::TAU * k as Real / 128.0;
                        Vec2::new(r * a.cos(), r * a.sin())
                    })
                    .collect()
            }
            Region::Polygon { points_mm } => {
                if points_mm.len() < 3 {
                    return bad(format!(
                        "a polygon needs at least 3 points, got {}",
                        points_mm.len()
                    ));
                }
                if points_mm.iter().flatten().any(|v| !v.is_finite()) {
                    return bad("a polygon point is not a finite number".into());
                }
                let p: Vec<Vec2> = points_mm
                    .iter()
                    .map(|v| Vec2::new(v[0], v[1]) / edge_mm)
                    .collect();
                let area = signed_area(&p).abs();
                if !area.is_finite() {
                    return bad("the polygon's area overflows (coordinates too large)".into());
                }
                if area <= 0.0 {
                    return bad("the polygon has no area".into());
                }
                if crate::geometry::is_simple_problem(&p, 1e-9).is_some() {
                    return bad("the polygon is not simple (its sides cross)".into());
                }
                p
            }
        };
        Ok(Some(poly))
    }

    /// The tiles of the sheet of `mech` (cell dims as built) that the region holds, in no
    /// particular order. `edge_mm` is the mean edge length L in mm (ignored for cells).
    pub fn tiles(&self, mech: &Mechanism, edge_mm: Real) -> Result<Vec<SheetTile>, FiniteError> {
        let n = mech.tile_count();
        let Some(poly) = self.outline(edge_mm)? else {
            let Region::Cells { rows, cols } = *self else {
                unreachable!("only cells have no outline")
            };
            let (rows, cols) = (rows as i32, cols as i32);
            return Ok((0..rows)
                .flat_map(|j| {
                    (0..cols).flat_map(move |i| {
                        (0..n).map(move |k| SheetTile {
                            cell: [i, j],
                            tile: k,
                        })
                    })
                })
                .collect());
        };
        let q = &mech.rest;
        let (u, w) = mech.lattice(q);
        let centroids: Vec<Vec2> = (0..n).map(|k| mech.pose(q, k).0).collect();
        let origin = centroids.iter().fold(Vec2::zeros(), |a, c| a + c) / n as Real;
        // Lattice coordinates of the region's points bound the cells to look at; a margin of
        // two cells covers tiles whose centroid lies outside their cell's parallelogram.
        // In floating point until the span is known to be small: a region of 1e308 mm has
        // lattice coordinates no integer holds.
        let det = cross(&u, &w);
        let (mut lo_f, mut hi_f) = ([Real::INFINITY; 2], [Real::NEG_INFINITY; 2]);
        for p in &poly {
            let rel = p + origin - centroids[0];
            let a = cross(&rel, &w) / det;
            let b = cross(&u, &rel) / det;
            for (d, v) in [a, b].into_iter().enumerate() {
                lo_f[d] = lo_f[d].min(v.floor() - 2.0);
                hi_f[d] = hi_f[d].max(v.ceil() + 2.0);
            }
        }
        let span = (hi_f[0] - lo_f[0]).max(hi_f[1] - lo_f[1]);
        let most = 4 * MAX_REGION_CELLS;
        if span.is_nan() || span > most as Real {
            return Err(FiniteError::BadRegion(format!(
                "the region spans {} cells; at most {most} fit",
                crate::settings_error::short_real(span)
            )));
        }
        let (lo, hi) = (lo_f.map(|v| v as i64), hi_f.map(|v| v as i64));
        let mut out = Vec::new();
        for j in lo[1]..=hi[1] {
            for i in lo[0]..=hi[0] {
                let shift = u * i as Real + w * j as Real;
                for (k, c) in centroids.iter().enumerate() {
                    let at = c + shift - origin;
                    if point_in_polygon_strict(&at, &poly, 1e-12) {
                        out.push(SheetTile {
                            cell: [i as i32, j as i32],
                            tile: k,
                        });
                    }
                }
            }
        }
        Ok(out)
    }
}

impl std::str::FromStr for Region {
    type Err = FiniteError;

    /// `RxC` (cells, e.g. `6x6`), `rect:W,H`, `disc:R` or `polygon:x,y;x,y;…` (mm).
    fn from_str(text: &str) -> Result<Region, FiniteError> {
        let bad = || {
            FiniteError::BadRegion(format!(
                "'{text}' is not a region: write RxC (cells, e.g. 6x6), rect:W,H, disc:R or \
                 polygon:x,y;x,y;… (mm)"
            ))
        };
        let number = |s: &str| s.trim().parse::<Real>().map_err(|_| bad());
        let text = text.trim();
        let region = if let Some(rest) = text.strip_prefix("rect:") {
            let (w, h) = rest.split_once(',').ok_or_else(bad)?;
            Region::Rect {
                width_mm: number(w)?,
                height_mm: number(h)?,
            }
        } else if let Some(rest) = text.strip_prefix("disc:") {
            Region::Disc {
                radius_mm: number(rest)?,
            }
        } else if let Some(rest) = text.strip_prefix("polygon:") {
            let points_mm = rest
                .split(';')
                .filter(|p| !p.trim().is_empty())
                .map(|p| {
                    let (x, y) = p.split_once(',').ok_or_else(bad)?;
                    Ok([number(x)?, number(y)?])
                })
                .collect::<Result<Vec<_>, FiniteError>>()?;
            Region::Polygon { points_mm }
        } else {
            let (r, c) = text.split_once(['x', 'X']).ok_or_else(bad)?;
            Region::Cells {
                rows: r.trim().parse().map_err(|_| bad())?,
                cols: c.trim().parse().map_err(|_| bad())?,
            }
        };
        region.outline(1.0)?;
        Ok(region)
    }
}

impl std::fmt::Display for Region {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Region::Cells { rows, cols } => write!(f, "{rows}x{cols}"),
            Region::Rect {
                width_mm,
                height_mm,
            } => write!(f, "rect:{width_mm},{height_mm}"),
            Region::Disc { radius_mm } => write!(f, "disc:{radius_mm}"),
            Region::Polygon { points_mm } => {
                f.write_str("polygon:")?;
                for (i, p) in points_mm.iter().enumerate() {
                    if i > 0 {
                        f.write_str(";")?;
                    }
                    write!(f, "{},{}", p[0], p[1])?;
                }
                Ok(())
            }
        }
    }
}

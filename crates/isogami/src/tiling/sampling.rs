//! Shape sampling (paper §4.2): a coarse grid over a family's shape parameters, kept to
//! well-shaped tiles.
//!
//! The grid is centred on Kaplan's defaults: each parameter takes `levels` values spread
//! evenly over default ± `span`·max(|default|, 0.25). A sample is kept when the tiling is
//! valid (simple, not inverted, tiles the plane) and the tile is well shaped: every interior
//! angle at least [`MIN_ANGLE_DEG`] (straight 180° vertices are fine), every edge at least
//! [`MIN_EDGE_RATIO`] of the mean edge, and an isoperimetric quotient 4πA/P² of at least
//! [`MIN_ROUNDNESS`] (no slivers). Deterministic; the default parameters are always first;
//! every value is canonical (see [`super::canonical_param`]) and no shape appears twice.

use super::canonical::canonical_param;
use super::family::Family;
use super::shape::Tiling;
use crate::geometry::signed_area;
use crate::math::{cross, Real, Vec2};

/// Smallest interior angle of a well-shaped tile, degrees.
pub const MIN_ANGLE_DEG: Real = 20.0;
/// Shortest edge of a well-shaped tile relative to its mean edge.
pub const MIN_EDGE_RATIO: Real = 0.25;
/// Smallest isoperimetric quotient 4πA/P² of a well-shaped tile (a square has 0.785).
pub const MIN_ROUNDNESS: Real = 0.3;

/// Why a valid tile is not well shaped, if it is not.
pub fn shape_quality_problem(poly: &[Vec2]) -> Option<String> {
    let n = poly.len();
    let lens: Vec<Real> = (0..n)
        .map(|k| (poly[(k + 1) % n] - poly[k]).norm())
        .collect();
    let perimeter: Real = lens.iter().sum();
    let mean = perimeter / n as Real;
    if let Some(k) = (0..n).find(|&k| lens[k] < MIN_EDGE_RATIO * mean) {
        return Some(format!(
            "edge {k} is shorter than {MIN_EDGE_RATIO} of the mean edge"
        ));
    }
    let orient = signed_area(poly).signum();
    for k in 0..n {
        let prev = poly[(k + n - 1) % n] - poly[k];
        let next = poly[(k + 1) % n] - poly[k];
        // Interior angle at vertex k, in (0°, 360°).
        let turn = cross(&next, &prev) * orient;
        let angle = turn.atan2(next.dot(&prev)).to_degrees();
        let interior = if angle < 0.0 { angle + 360.0 } else { angle };
        if interior < MIN_ANGLE_DEG {
            return Some(format!("angle at vertex {k} is {interior:.1}°"));
        }
    }
    let roundness = 4.0 * std::f64::consts::PI * signed_area(poly).abs() / (perimeter * perimeter);
    (roundness < MIN_ROUNDNESS).then(|| format!("tile is a sliver (roundness {roundness:.3})"))
}

/// The interval the shape grid samples each parameter of `family` over: default ±
/// `span`·max(|default|, 0.25), as (low, high) per parameter. Not every point of the box gives
/// a valid tile; the grid keeps those that do and are well shaped.
pub fn param_ranges(family: Family, span: Real) -> Vec<(Real, Real)> {
    half_widths(family, span)
        .into_iter()
        .map(|(d, half)| (d - half, d + half))
        .collect()
}

/// Each default parameter with the half width of its sampling interval.
fn half_widths(family: Family, span: Real) -> Vec<(Real, Real)> {
    family
        .default_params()
        .into_iter()
        .map(|d| (d, span * d.abs().max(0.25)))
        .collect()
}

/// Up to `max_samples` well-shaped parameter vectors of `family` on a grid with `levels`
/// values per parameter (levels ≥ 2; families without parameters give their one shape),
/// evenly spaced over [`param_ranges`].
pub fn shape_grid(family: Family, levels: usize, span: Real, max_samples: usize) -> Vec<Vec<Real>> {
    let defaults = family.default_params();
    let p = defaults.len();
    let mut out = vec![defaults.clone()];
    if p == 0 || levels < 2 || max_samples <= 1 {
        return out;
    }
    let values: Vec<Vec<Real>> = half_widths(family, span)
        .into_iter()
        .map(|(d, half)| {
            (0..levels)
                .map(|i| d - half + 2.0 * half * i as Real / (levels - 1) as Real)
                .collect()
        })
        .collect();
    let total = levels.saturating_pow(p as u32);
    for index in 0..total {
        if out.len() >= max_samples {
            break;
        }
        let mut rest = index;
        let params: Vec<Real> = (0..p)
            .map(|k| {
                let v = values[k][rest % levels];
                rest /= levels;
                canonical_param(v)
            })
            .collect();
        // Canonical values: a grid point that arithmetic put 1e-17 beside the defaults (or
        // beside another point) is that shape, not a second one.
        if out.contains(&params) {
            continue;
        }
        if let Ok(t) = Tiling::new(family, &params) {
            if shape_quality_problem(t.prototile()).is_none() {
                out.push(params);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::vec2;

    #[test]
    fn quality_rejects_slivers_and_sharp_tiles() {
        let square = [
            vec2(0.0, 0.0),
            vec2(1.0, 0.0),
            vec2(1.0, 1.0),
            vec2(0.0, 1.0),
        ];
        assert_eq!(shape_quality_problem(&square), None);
        // A straight vertex (180°) is fine.
        let five = [
            vec2(0.0, 0.0),
            vec2(0.5, 0.0),
            vec2(1.0, 0.0),
            vec2(1.0, 1.0),
            vec2(0.0, 1.0),
        ];
        assert_eq!(shape_quality_problem(&five), None);
        let sliver = [
            vec2(0.0, 0.0),
            vec2(10.0, 0.0),
            vec2(10.0, 0.5),
            vec2(0.0, 0.5),
        ];
        assert!(shape_quality_problem(&sliver).is_some());
        let sharp = [vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 0.2)];
        assert!(shape_quality_problem(&sharp).is_some());
    }

    #[test]
    fn grid_values_lie_in_the_parameter_ranges() {
        for f in Family::all() {
            let ranges = param_ranges(f, 0.3);
            assert_eq!(ranges.len(), f.param_count(), "{f}");
            for (k, (&d, &(lo, hi))) in f.default_params().iter().zip(&ranges).enumerate() {
                assert!(lo < d && d < hi, "{f} v{k}: {lo} < {d} < {hi}");
            }
            for p in shape_grid(f, 3, 0.3, 40) {
                for (k, (&v, &(lo, hi))) in p.iter().zip(&ranges).enumerate() {
                    assert!(
                        lo - 1e-12 <= v && v <= hi + 1e-12,
                        "{f} v{k}: {v} outside [{lo}, {hi}]"
                    );
                }
            }
        }
    }

    #[test]
    fn grids_are_valid_well_shaped_and_deterministic() {
        let mut with_samples = 0;
        for f in Family::all() {
            let g = shape_grid(f, 3, 0.3, 40);
            assert_eq!(g[0], f.default_params(), "{f}: defaults first");
            assert!(g.len() <= 40);
            for p in &g[1..] {
                let t = Tiling::new(f, p).unwrap();
                assert!(shape_quality_problem(t.prototile()).is_none());
            }
            assert_eq!(g, shape_grid(f, 3, 0.3, 40), "{f}: deterministic");
            if g.len() > 1 {
                with_samples += 1;
            }
        }
        assert!(
            with_samples > 40,
            "most families with parameters get samples: {with_samples}"
        );
    }
}

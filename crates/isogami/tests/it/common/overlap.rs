//! An overlap check of deployment reports that shares nothing with the library's contact code
//! but the kerf inset: it places every tile from the report's poses (vertex ↦
//! R(θ)(v − centroid) plus (x, y); copies shifted by k_u·u + k_w·w), enumerates lattice copies
//! by brute force over a block sized from nalgebra's singular values of [u w], and measures
//! overlap with `geo`'s polygon intersection.
#![allow(dead_code)]

use geo::{Area, BooleanOps, Coord, LineString, Polygon};
use isogami::contact::inset_polygon;
use isogami::deploy::{DeploymentReport, FrameReport};
use isogami::math::{rotation, Real, Vec2};
use isogami::topology::Design;

/// Intersection areas above this fraction of L² count as overlap (geo's boolean operations
/// work on a snapped grid; touching polygons give areas near 1e-15).
pub const AREA_TOL: Real = 1e-9;

fn to_geo(poly: &[Vec2]) -> Polygon<Real> {
    let ring: Vec<Coord<Real>> = poly.iter().map(|v| Coord { x: v.x, y: v.y }).collect();
    Polygon::new(LineString::new(ring), vec![])
}

/// Each tile's polygon about its centroid, inset by half the report's kerf (tiling units).
fn collision_shapes(design: &Design, report: &DeploymentReport) -> Vec<Vec<Vec2>> {
    let cell = design.cell().expect("the design builds");
    let h = 0.5 * report.kerf * report.length_scale;
    cell.tiles
        .iter()
        .map(|t| {
            let local: Vec<Vec2> = t.polygon.iter().map(|v| v - t.centroid).collect();
            inset_polygon(&local, h).expect("the kerf fits every tile")
        })
        .collect()
}

/// The centre cell's polygons at a frame's poses: vertex v ↦ R(θ)v + (x, y).
fn place(frame: &FrameReport, shapes: &[Vec<Vec2>]) -> Vec<Vec<Vec2>> {
    frame
        .tiles
        .iter()
        .zip(shapes)
        .map(|(t, s)| {
            let r = rotation(t.theta);
            s.iter().map(|v| r * v + Vec2::new(t.x, t.y)).collect()
        })
        .collect()
}

/// Every overlap found in the report's frames, as readable lines (empty when none).
pub fn report_overlaps(design: &Design, report: &DeploymentReport) -> Vec<String> {
    let l = report.length_scale;
    let shapes = collision_shapes(design, report);
    let radii: Vec<Real> = shapes
        .iter()
        .map(|s| s.iter().map(|v| v.norm()).fold(0.0, Real::max))
        .collect();
    let rmax = radii.iter().copied().fold(0.0, Real::max);
    let mut found = Vec::new();
    for (f, frame) in report.frames.iter().enumerate() {
        let (u, w) = (Vec2::from(frame.u), Vec2::from(frame.w));
        let centres: Vec<Vec2> = frame.tiles.iter().map(|t| Vec2::new(t.x, t.y)).collect();
        let placed = place(frame, &shapes);
        let sigma = nalgebra::Matrix2::from_columns(&[u, w])
            .singular_values()
            .min();
        assert!(sigma > 0.0, "frame {f}: degenerate lattice");
        let dmax = centres
            .iter()
            .flat_map(|a| centres.iter().map(move |b| (a - b).norm()))
            .fold(0.0, Real::max);
        // |k_u·u + k_w·w| ≥ σ‖k‖: copies beyond this block cannot reach a centre tile.
        let span = ((dmax + 2.0 * rmax) / sigma).ceil() as i32 + 1;
        for a in 0..placed.len() {
            let pa = to_geo(&placed[a]);
            for b in 0..placed.len() {
                for ku in -span..=span {
                    for kw in -span..=span {
                        if a == b && (ku, kw) == (0, 0) {
                            continue;
                        }
                        let shift = u * Real::from(ku) + w * Real::from(kw);
                        if (centres[b] + shift - centres[a]).norm() > radii[a] + radii[b] {
                            continue;
                        }
                        let pb: Vec<Vec2> = placed[b].iter().map(|v| v + shift).collect();
                        let area = pa.intersection(&to_geo(&pb)).unsigned_area();
                        if area > AREA_TOL * l * l {
                            found.push(format!(
                                "frame {f} (t = {:.3}, step {}): tile {a} overlaps tile {b} of cell ({ku}, {kw}), area {:.3e} L²",
                                frame.t,
                                frame.step,
                                area / (l * l)
                            ));
                        }
                    }
                }
            }
        }
    }
    found
}

/// The smallest distance, over the report's frames, between a collision polygon of the centre
/// cell and one of a copy outside the 3×3 block of cells (|k_u| or |k_w| ≥ 2): how closely
/// the deployment met tiles that a fixed 3×3 contact search would not see.
pub fn far_copy_min_distance(design: &Design, report: &DeploymentReport) -> Real {
    use geo::{Distance, Euclidean};
    let l = report.length_scale;
    let shapes = collision_shapes(design, report);
    let mut best = Real::INFINITY;
    for frame in &report.frames {
        let (u, w) = (Vec2::from(frame.u), Vec2::from(frame.w));
        let placed = place(frame, &shapes);
        for a in &placed {
            let pa = to_geo(a);
            for b in &placed {
                for ku in -4i32..=4 {
                    for kw in -4i32..=4 {
                        if ku.abs() < 2 && kw.abs() < 2 {
                            continue;
                        }
                        let shift = u * Real::from(ku) + w * Real::from(kw);
                        let pb: Vec<Vec2> = b.iter().map(|v| v + shift).collect();
                        best = best.min(Euclidean.distance(&pa, &to_geo(&pb)) / l);
                    }
                }
            }
        }
    }
    best
}

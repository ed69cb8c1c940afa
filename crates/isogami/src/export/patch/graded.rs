//! A graded sheet (issue 25) as a [`Patch`], so that every export format writes it.
//!
//! A graded sheet's tiles each have their own closed shape ([`GradedSheet`]: nodes, tiles as
//! node lists, pins at nodes, one pose per tile in each state). Its patch is:
//!
//! - the **closed sheet** (what a laser cuts): every tile's polygon at its nodes;
//! - its **states**, closed first: the closed sheet, then the states part of the way — the
//!   path check's ([`PathCheck`], what `isogami graded` writes beside the sheet) when given,
//!   else the sheet's own [`GradedSheet::path`] — then the optimised opened state
//!   ([`GradedSheet::opened`]). A state's `t` is its opening as a fraction of the opened
//!   state's (0 closed, 1 opened). The path check's states are turned rigidly by a share of
//!   the turn its closed end has (none at the opened end, all of it at the closed end), so
//!   that an animation neither jumps at the closed end nor spins; a rigid motion of the
//!   whole sheet keeps every pin closed;
//! - the **exported state** ([`State::T`]: the state of nearest opening; [`State::Open`]: the
//!   optimised one) placed as [`Patch::tiles`].
//!
//! Scale: [`Scale::EdgeMm`] is the mean length of the closed sheet's edges (each edge once),
//! [`Scale::WidthMm`] the width at the exported state. Joints, outline loops and every set of
//! polygons are placed as a design's patch places them (see the parent module); which edges
//! are on the outline is read from the node lists (an edge no other tile has), never from
//! positions. What the sheet is as a mechanism is counted on its own pins
//! ([`GradedMobility`]). [`read_graded`] reads the JSON `isogami graded --out` writes.

use super::mobility::GradedMobility;
use super::place::{all_finite, bounds, outline_loops, polygons_mm, split_loops};
use super::request::{check_scale_state_frames, scale_value};
use super::{Patch, PatchJoint, PatchState, PatchTile, Scale, State};
use crate::cell::{End, UnitCell};
use crate::export::error::ExportError;
use crate::geometry::{centroid, convex_hull, signed_area};
use crate::graded::{GradedError, GradedSheet, OpenedPose, PathCheck};
use crate::math::{rotation, Real, Vec2};
use std::collections::BTreeMap;

/// How to write a graded sheet: its scale, the state placed as the patch's tiles, and how
/// many states animated formats keep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradedPatchRequest {
    /// Millimetres: the mean edge length of the closed sheet, or its width at the state.
    pub scale: Scale,
    /// The state: [`State::T`] an opening in [0, 1] (the state of nearest opening; 0 closed,
    /// 1 the optimised opened state), [`State::Open`] the optimised opened state.
    pub state: State,
    /// Most states kept in [`Patch::states`] (2..=[`super::MAX_PATCH_FRAMES`]): all of them
    /// when there are no more, else those nearest to evenly spaced openings (the closed and
    /// the opened state always).
    pub frames: usize,
}

impl Default for GradedPatchRequest {
    /// 20 mm mean edge, closed, 11 states: a design's patch's defaults.
    fn default() -> Self {
        let d = super::PatchRequest::default();
        GradedPatchRequest {
            scale: d.scale,
            state: d.state,
            frames: d.frames,
        }
    }
}

impl GradedPatchRequest {
    /// Checks the scale, state and frame count against a design's patch's limits.
    pub fn validate(&self) -> Result<(), ExportError> {
        check_scale_state_frames(self.scale, self.state, self.frames)
    }
}

/// A graded sheet as read from a file, with its path check when the file has one.
#[derive(Debug, Clone, PartialEq)]
pub struct GradedInput {
    /// The sheet (checked by [`GradedSheet::validate`]).
    pub sheet: GradedSheet,
    /// The path check written beside it, if any.
    pub path: Option<PathCheck>,
}

/// Reads a graded sheet from JSON: what `isogami graded --out` writes (an object with the
/// `sheet`, its `report` and its `path` check) or a bare [`GradedSheet`]. Refuses text that
/// is not JSON (NaN included), JSON that is not a graded sheet, and a sheet that fails
/// [`GradedSheet::validate`], in one line naming the problem.
pub fn read_graded(text: &str) -> Result<GradedInput, ExportError> {
    let read = |reason: String| ExportError::Read {
        format: "graded sheet",
        reason,
    };
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| read(format!("not JSON ({e})")))?;
    if !value.is_object() {
        return Err(read("not a graded sheet (expected a JSON object)".into()));
    }
    let (sheet, path) = match value.get("sheet") {
        Some(sheet) => (sheet.clone(), value.get("path").cloned()),
        None => (value, None),
    };
    let sheet: GradedSheet =
        serde_json::from_value(sheet).map_err(|e| read(format!("not a graded sheet ({e})")))?;
    let path: Option<PathCheck> = path
        .map(serde_json::from_value)
        .transpose()
        .map_err(|e| read(format!("its path check cannot be read ({e})")))?;
    sheet.validate().map_err(crate::Error::from)?;
    if let Some(p) = &path {
        check_path_states(&sheet, p)?;
    }
    Ok(GradedInput { sheet, path })
}

/// One state of the sheet: its opening and a pose per tile.
struct Posed {
    opening: Real,
    poses: Vec<OpenedPose>,
}

/// The patch of a graded sheet (see the module docs); `path` is its path check, if any.
pub fn graded_patch(
    sheet: &GradedSheet,
    path: Option<&PathCheck>,
    request: &GradedPatchRequest,
) -> Result<Patch, ExportError> {
    request.validate()?;
    sheet.validate().map_err(crate::Error::from)?;
    if let Some(p) = path {
        check_path_states(sheet, p)?;
    }
    let design = crate::api::resolve_design(&sheet.design)?;
    let cell = design.cell().map_err(crate::Error::from)?;
    let vertex_of = |tile: usize, node: usize| {
        sheet.tiles[tile]
            .nodes
            .iter()
            .position(|&n| n == node)
            .expect("validated: a pin's node is a corner of its tiles")
    };
    let edges = joint_edges(sheet, &cell, &vertex_of)?;

    let all = states(sheet, path);
    let chosen = match request.state {
        State::T(t) => (0..all.len())
            .min_by(|&a, &b| {
                (all[a].opening - t)
                    .abs()
                    .total_cmp(&(all[b].opening - t).abs())
            })
            .expect("a sheet has states"),
        State::Open | State::Limit => all.len() - 1,
    };
    let at_state = placed(sheet, &all[chosen].poses);
    let closed = placed(sheet, &all[0].poses);
    let (lo, hi) = bounds(&at_state);
    let mean_edge = mean_edge(sheet);
    let per_unit = match request.scale {
        Scale::EdgeMm(mm) => mm / mean_edge,
        Scale::WidthMm(mm) => mm / (hi[0] - lo[0]),
    };
    if !(per_unit.is_finite() && per_unit > 0.0) {
        return Err(ExportError::Degenerate {
            what: match request.scale {
                Scale::EdgeMm(_) => "mean edge length",
                Scale::WidthMm(_) => "width",
            },
        });
    }
    let tiles: Vec<PatchTile> = polygons_mm(&at_state, per_unit)
        .into_iter()
        .enumerate()
        .map(|(id, polygon_mm)| {
            let c = centroid(
                &polygon_mm
                    .iter()
                    .map(|p| Vec2::new(p[0], p[1]))
                    .collect::<Vec<_>>(),
            );
            PatchTile {
                id,
                tile: sheet.tiles[id].tile,
                cell: sheet.tiles[id].cell,
                polygon_mm,
                centroid_mm: [c.x, c.y],
                rotation: all[chosen].poses[id].theta,
            }
        })
        .collect();
    let closed_polygons_mm = polygons_mm(&closed, per_unit);
    let states: Vec<PatchState> = keep_states(&all, request.frames)
        .into_iter()
        .map(|k| PatchState {
            t: all[k].opening,
            polygons_mm: polygons_mm(&placed(sheet, &all[k].poses), per_unit),
        })
        .collect();
    let joints = sheet
        .joints
        .iter()
        .zip(edges)
        .map(|(j, (edge, end))| {
            let vertex_a = vertex_of(j.a, j.node);
            PatchJoint {
                a: j.a,
                b: j.b,
                point_mm: tiles[j.a].polygon_mm[vertex_a],
                edge,
                end: if end == End::A { 'a' } else { 'b' },
                vertex_a,
                vertex_b: vertex_of(j.b, j.node),
            }
        })
        .collect();
    let edge_mm = mean_edge * per_unit;
    let shared = edge_counts(sheet);
    let on_boundary = |id: usize, k: usize| {
        let nodes = &sheet.tiles[id].nodes;
        shared[&edge_key(nodes[k], nodes[(k + 1) % nodes.len()])] == 1
    };
    let loops = outline_loops(&closed_polygons_mm, on_boundary, 1e-7 * edge_mm);
    let (outline_mm, outline_vertices) = split_loops(&loops);
    let numbers = all_finite(tiles.iter().map(|t| &t.polygon_mm))
        && all_finite(&closed_polygons_mm)
        && all_finite(states.iter().flat_map(|s| &s.polygons_mm));
    if !numbers {
        let (what, value) = scale_value(request.scale);
        return Err(ExportError::BadSize { what, value });
    }
    let finite = mobility(sheet, &all, path).patch_mobility(sheet.tiles.len());
    let span = |d: usize| {
        let (lo, hi) = sheet.tiles.iter().fold((i32::MAX, i32::MIN), |(l, h), t| {
            (l.min(t.cell[d]), h.max(t.cell[d]))
        });
        (hi - lo + 1) as usize
    };
    Ok(Patch {
        design: sheet.design.clone(),
        rows: span(1),
        cols: span(0),
        tiles_per_cell: cell.tiles.len(),
        finite,
        // The path check looks for overlapping tiles, not for tiles nearer than a kerf.
        kerf: 0.0,
        edge_mm,
        mm_per_unit: per_unit / sheet.length_scale,
        t: all[chosen].opening,
        area_ratio: hull_area(&at_state) / hull_area(&closed),
        size_mm: [(hi[0] - lo[0]) * per_unit, (hi[1] - lo[1]) * per_unit],
        tiles,
        joints,
        closed_polygons_mm,
        outline_mm,
        outline_vertices,
        states,
    })
}

/// The path check's states fit the sheet: a pose per tile, finite numbers, openings in
/// [0, 1].
fn check_path_states(sheet: &GradedSheet, path: &PathCheck) -> Result<(), ExportError> {
    let bad = |m: String| ExportError::from(crate::Error::from(GradedError::BadSheet(m)));
    for (k, s) in path.states.iter().enumerate() {
        if s.poses.len() != sheet.tiles.len() {
            return Err(bad(format!(
                "state {k} of its path check has {} poses for {} tiles",
                s.poses.len(),
                sheet.tiles.len()
            )));
        }
        let finite = |p: &OpenedPose| p.x.is_finite() && p.y.is_finite() && p.theta.is_finite();
        if !(0.0..=1.0).contains(&s.opening) || !s.poses.iter().all(finite) {
            return Err(bad(format!(
                "state {k} of its path check is not an opening in [0, 1] with finite poses"
            )));
        }
    }
    Ok(())
}

/// Every state of the sheet, closed first and the optimised opened state last.
fn states(sheet: &GradedSheet, path: Option<&PathCheck>) -> Vec<Posed> {
    let closed = Posed {
        opening: 0.0,
        poses: sheet
            .tiles
            .iter()
            .map(|t| OpenedPose {
                x: sheet.nodes[t.nodes[0]][0],
                y: sheet.nodes[t.nodes[0]][1],
                theta: 0.0,
            })
            .collect(),
    };
    let mut all = vec![closed];
    match path {
        Some(p) => {
            // The turn of the path check's closed end (every tile turned alike there).
            let turn = p.states.iter().find(|s| s.opening == 0.0).map_or(0.0, |s| {
                s.poses.iter().map(|q| q.theta).sum::<Real>() / s.poses.len() as Real
            });
            let mut between: Vec<&crate::graded::PathState> = p
                .states
                .iter()
                .filter(|s| s.opening > 0.0 && s.opening < 1.0)
                .collect();
            between.sort_by(|a, b| a.opening.total_cmp(&b.opening));
            all.extend(between.into_iter().map(|s| Posed {
                opening: s.opening,
                poses: turned(&s.poses, -turn * (1.0 - s.opening)),
            }));
        }
        None => {
            let signs = crate::graded::joint_signs(sheet);
            let opening = |poses: &[OpenedPose]| -> Real {
                crate::graded::mean_opening(poses, sheet, &signs)
            };
            let full = opening(&sheet.opened);
            let n = sheet.path.len();
            all.extend(sheet.path.iter().enumerate().map(|(k, poses)| Posed {
                // A sheet whose pins do not turn: its states spaced evenly.
                opening: if full.abs() > 1e-12 {
                    opening(poses) / full
                } else {
                    (k + 1) as Real / (n + 1) as Real
                },
                poses: poses.clone(),
            }));
        }
    }
    all.push(Posed {
        opening: 1.0,
        poses: sheet.opened.clone(),
    });
    all
}

/// Poses turned rigidly by `angle` about the origin.
fn turned(poses: &[OpenedPose], angle: Real) -> Vec<OpenedPose> {
    let r = rotation(angle);
    poses
        .iter()
        .map(|p| {
            let q = r * Vec2::new(p.x, p.y);
            OpenedPose {
                x: q.x,
                y: q.y,
                theta: p.theta + angle,
            }
        })
        .collect()
}

/// Indices of the states kept (see [`GradedPatchRequest::frames`]).
fn keep_states(all: &[Posed], frames: usize) -> Vec<usize> {
    if all.len() <= frames {
        return (0..all.len()).collect();
    }
    let mut kept: Vec<usize> = (0..frames)
        .map(|k| {
            let want = k as Real / (frames - 1) as Real;
            (0..all.len())
                .min_by(|&a, &b| {
                    (all[a].opening - want)
                        .abs()
                        .total_cmp(&(all[b].opening - want).abs())
                })
                .expect("a sheet has states")
        })
        .collect();
    kept[0] = 0;
    kept[frames - 1] = all.len() - 1;
    kept.sort_unstable();
    kept.dedup();
    kept
}

/// Every tile's polygon placed by `poses` (units of the length scale).
fn placed(sheet: &GradedSheet, poses: &[OpenedPose]) -> Vec<Vec<[Real; 2]>> {
    sheet
        .tiles
        .iter()
        .zip(poses)
        .map(|(t, pose)| {
            let r = rotation(pose.theta);
            let first = sheet.node(t.nodes[0]);
            t.nodes
                .iter()
                .map(|&n| {
                    let p = Vec2::new(pose.x, pose.y) + r * (sheet.node(n) - first);
                    [p.x, p.y]
                })
                .collect()
        })
        .collect()
}

fn edge_key(p: usize, q: usize) -> (usize, usize) {
    (p.min(q), p.max(q))
}

/// How many tiles have each closed edge (node pair): 1 on the outline, 2 inside.
fn edge_counts(sheet: &GradedSheet) -> BTreeMap<(usize, usize), usize> {
    // Ordered: the mean edge sums over it, and a sum in a hash map's per-process order made
    // the export's millimetres differ in the last bits from run to run.
    let mut count = BTreeMap::new();
    for t in &sheet.tiles {
        let n = t.nodes.len();
        for v in 0..n {
            *count
                .entry(edge_key(t.nodes[v], t.nodes[(v + 1) % n]))
                .or_insert(0) += 1;
        }
    }
    count
}

/// Mean length of the closed sheet's edges, each edge once (units of the length scale).
fn mean_edge(sheet: &GradedSheet) -> Real {
    let edges = edge_counts(sheet);
    let total: Real = edges
        .keys()
        .map(|&(p, q)| (sheet.node(p) - sheet.node(q)).norm())
        .sum();
    total / edges.len() as Real
}

/// Area of the convex hull of polygons' corners.
fn hull_area(polys: &[Vec<[Real; 2]>]) -> Real {
    let points: Vec<Vec2> = polys
        .iter()
        .flatten()
        .map(|p| Vec2::new(p[0], p[1]))
        .collect();
    signed_area(&convex_hull(&points))
}

/// The design's cell edge and end of every pin: the edge from the pin's first tile to its
/// second (their cells offset as the edge says) with the pin's node at that end on both.
fn joint_edges(
    sheet: &GradedSheet,
    cell: &UnitCell,
    vertex_of: &dyn Fn(usize, usize) -> usize,
) -> Result<Vec<(usize, End)>, ExportError> {
    let bad = |m: String| ExportError::from(crate::Error::from(GradedError::BadSheet(m)));
    for (i, t) in sheet.tiles.iter().enumerate() {
        let corners = cell.tiles.get(t.tile).map(|c| c.polygon.len());
        if corners != Some(t.nodes.len()) {
            return Err(bad(format!(
                "tile {i} is not a tile of its design's cell (tile index {}, {} corners)",
                t.tile,
                t.nodes.len()
            )));
        }
    }
    sheet
        .joints
        .iter()
        .enumerate()
        .map(|(k, j)| {
            let (ta, tb) = (&sheet.tiles[j.a], &sheet.tiles[j.b]);
            let (va, vb) = (vertex_of(j.a, j.node), vertex_of(j.b, j.node));
            cell.edges
                .iter()
                .enumerate()
                .filter(|(_, e)| {
                    e.tile_a == ta.tile
                        && e.tile_b == tb.tile
                        && [ta.cell[0] + e.offset[0], ta.cell[1] + e.offset[1]] == tb.cell
                })
                .flat_map(|(e, _)| [(e, End::A), (e, End::B)])
                .find(|&(e, end)| {
                    cell.endpoint_index_on_a(e, end) == va && cell.endpoint_index_on_b(e, end) == vb
                })
                .ok_or_else(|| {
                    bad(format!(
                        "pin {k} is not at the end of an edge of its design's cell"
                    ))
                })
        })
        .collect()
}

/// The sheet as a mechanism: its degrees of freedom at the opened state nearest half open.
fn mobility(sheet: &GradedSheet, all: &[Posed], path: Option<&PathCheck>) -> GradedMobility {
    let at = (1..all.len())
        .min_by(|&a, &b| {
            (all[a].opening - 0.5)
                .abs()
                .total_cmp(&(all[b].opening - 0.5).abs())
        })
        .expect("a sheet has an opened state");
    let posed = GradedSheet {
        opened: all[at].poses.clone(),
        path: Vec::new(),
        ..sheet.clone()
    };
    GradedMobility {
        counted_at: all[at].opening,
        dof: crate::graded::deploy::dof(&posed).map(|(d, _)| d),
        path_reached: path.map(|p| p.reached),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::{graded_sheet, GradedRun};
    use crate::graded::{GradedRequest, SolveSettings};

    fn small() -> GradedRun {
        let request = GradedRequest {
            rows: 2,
            cols: 2,
            states: 4,
            solve: SolveSettings {
                max_iterations: 80,
                ..SolveSettings::default()
            },
            ..GradedRequest::default()
        };
        graded_sheet(&request, &mut |_| true, crate::stop::NEVER).unwrap()
    }

    fn largest_turn(poses: &[OpenedPose]) -> Real {
        poses.iter().map(|p| p.theta.abs()).fold(0.0, Real::max)
    }

    /// The path check ends at the closed tiling turned as a whole (by however much); its
    /// states are turned back so that the one next to closed is nearly unturned (no jump to
    /// the closed sheet), whatever that turn; the optimised state is the sheet's own; the DOF
    /// is counted at half open.
    /// The same sheet places to the same bits every time (the mean edge, the millimetres'
    /// scale, was once summed in a hash map's per-instance order).
    #[test]
    fn placing_is_deterministic_to_the_bit() {
        let run = small();
        let request = GradedPatchRequest::default();
        let first =
            serde_json::to_string(&graded_patch(&run.sheet, Some(&run.path), &request).unwrap())
                .unwrap();
        for _ in 0..8 {
            let again = serde_json::to_string(
                &graded_patch(&run.sheet, Some(&run.path), &request).unwrap(),
            )
            .unwrap();
            assert!(again == first, "the patch differs between two placements");
        }
    }

    #[test]
    fn path_states_meet_the_closed_sheet_and_the_count_is_at_half_open() {
        let run = small();
        // The same path turned as a whole by a further 0.7 rad: a path check just as right.
        let mut spun = run.path.clone();
        for s in &mut spun.states {
            s.poses = turned(&s.poses, 0.7);
        }
        let next = |p: &PathCheck| {
            p.states
                .iter()
                .filter(|s| s.opening > 0.0)
                .min_by(|a, b| a.opening.total_cmp(&b.opening))
                .unwrap()
                .clone()
        };
        let turn = largest_turn(&next(&spun).poses);
        assert!(turn > 0.3, "{turn}");
        for path in [&run.path, &spun] {
            let all = states(&run.sheet, Some(path));
            assert_eq!(all.len(), path.states.len());
            assert_eq!(all[0].opening, 0.0);
            assert!(all[0].poses.iter().all(|p| p.theta == 0.0));
            assert_eq!(all[1].opening, next(path).opening);
            assert!(
                largest_turn(&all[1].poses) < 0.25 * turn,
                "{} vs {turn}",
                largest_turn(&all[1].poses)
            );
            assert!(all.windows(2).all(|w| w[0].opening < w[1].opening));
            assert_eq!(all.last().unwrap().poses, run.sheet.opened);
        }

        let patch =
            graded_patch(&run.sheet, Some(&run.path), &GradedPatchRequest::default()).unwrap();
        let g = patch.finite.graded.as_ref().unwrap();
        assert_eq!(g.counted_at, 0.5);
        let half = run.path.states.iter().find(|s| s.opening == 0.5).unwrap();
        assert_eq!(g.dof, half.dof);
        assert_eq!(g.path_reached, Some(run.path.reached));
        assert_eq!(
            patch.finite.warning().is_some(),
            !run.path.reached || g.dof != Some(1)
        );
    }

    #[test]
    fn keep_states_thins_to_evenly_spaced_openings_ends_included() {
        let posed = |opening: Real| Posed {
            opening,
            poses: Vec::new(),
        };
        let all: Vec<Posed> = [0.0, 0.1, 0.2, 0.45, 0.5, 0.9, 1.0]
            .into_iter()
            .map(posed)
            .collect();
        assert_eq!(keep_states(&all, 3), [0, 4, 6]);
        assert_eq!(keep_states(&all, 7), [0, 1, 2, 3, 4, 5, 6]);
        assert_eq!(keep_states(&all[..2], 5), [0, 1]);
    }
}

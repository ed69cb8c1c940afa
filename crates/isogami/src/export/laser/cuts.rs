//! The cut layout of a laser sheet: where the beam runs, where bridges of material stay.
//!
//! Every tile edge is cut, except a bridge of `hinge_mm` at each joint, and the patch is cut
//! out along its outline. All paths are beam centrelines, compensated for the kerf `k`:
//!
//! * **Cuts between two tiles.** Both sides are parts, so the waste is the slot itself: the
//!   centreline runs on the design edge and each tile loses `k/2`, which is exactly the
//!   kerf-inset tile the contact model simulates. Compensation shows at the cut ends: a cut
//!   that stops at a bridge stops `k/2` short of it, so its round burn ends on the bridge.
//! * **The outline.** The waste is outside the patch: the outline path is moved `k/2`
//!   outwards (mitred corners) so the burn's inner edge is the design outline.
//! * **Bridges.** A joint of tiles A and B at vertex V sits on the edge e that A and B share,
//!   as the span `[s0, s0 + h]` measured from V along e. Material crosses e exactly there: the
//!   cut of e resumes at `s0 + h + k/2`, and e is cleared from V to `s0` by a short stub cut
//!   from V (to `s0 - k/2`) or, when `s0 = k/2`, by the round end of another cut at V. So no
//!   bridge touches V, no two tiles meet at V, and each bridge holds only A and B even where
//!   three or more tiles meet. `s0` is the least distance at which every other burn at V
//!   (other cuts, stubs, outline, relief) stays at least `h` from the bridge's far end: for
//!   a burn of half-width c along a ray at angle φ < 90° from e,
//!   `s0 ≥ (h + k/2 + c)/sin φ − h − k/2`, else `s0 ≥ c`. The other end W of e is kept clear
//!   the same way when no bridge sits there: the cut of e runs into W, so the burns at W
//!   belong to the far side of the bridge, and the bridge must end at least the same
//!   distance (with W's burns) short of W, or those burns eat into it (issue 23 item 12:
//!   bridges of 1.447 mm with 0.81 mm necks for a 1.5 mm hinge on 2.9 mm edges). Hence the
//!   narrowest section of the bridge is `h`, along e, and its length is `h`.
//! * **Relief cuts.** Where two or more tiles meet on the outline at a corner the material
//!   wraps round (reflex), a round beam cannot clear the waste corner and would leave a
//!   sliver joining the tiles: a short cut runs from V out to the outline path.
//!
//! A bridge that does not fit on its edge (hinge wider than the edge, or too little room
//! left for the cut between the bridges or for the clearance at the far end) is refused,
//! naming the edge that needs the most room relative to its length: every length the
//! bridges need is independent of the patch's scale, so that edge fixes the smallest
//! scale that works ([`super::laser_sheet`] turns it into the smallest `edge_mm`).

use super::error::LaserError;
use super::graph::PatchGraph;
use super::outline::outline_loops;
use super::JointAt;
use crate::math::{cross, Real, Vec2};
use serde::Serialize;

/// A straight cut: the beam's centreline from `a` to `b` (mm).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Cut {
    /// Start.
    pub a: Vec2,
    /// End.
    pub b: Vec2,
}

/// A bridge: where the material joining two tiles crosses their shared edge.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Bridge {
    /// The joint's two tiles.
    pub tiles: [usize; 2],
    /// The joint point (a tiling vertex).
    pub joint: Vec2,
    /// End of the span nearer the joint.
    pub from: Vec2,
    /// Far end of the span: `|to - from|` is the hinge width.
    pub to: Vec2,
}

/// Everything the laser draws, in the patch's millimetres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CutLayout {
    /// Cuts between tiles: edge cuts, stubs and relief cuts.
    pub cuts: Vec<Cut>,
    /// The outline cut: closed paths, offset by half the kerf into the waste.
    pub outline: Vec<Vec<Vec2>>,
    /// The design outline of the patch (not cut; for drawings and checks).
    pub boundary: Vec<Vec<Vec2>>,
    /// One bridge per joint end.
    pub bridges: Vec<Bridge>,
}

/// A burn near a vertex: a ray from the vertex along `dir` with half-width `c` (`c = 0` for
/// the material's own outline edge, whose burn lies wholly outside it).
struct Burn {
    dir: Vec2,
    c: Real,
}

/// Lays out the cuts of `tiles` (counter-clockwise polygons, mm) with a bridge of
/// `hinge` at each of `joints`, compensated for `kerf`. Both sizes must be positive and
/// finite (checked by [`super::LaserSettings::validate`]).
pub fn layout_cuts(
    tiles: &[Vec<[Real; 2]>],
    joints: &[JointAt],
    hinge: Real,
    kerf: Real,
) -> Result<CutLayout, LaserError> {
    let g = PatchGraph::new(tiles, joints)?;
    let hk = 0.5 * kerf;
    let eps = 1e-6 * (1.0 + kerf);
    let loops = outline_loops(&g, hk);

    // Relief cuts at reflex outline corners where an edge between two tiles ends.
    let mut reliefs: Vec<Option<Vec2>> = vec![None; g.points.len()];
    for lp in &loops {
        let n = lp.vertices.len();
        for k in 0..n {
            let v = lp.vertices[k];
            let before = g.point(lp.vertices[(k + n - 1) % n]);
            let after = g.point(lp.vertices[(k + 1) % n]);
            let turn = cross(&(g.point(v) - before), &(after - g.point(v)));
            let inner = g.star[v].iter().any(|&e| g.edges[e].right.is_some());
            if inner && turn < 0.0 {
                reliefs[v] = Some(lp.cut[k]);
            }
        }
    }
    // A vertex is cleared when some burn is centred on it: an edge cut that runs to it, or a
    // relief cut.
    let cleared: Vec<bool> = (0..g.points.len())
        .map(|v| {
            reliefs[v].is_some()
                || g.star[v].iter().any(|&e| {
                    let edge = &g.edges[e];
                    edge.right.is_some() && !edge.joint[usize::from(edge.v[1] == v)]
                })
        })
        .collect();

    let mut cuts = Vec::new();
    let mut bridges = Vec::new();
    // The edge that needs the most room for its length: (needed / length, error).
    let mut worst: Option<(Real, LaserError)> = None;
    for (ei, edge) in g.edges.iter().enumerate() {
        let Some(right) = edge.right else { continue };
        let tiles_ab = [edge.left, right];
        let (t, len) = g.leaving(ei, edge.v[0]);
        let p0 = g.point(edge.v[0]);
        // Along the edge from end 0: where the main cut starts and ends.
        let mut start = 0.0;
        let mut end = len;
        for side in 0..2 {
            if !edge.joint[side] {
                continue;
            }
            let v = edge.v[side];
            let dir = if side == 0 { t } else { -t };
            let burns = burns_at(&g, v, ei, &reliefs, hk);
            let mut s0 = (if cleared[v] { hk } else { 0.0 }).max(clearance(&burns, dir, hinge, hk));
            if !cleared[v] && s0 > 0.0 {
                // Nothing burns at V: a stub from V must clear the edge up to the bridge.
                s0 = s0.max(kerf);
            }
            let mut stub = s0 - hk;
            if stub < eps {
                // No stub: V's own burn (cleared) clears the edge to k/2, or the bridge starts
                // at V on the outline (s0 = 0).
                stub = 0.0;
                if s0 > 0.0 {
                    s0 = hk;
                }
            }
            let vp = g.point(v);
            if stub > 0.0 {
                cuts.push(Cut {
                    a: vp,
                    b: vp + dir * stub,
                });
            }
            bridges.push(Bridge {
                tiles: tiles_ab,
                joint: vp,
                from: vp + dir * s0,
                to: vp + dir * (s0 + hinge),
            });
            let resume = s0 + hinge + hk;
            if side == 0 {
                start = resume;
            } else {
                end = len - resume;
            }
        }
        // A bridge at one end only: the cut of e runs into the other end, whose burns must
        // stay clear of the bridge as those at the joint do.
        let mut room = end - start - eps;
        for side in 0..2 {
            if edge.joint[side] && !edge.joint[1 - side] {
                let w = edge.v[1 - side];
                let dir = if side == 0 { -t } else { t };
                let burns = burns_at(&g, w, ei, &reliefs, hk);
                room = room.min(end - start + hk - clearance(&burns, dir, hinge, hk));
            }
        }
        if room.is_nan() || room <= 0.0 {
            let needed = len - room;
            let ratio = if needed.is_finite() {
                needed / len
            } else {
                Real::INFINITY
            };
            if worst.as_ref().is_none_or(|(r, _)| ratio > *r) {
                let e = LaserError::HingeTooWide {
                    hinge_mm: hinge,
                    edge_mm: len,
                    needed_mm: needed,
                    tiles: tiles_ab,
                };
                worst = Some((ratio, e));
            }
            continue;
        }
        cuts.push(Cut {
            a: p0 + t * start,
            b: p0 + t * end,
        });
    }
    if let Some((_, e)) = worst {
        return Err(e);
    }
    for (v, relief) in reliefs.iter().enumerate() {
        if let Some(p) = relief {
            cuts.push(Cut {
                a: g.point(v),
                b: *p,
            });
        }
    }
    let boundary = loops
        .iter()
        .map(|lp| lp.vertices.iter().map(|&v| g.point(v)).collect())
        .collect();
    Ok(CutLayout {
        cuts,
        outline: loops.into_iter().map(|lp| lp.cut).collect(),
        boundary,
        bridges,
    })
}

/// The least distance from a vertex along `dir` at which a bridge of `hinge` keeps `hinge`
/// of material from each of the vertex's other `burns` (zero when none is in the way).
fn clearance(burns: &[Burn], dir: Vec2, hinge: Real, hk: Real) -> Real {
    burns.iter().fold(0.0, |s0: Real, b| {
        let cos = dir.dot(&b.dir);
        let sin = cross(&dir, &b.dir).abs();
        let need = if cos <= 0.0 {
            b.c
        } else if sin < 1e-12 {
            Real::INFINITY
        } else {
            (hinge + hk + b.c) / sin - hinge - hk
        };
        s0.max(need)
    })
}

/// The burns at vertex `v` other than edge `skip`'s: every other edge at `v` (cut or
/// bridged, counted as a full cut: conservative), outline edges (c = 0) and a relief cut.
fn burns_at(
    g: &PatchGraph,
    v: usize,
    skip: usize,
    reliefs: &[Option<Vec2>],
    hk: Real,
) -> Vec<Burn> {
    let mut out: Vec<Burn> = g.star[v]
        .iter()
        .filter(|&&e| e != skip)
        .map(|&e| Burn {
            dir: g.leaving(e, v).0,
            c: if g.edges[e].right.is_some() { hk } else { 0.0 },
        })
        .collect();
    if let Some(p) = reliefs[v] {
        out.push(Burn {
            dir: (p - g.point(v)).normalize(),
            c: hk,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: Real, y: Real, s: Real) -> Vec<[Real; 2]> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    fn four_squares() -> Vec<Vec<[Real; 2]>> {
        vec![
            square(0.0, 0.0, 10.0),
            square(10.0, 0.0, 10.0),
            square(0.0, 10.0, 10.0),
            square(10.0, 10.0, 10.0),
        ]
    }

    fn joint(a: usize, b: usize, p: [Real; 2]) -> JointAt {
        JointAt {
            tiles: [a, b],
            point: p,
        }
    }

    fn near(a: Vec2, b: [Real; 2]) -> bool {
        (a - Vec2::new(b[0], b[1])).norm() < 1e-9
    }

    /// Rotating-squares corner: 0–1 and 2–3 pinned at the centre, the horizontal edges cut
    /// through it. The cuts there clear the centre, so the bridges start k/2 from it.
    #[test]
    fn bridges_at_a_four_tile_vertex_start_half_a_kerf_from_it() {
        let (h, k) = (1.5, 0.2);
        let joints = [joint(0, 1, [10.0, 10.0]), joint(2, 3, [10.0, 10.0])];
        let lay = layout_cuts(&four_squares(), &joints, h, k).unwrap();
        assert_eq!(lay.bridges.len(), 2);
        for b in &lay.bridges {
            assert!(((b.to - b.from).norm() - h).abs() < 1e-12);
            assert!(((b.from - b.joint).norm() - k / 2.0).abs() < 1e-12);
        }
        // The cut of edge 0–1 stops k/2 short of the bridge; the horizontal cuts run through.
        let lower: Vec<&Cut> = lay
            .cuts
            .iter()
            .filter(|c| c.a.x == 10.0 && c.b.x == 10.0 && c.a.y.max(c.b.y) <= 10.0)
            .collect();
        assert_eq!(lower.len(), 1, "{lower:?}");
        assert!((lower[0].a.y.max(lower[0].b.y) - (10.0 - k - h)).abs() < 1e-12);
        let through: usize = lay
            .cuts
            .iter()
            .filter(|c| c.a.y == 10.0 && c.b.y == 10.0)
            .filter(|c| near(c.a, [10.0, 10.0]) || near(c.b, [10.0, 10.0]))
            .count();
        assert_eq!(through, 2);
        assert_eq!(lay.outline.len(), 1);
        // Outline offset outwards by k/2: a 20.2 mm square.
        let o = &lay.outline[0];
        let xs: Vec<Real> = o.iter().map(|p| p.x).collect();
        let min = xs.iter().cloned().fold(Real::INFINITY, Real::min);
        assert!((min + k / 2.0).abs() < 1e-12);
    }

    /// Four tiles pinned together at one vertex: no cut burns there, so each bridge gets a
    /// stub cut from the vertex and starts a kerf away from it.
    #[test]
    fn a_vertex_without_cuts_gets_stubs() {
        let (h, k) = (1.0, 0.2);
        let v = [10.0, 10.0];
        let joints = [
            joint(0, 1, v),
            joint(2, 3, v),
            joint(0, 2, v),
            joint(1, 3, v),
        ];
        let lay = layout_cuts(&four_squares(), &joints, h, k).unwrap();
        assert_eq!(lay.bridges.len(), 4);
        let stubs = lay
            .cuts
            .iter()
            .filter(|c| near(c.a, v) && ((c.b - c.a).norm() - k / 2.0).abs() < 1e-12)
            .count();
        assert_eq!(stubs, 4);
        for b in &lay.bridges {
            assert!(((b.from - b.joint).norm() - k).abs() < 1e-12);
        }
    }

    /// A joint on a straight stretch of the outline starts right at the outline.
    #[test]
    fn a_joint_on_the_outline_starts_at_the_vertex() {
        let tiles = vec![square(0.0, 0.0, 10.0), square(10.0, 0.0, 10.0)];
        let lay = layout_cuts(&tiles, &[joint(0, 1, [10.0, 10.0])], 1.5, 0.2).unwrap();
        let b = lay.bridges[0];
        assert!(near(b.from, [10.0, 10.0]) && near(b.to, [10.0, 8.5]));
        assert_eq!(lay.cuts.len(), 1);
        assert!(near(lay.cuts[0].a, [10.0, 0.0]) && near(lay.cuts[0].b, [10.0, 8.4]));
    }

    /// A burn at an acute angle pushes the bridge out until the neck is h wide.
    #[test]
    fn an_acute_neighbour_pushes_the_bridge_out() {
        // Two triangles (split along the diagonal of a square) and a square beside them.
        let tiles = vec![
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]],
            vec![[0.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
            vec![[10.0, 0.0], [20.0, 0.0], [20.0, 10.0], [10.0, 10.0]],
        ];
        let (h, k) = (1.0, 0.2);
        // Joint of 0 and 2 at (10, 10): the diagonal is cut to that vertex at 45° from the
        // jointed edge (which runs down from it).
        let lay = layout_cuts(&tiles, &[joint(0, 2, [10.0, 10.0])], h, k).unwrap();
        let b = lay.bridges[0];
        let s0 = (b.from - b.joint).norm();
        let sin = std::f64::consts::FRAC_1_SQRT_2;
        assert!((s0 - ((h + k) / sin - h - k / 2.0)).abs() < 1e-9, "{s0}");
        // The far cap's distance to the diagonal burn is then exactly h.
        let far = b.joint + (b.to - b.joint) / (b.to - b.joint).norm() * (s0 + h + k / 2.0);
        let to_diagonal = (far.x - far.y).abs() * sin;
        assert!((to_diagonal - k - h).abs() < 1e-9);
    }

    #[test]
    fn a_hinge_longer_than_its_edge_is_refused() {
        let tiles = vec![square(0.0, 0.0, 2.0), square(2.0, 0.0, 2.0)];
        let e = layout_cuts(&tiles, &[joint(0, 1, [2.0, 2.0])], 2.5, 0.2).unwrap_err();
        assert!(matches!(e, LaserError::HingeTooWide { .. }), "{e}");
        assert!(e.to_string().contains("2.5 mm"), "{e}");
        // Both ends jointed: two bridges must fit with a cut between them.
        let both = [joint(0, 1, [2.0, 2.0]), joint(0, 1, [2.0, 0.0])];
        assert!(layout_cuts(&tiles, &both, 0.9, 0.2).is_err());
        assert_eq!(
            layout_cuts(&tiles, &both, 0.8, 0.1).unwrap().bridges.len(),
            2
        );
    }
}

//! Tiles that meet in the closed sheet stay apart as it opens: the contact rows of the
//! graded problem.
//!
//! A graded sheet's tiles may change shape so much that two tiles beside each other (sharing a
//! closed node, pinned or not) run into each other part of the way open, although the
//! periodic design's never do. The pin gaps ([`super::problem::PinGap`]) keep a pinned pair
//! from turning into each other around its pin; these rows keep every corner of one tile of a
//! pair out of the other tile, in every state: a corner inside is a one-sided residual, its
//! depth (distance to the other tile's nearest boundary point), with exact derivatives through
//! both tiles' opened corners. The pin's own node, on both tiles' boundaries, is left out.
//!
//! In the opened state the corners come from both tiles' poses; in a state part of the way,
//! which keeps only rotations, from chains of tiles ([`super::loops`]): a's corners relative to
//! its first node, b's through the pins from a to b.

use super::loops::Segment;
use super::problem::{ChainJacobian, Problem, Rows};
use crate::geometry::point_in_polygon_strict;
use crate::math::{cross, DVec, Real, Vec2};

/// Two tiles that share a closed node: their opened interiors must stay apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Contact {
    /// One tile.
    pub a: usize,
    /// The other.
    pub b: usize,
    /// The node they are pinned at, if they are (left out of the check).
    pub pin: Option<usize>,
}

/// Every pair of tiles sharing a closed node, with the node they are pinned at.
pub fn contacts(tiles: &[Vec<usize>], joints: &[(usize, usize, usize)]) -> Vec<Contact> {
    let nodes = tiles.iter().flatten().max().map_or(0, |&n| n + 1);
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); nodes];
    for (i, t) in tiles.iter().enumerate() {
        for &n in t {
            at[n].push(i);
        }
    }
    let mut pairs: Vec<(usize, usize)> = at
        .iter()
        .flat_map(|ts| {
            ts.iter()
                .flat_map(move |&a| ts.iter().filter(move |&&b| b > a).map(move |&b| (a, b)))
        })
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs
        .into_iter()
        .map(|(a, b)| Contact {
            a,
            b,
            pin: joints
                .iter()
                .find(|&&(p, q, _)| (p, q) == (a, b) || (p, q) == (b, a))
                .map(|j| j.2),
        })
        .collect()
}

/// How deep a point lies inside a polygon, and the gradients of that depth.
struct Depth {
    /// Distance to the polygon's nearest boundary point.
    depth: Real,
    /// Gradient with respect to the point.
    point: Vec2,
    /// Gradients with respect to the polygon corners it depends on: (corner, gradient).
    corners: Vec<(usize, Vec2)>,
}

/// The depth of `p` inside the counter-clockwise polygon `poly`, or None when `p` is not
/// strictly inside.
fn depth(p: Vec2, poly: &[Vec2]) -> Option<Depth> {
    if !point_in_polygon_strict(&p, poly, 0.0) {
        return None;
    }
    let m = poly.len();
    let mut best: Option<Depth> = None;
    for k in 0..m {
        let (q0, q1) = (poly[k], poly[(k + 1) % m]);
        let e = q1 - q0;
        let w = p - q0;
        let len2 = e.norm_squared();
        if len2 == 0.0 {
            continue;
        }
        let s = w.dot(&e) / len2;
        let candidate = if s <= 0.0 || s >= 1.0 {
            // Nearest at a corner: |p − q|.
            let (j, q) = if s <= 0.0 { (k, q0) } else { ((k + 1) % m, q1) };
            let d = (p - q).norm();
            if d == 0.0 {
                continue;
            }
            let g = (p - q) / d;
            Depth {
                depth: d,
                point: g,
                corners: vec![(j, -g)],
            }
        } else {
            // Nearest on the edge: the signed distance cross(e, w)/|e| (positive inside).
            let len = len2.sqrt();
            let c = cross(&e, &w);
            let d = c / len;
            let dp = Vec2::new(-e.y, e.x) / len;
            let dce = Vec2::new(w.y, -w.x);
            let dq1 = dce / len - e * (c / (len * len2));
            let dq0 = -dq1 - dp;
            Depth {
                depth: d,
                point: dp,
                corners: vec![(k, dq0), ((k + 1) % m, dq1)],
            }
        };
        if best.as_ref().is_none_or(|b| candidate.depth < b.depth) {
            best = Some(candidate);
        }
    }
    best
}

/// A tile's corners placed in some frame, with their derivative entries.
type Corners = Vec<(Vec2, ChainJacobian)>;

impl Problem {
    /// The corners of contact `k`'s two tiles in state `state`: in the opened state from their
    /// poses; in a state part of the way, which has rotations only, both in a's frame, b's
    /// through the shortest pin path from a (None when there is none: the pair is in two
    /// pieces of the pin graph).
    fn pair_corners(
        &self,
        z: &DVec,
        nodes: usize,
        state: usize,
        k: usize,
    ) -> Option<(Corners, Corners)> {
        let contact = &self.contacts[k];
        if state == self.openings.len() - 1 {
            let opened = |i: usize| -> Corners {
                self.tiles[i]
                    .iter()
                    .map(|&n| {
                        let (p, j) = self.corner(z, nodes, state, i, n);
                        (p, ChainJacobian::from(j))
                    })
                    .collect()
            };
            return Some((opened(contact.a), opened(contact.b)));
        }
        let (route, entry) = self.contact_routes[k].as_ref()?;
        let from_first = |tile: usize, from: usize| -> Corners {
            self.tiles[tile]
                .iter()
                .map(|&to| self.chain(z, nodes, state, [Segment { tile, from, to }]))
                .collect()
        };
        let (a, b) = (contact.a, contact.b);
        let ca = from_first(a, self.tiles[a][0]);
        // b's corners: the route to its entry node, then across b.
        let (at, via) = self.chain(z, nodes, state, route.iter().copied());
        let cb = from_first(b, *entry)
            .into_iter()
            .map(|(p, j)| (at + p, via.then(j)))
            .collect();
        Some((ca, cb))
    }

    /// The corners' places alone, as [`Self::pair_corners`] gives them.
    fn pair_points(
        &self,
        z: &DVec,
        nodes: usize,
        state: usize,
        k: usize,
    ) -> Option<(Vec<Vec2>, Vec<Vec2>)> {
        let contact = &self.contacts[k];
        if state == self.openings.len() - 1 {
            let opened = |i: usize| -> Vec<Vec2> {
                self.tiles[i]
                    .iter()
                    .map(|&n| self.corner(z, nodes, state, i, n).0)
                    .collect()
            };
            return Some((opened(contact.a), opened(contact.b)));
        }
        let (route, entry) = self.contact_routes[k].as_ref()?;
        let from = |tile: usize, from: usize, at: Vec2| -> Vec<Vec2> {
            self.tiles[tile]
                .iter()
                .map(|&to| at + self.chain_point(z, nodes, state, [Segment { tile, from, to }]))
                .collect()
        };
        let (a, b) = (contact.a, contact.b);
        let at = self.chain_point(z, nodes, state, route.iter().copied());
        Some((
            from(a, self.tiles[a][0], Vec2::zeros()),
            from(b, *entry, at),
        ))
    }

    /// Whether a corner of either tile of contact `k` (its pin's node left out) lies inside
    /// the other tile, the two placed at `points`.
    fn touching(&self, k: usize, (pa, pb): &(Vec<Vec2>, Vec<Vec2>)) -> bool {
        let contact = &self.contacts[k];
        [(pa, pb, contact.a), (pb, pa, contact.b)]
            .into_iter()
            .any(|(corners, other, tile)| {
                corners.iter().enumerate().any(|(v, p)| {
                    Some(self.tiles[tile][v]) != contact.pin
                        && point_in_polygon_strict(p, other, 0.0)
                })
            })
    }

    /// The contact rows of state `state`: every pair, each corner of one tile inside the other.
    pub(super) fn contact_rows(
        &self,
        z: &DVec,
        nodes: usize,
        state: usize,
        every: bool,
        out: &mut Rows,
    ) {
        let weight = self.weights.contact;
        let last = self.openings.len() - 1;
        for (k, contact) in self.contacts.iter().enumerate() {
            // Most pairs are apart: their rows are found from the corners' places alone, and
            // only a touching pair's derivatives are formed.
            if !every {
                match self.pair_points(z, nodes, state, k) {
                    Some(points) if self.touching(k, &points) => {}
                    _ => continue,
                }
            }
            let Some((ca, cb)) = self.pair_corners(z, nodes, state, k) else {
                continue;
            };
            if every {
                // The pattern: one row over every column of both tiles.
                let e = ca.iter().chain(&cb).flat_map(|(_, j)| {
                    (0..2).flat_map(move |r| j.row(r).iter().map(|&(c, _)| (c, 1.0)))
                });
                if state == last {
                    out.push(0.0, e);
                } else {
                    out.push(0.0, super::problem::merged(e.collect()));
                }
                continue;
            }
            for (corners, other, tile) in [(&ca, &cb, contact.a), (&cb, &ca, contact.b)] {
                let poly: Vec<Vec2> = other.iter().map(|c| c.0).collect();
                for (v, (p, jp)) in corners.iter().enumerate() {
                    if Some(self.tiles[tile][v]) == contact.pin {
                        continue;
                    }
                    let Some(Depth {
                        depth: d,
                        point: dp,
                        corners: dq,
                    }) = depth(*p, &poly)
                    else {
                        continue;
                    };
                    let mut e = Vec::with_capacity(24);
                    for r in 0..2 {
                        e.extend(jp.row(r).iter().map(|&(c, x)| (c, weight * dp[r] * x)));
                        for (k, g) in &dq {
                            let jq = &other[*k].1;
                            e.extend(jq.row(r).iter().map(|&(c, x)| (c, weight * g[r] * x)));
                        }
                    }
                    if state == last {
                        out.push(weight * d, e);
                    } else {
                        out.push(weight * d, super::problem::merged(e));
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{setup, GradedRequest};
    use super::*;

    /// The corners' places found without derivatives are the ones the rows are formed from,
    /// and a pair counts as touching exactly when one of its corners has a depth: the
    /// shortcut past pairs that are apart drops no row. Checked with tiles turned at random,
    /// in the opened state and part of the way, on a square and a concave design.
    #[test]
    fn pairs_apart_are_skipped_and_no_touching_pair_is() {
        for design in [
            "rotating-squares",
            "IH27:0.141304,0.6046404,0.6953583:1x1:-aaaaaaaa-",
        ] {
            let request = GradedRequest {
                design: design.into(),
                rows: 2,
                cols: 2,
                states: 3,
                ..GradedRequest::default()
            };
            let (sheet, problem) = setup(&request).unwrap();
            let nodes = sheet.nodes.len();
            let mut z = Problem::pack(&sheet);
            let mut seed = 3u64;
            for k in 2 * nodes..z.len() {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                z[k] += 1.2 * ((seed >> 11) as Real / (1u64 << 53) as Real - 0.5);
            }
            let (mut touching, mut apart) = (0, 0);
            for state in 0..problem.openings.len() {
                for k in 0..problem.contacts.len() {
                    let Some(points) = problem.pair_points(&z, nodes, state, k) else {
                        assert!(problem.pair_corners(&z, nodes, state, k).is_none());
                        continue;
                    };
                    let (ca, cb) = problem.pair_corners(&z, nodes, state, k).unwrap();
                    let places = |c: &Corners| c.iter().map(|x| x.0).collect::<Vec<_>>();
                    assert_eq!(points.0, places(&ca), "{design}: state {state} pair {k}");
                    assert_eq!(points.1, places(&cb), "{design}: state {state} pair {k}");
                    let contact = &problem.contacts[k];
                    let deep = [
                        (&points.0, &points.1, contact.a),
                        (&points.1, &points.0, contact.b),
                    ]
                    .into_iter()
                    .any(|(corners, other, tile)| {
                        corners.iter().enumerate().any(|(v, p)| {
                            Some(problem.tiles[tile][v]) != contact.pin
                                && depth(*p, other).is_some()
                        })
                    });
                    assert_eq!(problem.touching(k, &points), deep, "{design}: pair {k}");
                    if deep {
                        touching += 1;
                    } else {
                        apart += 1;
                    }
                }
            }
            assert!(
                touching > 0 && apart > 0,
                "{design}: {touching} touching, {apart} apart"
            );
        }
    }

    /// The depth's gradients match central differences (inside near an edge, and near a
    /// corner of an L-shaped, concave polygon).
    #[test]
    fn the_depth_gradient_matches_finite_differences() {
        let l = [
            Vec2::new(0.0, 0.0),
            Vec2::new(2.0, 0.0),
            Vec2::new(2.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 2.0),
            Vec2::new(0.0, 2.0),
        ];
        let h = 1e-7;
        for p in [
            Vec2::new(1.7, 0.2),
            Vec2::new(0.8, 0.9),
            Vec2::new(0.3, 1.6),
        ] {
            let Depth {
                depth: d,
                point: dp,
                corners: dq,
            } = depth(p, &l).expect("inside");
            assert!(d > 0.0);
            for r in 0..2 {
                let mut e = Vec2::zeros();
                e[r] = h;
                let at = |p: Vec2, l: &[Vec2]| depth(p, l).unwrap().depth;
                let fd = (at(p + e, &l) - at(p - e, &l)) / (2.0 * h);
                assert!((fd - dp[r]).abs() < 1e-6, "p {p:?}: {fd} vs {}", dp[r]);
                for (k, g) in &dq {
                    let (mut lp, mut lm) = (l, l);
                    lp[*k] += e;
                    lm[*k] -= e;
                    let fd = (at(p, &lp) - at(p, &lm)) / (2.0 * h);
                    assert!((fd - g[r]).abs() < 1e-6, "corner {k}: {fd} vs {}", g[r]);
                }
            }
        }
        assert!(
            depth(Vec2::new(1.5, 1.5), &l).is_none(),
            "the notch is outside"
        );
    }
}

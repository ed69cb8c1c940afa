//! The outline of a closed patch: the tile edges whose neighbour lies outside the patch,
//! chained end to start into closed loops.

use crate::math::Real;

/// Chains directed boundary edges (`[start, end]` pairs, each with a label for its start)
/// into closed loops of (start, label), each loop listed once without repeating its first
/// vertex. An edge starts where the previous one
/// ends (within `tol`); where several could follow (the patch touching itself at a vertex)
/// the first unused one is taken. Edges that cannot be closed into a loop end their chain
/// where it stops.
pub(crate) fn chain_loops<L: Copy>(
    edges: &[([[Real; 2]; 2], L)],
    tol: Real,
) -> Vec<Vec<([Real; 2], L)>> {
    let mut used = vec![false; edges.len()];
    let mut loops = Vec::new();
    for first in 0..edges.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let ([start, mut at], label) = edges[first];
        let mut ring = vec![(start, label)];
        while dist(at, start) > tol {
            let next = (0..edges.len()).find(|&k| !used[k] && dist(edges[k].0[0], at) <= tol);
            let Some(next) = next else { break };
            used[next] = true;
            ring.push((edges[next].0[0], edges[next].1));
            at = edges[next].0[1];
        }
        loops.push(ring);
    }
    loops
}

fn dist(p: [Real; 2], q: [Real; 2]) -> Real {
    (p[0] - q[0]).hypot(p[1] - q[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_squares_sharing_an_edge_give_one_six_vertex_loop() {
        // Boundary of the 2×1 rectangle made of two unit squares, edges given out of order.
        let e = |a: [Real; 2], b: [Real; 2]| ([a, b], a[0] as i32);
        let edges = [
            e([2.0, 1.0], [1.0, 1.0]),
            e([0.0, 0.0], [1.0, 0.0]),
            e([1.0, 1.0], [0.0, 1.0]),
            e([2.0, 0.0], [2.0, 1.0]),
            e([0.0, 1.0], [0.0, 0.0]),
            e([1.0, 0.0], [2.0, 0.0]),
        ];
        let loops = chain_loops(&edges, 1e-12);
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].len(), 6);
        assert_eq!(loops[0][0], ([2.0, 1.0], 2));
        assert_eq!(loops[0][1], ([1.0, 1.0], 1));
        assert_eq!(loops[0][5], ([2.0, 0.0], 2));
    }

    #[test]
    fn separate_rings_stay_separate() {
        let sq = |x: Real| {
            [
                ([[x, 0.0], [x + 1.0, 0.0]], ()),
                ([[x + 1.0, 0.0], [x + 1.0, 1.0]], ()),
                ([[x + 1.0, 1.0], [x, 1.0]], ()),
                ([[x, 1.0], [x, 0.0]], ()),
            ]
        };
        let edges: Vec<_> = sq(0.0).into_iter().chain(sq(5.0)).collect();
        let loops = chain_loops(&edges, 1e-12);
        assert_eq!(loops.len(), 2);
        assert!(loops.iter().all(|l| l.len() == 4));
    }
}

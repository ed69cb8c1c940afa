//! Whether a one-DOF sheet can exist in a region, decided by counting tiles and pins alone.
//!
//! A sheet of N tiles held by P pins has at least 3N − 2P − 3 degrees of freedom: each tile
//! has three, each pin removes at most two, and three are the sheet's rigid motions. So a
//! one-DOF sheet has 2P − 3N ≥ −4. Completion keeps some set S of the region's tiles and the
//! ring around them, and must keep a fraction f of the region's area A; if no such S has
//! 2P_S − 3N_S ≥ −4, no completion exists and the refusal needs no factorisation.
//!
//! Whether one does is decided through a Lagrangian bound: for every λ ≥ 0 and every S
//! covering at least f·A,
//!
//! 2P_S − 3N_S ≤ max_S' (2P_S' − 3N_S' + λ·a(S')) − λ·f·A =: g(λ),
//!
//! and the maximum is a maximum-weight closure (each pin weighs 2 and needs its two tiles,
//! each tile weighs λ·a − 3), found by one minimum cut. g is convex and piecewise linear in
//! λ with slope a(S*) − f·A at the maximiser S*, so its minimum is found by bisection on the
//! slope's sign. When some g(λ) < −4, every sheet covering f·A has at least ⌈−g(λ)⌉ − 3
//! degrees of freedom. The bound is one-sided: a region it does not refuse may still have
//! no one-DOF sheet (completion decides that), but a region it refuses has none.
//!
//! The maximum is bounded from above by the cut's capacity minus the flow pushed (any flow
//! is at most the minimum cut), so rounding in the flow can only weaken a refusal.

use crate::math::Real;

/// The least degrees of freedom every sheet covering the required area has, when counting
/// proves it more than one; `None` when counting cannot refuse.
///
/// `areas[t]` is tile t's area that counts towards the covered fraction (zero for tiles
/// outside the region), `pins` are the pins as pairs of tile indices, `required` the area
/// a sheet must keep (f·A).
pub fn least_dof(areas: &[Real], pins: &[(usize, usize)], required: Real) -> Option<usize> {
    if !(required.is_finite() && required > 0.0) || areas.is_empty() {
        return None;
    }
    let bound = |lambda: Real| -> (Real, Real) {
        let (value, covered) = max_closure(areas, pins, lambda);
        (value - lambda * required, covered - required)
    };
    // Refused when g(λ) < −4, with a margin for rounding in the weights.
    let limit = -4.0 - 1e-6;
    let verdict = |g: Real| (g < limit).then(|| (-g - 3.0).ceil() as usize);
    // g(0) ≥ 0 (the empty set); g falls while its maximiser covers less than required. Find
    // a λ where it covers at least the required area, then bisect between.
    let mut lo = 0.0;
    let mut hi = 4.0 / required;
    let mut bracketed = false;
    for _ in 0..64 {
        let (g, slope) = bound(hi);
        if let Some(dof) = verdict(g) {
            return Some(dof);
        }
        if slope >= 0.0 {
            bracketed = true;
            break;
        }
        lo = hi;
        hi *= 2.0;
    }
    if !bracketed {
        return None;
    }
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        let (g, slope) = bound(mid);
        if let Some(dof) = verdict(g) {
            return Some(dof);
        }
        if slope >= 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    None
}

/// An upper bound on max_S (2P_S − 3N_S + λ·a(S)) (tight up to rounding) and the area a of
/// the maximiser found.
fn max_closure(areas: &[Real], pins: &[(usize, usize)], lambda: Real) -> (Real, Real) {
    let n = areas.len();
    // Nodes: source, sink, tiles, pins.
    let (source, sink) = (0, 1);
    let tile = |t: usize| 2 + t;
    let mut net = Network::new(2 + n + pins.len());
    let mut positive = 0.0;
    for (t, &a) in areas.iter().enumerate() {
        let w = lambda * a - 3.0;
        if w > 0.0 {
            positive += w;
            net.add(source, tile(t), w);
        } else if w < 0.0 {
            net.add(tile(t), sink, -w);
        }
    }
    for (k, &(a, b)) in pins.iter().enumerate() {
        let p = 2 + n + k;
        positive += 2.0;
        net.add(source, p, 2.0);
        net.add(p, tile(a), Real::INFINITY);
        net.add(p, tile(b), Real::INFINITY);
    }
    let flow = net.max_flow(source, sink);
    let reached = net.reachable(source);
    let covered = (0..n).filter(|&t| reached[tile(t)]).map(|t| areas[t]).sum();
    (positive - flow, covered)
}

/// A flow network with real capacities (Dinic's algorithm, iterative).
struct Network {
    /// Edges in pairs (forward at 2k, residual at 2k + 1): head and remaining capacity.
    to: Vec<usize>,
    cap: Vec<Real>,
    /// Edge indices leaving each node.
    out: Vec<Vec<usize>>,
}

impl Network {
    fn new(nodes: usize) -> Self {
        Network {
            to: Vec::new(),
            cap: Vec::new(),
            out: vec![Vec::new(); nodes],
        }
    }

    fn add(&mut self, from: usize, to: usize, cap: Real) {
        self.out[from].push(self.to.len());
        self.to.push(to);
        self.cap.push(cap);
        self.out[to].push(self.to.len());
        self.to.push(from);
        self.cap.push(0.0);
    }

    /// Capacities this small are spent (rounding left by subtraction).
    fn open(&self, e: usize) -> bool {
        self.cap[e] > 1e-12
    }

    /// BFS levels from `s` over open edges (usize::MAX where unreached).
    fn levels(&self, s: usize) -> Vec<usize> {
        let mut level = vec![usize::MAX; self.out.len()];
        let mut queue = std::collections::VecDeque::from([s]);
        level[s] = 0;
        while let Some(v) = queue.pop_front() {
            for &e in &self.out[v] {
                let w = self.to[e];
                if self.open(e) && level[w] == usize::MAX {
                    level[w] = level[v] + 1;
                    queue.push_back(w);
                }
            }
        }
        level
    }

    /// Nodes reachable from `s` over open edges: the source side of a minimum cut once the
    /// flow is maximal.
    fn reachable(&self, s: usize) -> Vec<bool> {
        self.levels(s).iter().map(|&l| l != usize::MAX).collect()
    }

    fn max_flow(&mut self, s: usize, t: usize) -> Real {
        let mut total = 0.0;
        loop {
            let mut level = self.levels(s);
            if level[t] == usize::MAX {
                return total;
            }
            // Blocking flow along level-increasing paths, found depth first without recursion.
            let mut next = vec![0usize; self.out.len()];
            let mut path: Vec<usize> = Vec::new();
            let mut v = s;
            loop {
                if v == t {
                    let push = path
                        .iter()
                        .map(|&e| self.cap[e])
                        .fold(Real::INFINITY, Real::min);
                    for &e in &path {
                        self.cap[e] -= push;
                        self.cap[e ^ 1] += push;
                    }
                    total += push;
                    path.clear();
                    v = s;
                    continue;
                }
                let mut advanced = false;
                while next[v] < self.out[v].len() {
                    let e = self.out[v][next[v]];
                    let w = self.to[e];
                    if self.open(e) && level[w] == level[v] + 1 {
                        path.push(e);
                        v = w;
                        advanced = true;
                        break;
                    }
                    next[v] += 1;
                }
                if advanced {
                    continue;
                }
                // A dead end: no path to t through v in this phase.
                level[v] = usize::MAX;
                match path.pop() {
                    Some(e) => {
                        v = self.to[e ^ 1];
                        next[v] += 1;
                    }
                    None => break,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::xorshift;

    /// Random small tile/pin graphs (up to 11 tiles, pins drawn with a seeded density,
    /// doubled pins included): the closure's maximum equals brute force over every subset.
    #[test]
    fn the_cut_finds_the_best_closure() {
        let mut rand = xorshift(0x9e37_79b9_7f4a_7c15);
        for case in 0..400 {
            let n = 1 + (rand() * 11.0) as usize;
            let areas: Vec<Real> = (0..n)
                .map(|_| if rand() < 0.2 { 0.0 } else { 0.2 + rand() })
                .collect();
            let density = 0.2 + 0.6 * rand();
            let mut pins = Vec::new();
            for a in 0..n {
                for b in a + 1..n {
                    while rand() < density && pins.len() < 40 {
                        pins.push((a, b));
                    }
                }
            }
            let lambda = 10.0 * rand();
            let best = (0u32..1 << n)
                .map(|s| value(&areas, &pins, lambda, s))
                .fold(Real::NEG_INFINITY, Real::max);
            let (found, _) = max_closure(&areas, &pins, lambda);
            assert!(
                (found - best).abs() < 1e-9,
                "case {case}: {found} vs {best}"
            );
        }
    }

    /// On random graphs, a refusal is never wrong: when `least_dof` says k, brute force finds
    /// no subset covering the required area with 2P − 3N > 3 − k; and where brute force finds
    /// no subset with 2P − 3N ≥ −4 covering it, the bound refuses in most cases (it is a
    /// relaxation, exact only at the breakpoints of g).
    #[test]
    fn a_refusal_is_never_wrong() {
        let mut rand = xorshift(0x2545_f491_4f6c_dd1d);
        let (mut impossible, mut refused) = (0, 0);
        for case in 0..600 {
            let n = 2 + (rand() * 10.0) as usize;
            let areas: Vec<Real> = (0..n).map(|_| 0.3 + rand()).collect();
            let density = 0.1 + 0.5 * rand();
            let mut pins = Vec::new();
            for a in 0..n {
                for b in a + 1..n {
                    if rand() < density {
                        pins.push((a, b));
                    }
                }
            }
            let total: Real = areas.iter().sum();
            let required = total * (0.2 + 0.8 * rand());
            let best = (0u32..1 << n)
                .filter(|&s| covered(&areas, s) >= required)
                .map(|s| count(&pins, s))
                .max();
            let verdict = least_dof(&areas, &pins, required);
            if let Some(k) = verdict {
                let best = best.unwrap_or(i64::MIN);
                assert!(
                    best == i64::MIN || 3 - best >= k as i64,
                    "case {case}: refused with {k} DOF but a subset has 2P − 3N = {best}"
                );
            }
            if best.is_none_or(|b| b < -4) {
                impossible += 1;
                refused += usize::from(verdict.is_some());
            }
        }
        assert!(impossible > 50, "too few impossible cases ({impossible})");
        assert!(
            refused * 10 >= impossible * 7,
            "{refused} of {impossible} impossible cases refused"
        );
    }

    #[test]
    fn nothing_required_is_never_refused() {
        assert_eq!(least_dof(&[1.0, 1.0], &[], 0.0), None);
        assert_eq!(least_dof(&[], &[], 1.0), None);
    }

    fn covered(areas: &[Real], s: u32) -> Real {
        (0..areas.len())
            .filter(|&t| s >> t & 1 == 1)
            .map(|t| areas[t])
            .sum()
    }

    fn count(pins: &[(usize, usize)], s: u32) -> i64 {
        let tiles = s.count_ones() as i64;
        let inner = pins
            .iter()
            .filter(|&&(a, b)| s >> a & 1 == 1 && s >> b & 1 == 1)
            .count() as i64;
        2 * inner - 3 * tiles
    }

    fn value(areas: &[Real], pins: &[(usize, usize)], lambda: Real, s: u32) -> Real {
        count(pins, s) as Real + lambda * covered(areas, s)
    }
}

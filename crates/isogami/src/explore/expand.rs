//! Expansion of a reduced topology (a joint mask) into its 2^k endpoint choices, keeping those
//! with exactly one degree of freedom (paper §4.1, first eigen-analysis check).
//!
//! The choices are assigned depth-first, one jointed edge at a time (end A, then end B). Each
//! joint adds two rows to the Jacobian of the closed state (non-dimensional model, tile 0's
//! three columns removed — exactly the matrix whose H = JᵀJ `mobility::analyze` decomposes,
//! N = 3n + 1 columns). The search keeps three things about the rows added so far:
//!
//! - an orthonormal basis C of their orthogonal complement (N − rank vectors). A new row's
//!   residual is its projection on C; the rows are sparse (a joint touches two tiles and the
//!   lattice), so that costs O(nnz · (N − rank)). When the row is independent, one Householder
//!   reflection of C's coordinates turns its first vector into the new basis direction and the
//!   others into the new complement: O(N · (N − rank)). Deep in the tree, where almost every
//!   node is, the complement is small (a surviving node has N − rank ≤ 2·left + 1, see below),
//!   so adding a joint there costs O(N) instead of the O(N · rank) of Gram–Schmidt;
//! - the orthonormal basis Q of the rows' span, one vector per independent row (the Householder
//!   step gives it), and the triangular factor R with selected row i = Σ_j r[i][j] q_j (its
//!   entries are the sparse products q_j · row);
//! - R⁻¹ row by row, for the certificates below.
//!
//! Backtracking truncates Q and R and restores C from a copy kept per depth.
//!
//! Adding joints only removes motions, which gives two prunes, both safe:
//!
//! - **too flexible**: a row whose residual is below `1e-9 ·` its norm counts as dependent.
//!   With `r` the basis size and `left` the edges still undecided, every completion has
//!   rank ≤ r + 2·left; if N − r − 2·left > 1 no completion can have dof = 1. (The dropped
//!   residuals are ≤ 3e-9, four decades below the smallest zero threshold `analyze` can use,
//!   √1e-9 ≈ 3.2e-5 on singular values, so the count is an upper bound of `analyze`'s
//!   numerical rank.)
//! - **rigid**: once the basis has N rows, R is square and σ_min(J) ≥ σ_min(R) ≥ 1/‖R⁻¹‖_F.
//!   Adding rows never lowers the smallest eigenvalue of H, and `analyze`'s threshold for any
//!   completion is at most `rel_tol · max(B, 1)` with B the sum over the mask's edges of the
//!   larger squared Frobenius norm of its two row pairs (a bound on λ_max). If
//!   σ_min(R)² ≥ 2 · that threshold, every completion is rigid and the subtree is dropped.
//!
//! At a leaf with a basis of N − 1 rows, the same bound decides dof = 1 without an
//! eigen-decomposition when it is clear: the N − 1 selected rows have σ_min(R)² ≥ 2 · the zero
//! threshold `analyze` would use for this matrix (rel_tol · max(‖J‖_F², 1) ≥ rel_tol · λ_max),
//! so N − 1 eigenvalues are non-zero, while the N-th is at most the dropped residuals (≤ 3e-9),
//! far below any threshold. The motion is then the complement's one vector, signed as
//! `analyze` signs it (opening area, else largest component positive). Every other leaf
//! that may have dof = 1 (basis of N − 1 rows without the certificate, or N rows without the
//! rigidity certificate) is handed to `mobility::analyze` itself. `Leaf::analysed` says which.
//! Plain data in and out (joint choices, motion vectors); no separation or symmetry
//! reasoning, no I/O.

use crate::cell::UnitCell;
use crate::kinematics::KinematicsError;
use crate::kinematics::Mechanism;
use crate::math::DVec;
use crate::mobility::{analyze, area_rate, MobilitySettings};
use crate::topology::JointChoice;
use serde::Serialize;

/// A row counts as independent when its residual after projection exceeds this times its
/// norm.
const DEPENDENT_REL_TOL: f64 = 1e-9;

/// Safety factor between the certificates (rigid, dof = 1) and `analyze`'s zero threshold.
const RIGID_MARGIN: f64 = 2.0;

/// Counters of one or more expansions.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct ExpandStats {
    /// Σ 2^k over the expanded masks: the configurations the expansion stands for.
    pub configurations: u64,
    /// Partial assignments visited (including leaves).
    pub nodes: u64,
    /// Subtrees dropped because every completion is rigid.
    pub pruned_rigid: u64,
    /// Subtrees dropped because every completion has dof ≥ 2.
    pub pruned_flexible: u64,
    /// Full assignments reached.
    pub leaves: u64,
    /// Leaves whose dof = 1 was certified from the incremental factorisation.
    pub certified: u64,
    /// Calls to `mobility::analyze`.
    pub analyses: u64,
    /// Analyses that failed numerically (skipped, never kept).
    pub failures: u64,
    /// Configurations with dof = 1.
    pub mobility_one: u64,
}

impl ExpandStats {
    /// Adds another run's counters.
    pub fn add(&mut self, o: &ExpandStats) {
        self.configurations += o.configurations;
        self.nodes += o.nodes;
        self.pruned_rigid += o.pruned_rigid;
        self.pruned_flexible += o.pruned_flexible;
        self.leaves += o.leaves;
        self.certified += o.certified;
        self.analyses += o.analyses;
        self.failures += o.failures;
        self.mobility_one += o.mobility_one;
    }
}

/// One endpoint choice with exactly one degree of freedom.
#[derive(Debug, Clone, Copy)]
pub struct Leaf<'l> {
    /// Joint choice per unique edge.
    pub joints: &'l [JointChoice],
    /// Unit motion vector, full state (tile 0's entries zero), signed as `analyze` signs it
    /// (when the area rate vanishes, the largest component is made positive; components that
    /// tie within roundoff can make that sign differ from `analyze`'s).
    pub motion: &'l DVec,
    /// True when `mobility::analyze` decided this leaf (false: certified, see module docs).
    pub analysed: bool,
}

/// The joint rows of one cell, ready for expanding many masks.
#[derive(Debug, Clone)]
pub struct Expander<'a> {
    cell: &'a UnitCell,
    /// A jointless mechanism of the cell (state layout and closed state for signing motions).
    reference: Mechanism,
    settings: MobilitySettings,
    /// Reduced column count N = 3n + 1.
    cols: usize,
    /// rows[edge][end][i]: row i of the two Jacobian rows of a joint at that end (0 = A,
    /// 1 = B), as its non-zero entries (column, value).
    rows: Vec<[[SparseRow; 2]; 2]>,
    /// Per edge: the larger squared Frobenius norm of its two row pairs.
    row_weight: Vec<f64>,
    /// Per edge and end: the squared Frobenius norm of the row pair.
    row_sq: Vec<[f64; 2]>,
    /// Per edge, end and row of the pair: the row's Euclidean norm.
    row_norm: Vec<[[f64; 2]; 2]>,
}

/// The non-zero entries (column, value) of one Jacobian row.
type SparseRow = Vec<(usize, f64)>;

/// Working state of one depth-first expansion.
struct Search<'s> {
    edges: Vec<usize>,
    choice: Vec<JointChoice>,
    /// Orthonormal basis rows, `count` of them, each N long.
    q: Vec<f64>,
    /// Orthonormal basis of the complement of Q: N − `count` vectors, each N long.
    comp: Vec<f64>,
    /// Copies of `comp` on the current path, one per depth, for backtracking.
    saved: Vec<f64>,
    /// Scratch vectors (N long): a row's coordinates in the complement, and C · v.
    coords: Vec<f64>,
    image: Vec<f64>,
    /// Lower-triangular factor: selected row i = Σ_j r[i][j] q_j (N × N, row-major).
    r: Vec<f64>,
    /// R⁻¹ (lower triangular, N × N, row-major); its leading `l_valid` rows are up to date.
    /// Row i depends only on R's rows 0..=i, so backtracking keeps the rows before it.
    l: Vec<f64>,
    /// Squared Euclidean norm of each row of R⁻¹ (valid with the row).
    l_sq: Vec<f64>,
    l_valid: usize,
    count: usize,
    /// Set when the basis is full but the rigidity certificate failed.
    uncertain_full: bool,
    threshold_sq: f64,
    stats: ExpandStats,
    visit: &'s mut dyn FnMut(Leaf<'_>),
}

impl<'a> Expander<'a> {
    /// Precomputes the Jacobian rows of every possible joint of `cell` at the closed state.
    pub fn new(
        cell: &'a UnitCell,
        settings: MobilitySettings,
    ) -> Result<Expander<'a>, KinematicsError> {
        let m = cell.edges.len();
        let both = Mechanism::new(cell, &vec![JointChoice::Both; m])?;
        let reference = Mechanism::new(cell, &vec![JointChoice::None; m])?;
        let jac = both.jacobian(&both.rest);
        let cols = jac.ncols() - 3;
        let mut rows = Vec::with_capacity(m);
        let mut row_weight = Vec::with_capacity(m);
        let mut row_sq = Vec::with_capacity(m);
        let mut row_norm = Vec::with_capacity(m);
        for (k, j) in both.joints.chunks(2).enumerate() {
            debug_assert!(j.iter().all(|j| j.edge == k));
            let pair = |idx: usize| -> Vec<f64> {
                let r = 2 * (2 * k + idx);
                (0..2)
                    .flat_map(|d| (3..jac.ncols()).map(move |c| (r + d, c)))
                    .map(|rc| jac[rc])
                    .collect()
            };
            let (a, b) = (pair(0), pair(1));
            let sq = |v: &Vec<f64>| v.iter().map(|x| x * x).sum::<f64>();
            row_weight.push(sq(&a).max(sq(&b)));
            row_sq.push([sq(&a), sq(&b)]);
            let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
            let n = cols;
            row_norm.push([
                [norm(&a[..n]), norm(&a[n..])],
                [norm(&b[..n]), norm(&b[n..])],
            ]);
            let sparse = |v: &[f64]| -> SparseRow {
                v.iter()
                    .enumerate()
                    .filter(|(_, x)| **x != 0.0)
                    .map(|(c, x)| (c, *x))
                    .collect()
            };
            rows.push([
                [sparse(&a[..n]), sparse(&a[n..])],
                [sparse(&b[..n]), sparse(&b[n..])],
            ]);
        }
        Ok(Expander {
            cell,
            reference,
            settings,
            cols,
            rows,
            row_weight,
            row_sq,
            row_norm,
        })
    }

    /// Number of reduced columns N (3n + 1).
    pub fn columns(&self) -> usize {
        self.cols
    }

    /// Expands `mask` (bit k = edge k jointed) and calls `visit` with every endpoint choice
    /// that has exactly one degree of freedom, in depth-first order (A before B, edges
    /// ascending).
    pub fn expand(&self, mask: u32, visit: &mut dyn FnMut(Leaf<'_>)) -> ExpandStats {
        let m = self.rows.len();
        let edges: Vec<usize> = (0..m).filter(|&k| mask >> k & 1 == 1).collect();
        let mut s = self.search(edges, visit);
        s.saved.reserve(4 * self.cols * self.cols);
        self.descend(&mut s, 0);
        s.stats
    }

    /// Collects the dof = 1 endpoint choices of `mask`.
    pub fn expand_collect(&self, mask: u32) -> (Vec<Vec<JointChoice>>, ExpandStats) {
        let mut out = Vec::new();
        let stats = self.expand(mask, &mut |leaf| out.push(leaf.joints.to_vec()));
        (out, stats)
    }

    /// The motion of one endpoint choice when the incremental factorisation certifies that it
    /// has exactly one degree of freedom, as at a certified leaf (see the module docs): the
    /// unit motion vector, full state, signed as `analyze` signs it, and bit for bit the
    /// motion the expansion gives the same choice when it certifies it. `None` when the
    /// certificate does not decide (or `joints` holds a welded edge or has the wrong length):
    /// `mobility::analyze` must.
    pub fn certified_motion(&self, joints: &[JointChoice]) -> Option<DVec> {
        if joints.len() != self.rows.len() || joints.contains(&JointChoice::Both) {
            return None;
        }
        let edges: Vec<usize> = (0..joints.len())
            .filter(|&k| joints[k] != JointChoice::None)
            .collect();
        let mut ignore = |_: Leaf<'_>| {};
        let mut s = self.search(edges, &mut ignore);
        let n = self.cols;
        for k in 0..s.edges.len() {
            let edge = s.edges[k];
            let end = usize::from(joints[edge] == JointChoice::B);
            self.add_joint(&mut s, edge, end);
            s.choice[edge] = joints[edge];
        }
        if s.count + 1 != n {
            return None;
        }
        let threshold = self.settings.rel_tol * self.frobenius_sq(&s).max(1.0);
        self.certified_with(&mut s, n - 1, threshold)
            .then(|| self.null_vector(&s))
    }

    /// A search over `edges` from no rows at all.
    fn search<'s>(&self, edges: Vec<usize>, visit: &'s mut dyn FnMut(Leaf<'_>)) -> Search<'s> {
        let m = self.rows.len();
        let bound: f64 = edges.iter().map(|&k| self.row_weight[k]).sum();
        let n = self.cols;
        let mut comp = vec![0.0; n * n];
        for c in 0..n {
            comp[c * n + c] = 1.0;
        }
        Search {
            choice: vec![JointChoice::None; m],
            q: vec![0.0; n * n],
            comp,
            saved: Vec::new(),
            coords: vec![0.0; n],
            image: vec![0.0; n],
            r: vec![0.0; n * n],
            l: vec![0.0; n * n],
            l_sq: vec![0.0; n],
            l_valid: 0,
            count: 0,
            uncertain_full: false,
            threshold_sq: self.settings.rel_tol * bound.max(1.0),
            stats: ExpandStats {
                configurations: 1u64 << edges.len(),
                ..ExpandStats::default()
            },
            edges,
            visit,
        }
    }

    /// ‖J‖_F² of the current choice (every edge decided): a bound on λ_max of H.
    fn frobenius_sq(&self, s: &Search<'_>) -> f64 {
        s.edges
            .iter()
            .map(|&e| self.row_sq[e][usize::from(s.choice[e] == JointChoice::B)])
            .sum()
    }

    fn descend(&self, s: &mut Search<'_>, depth: usize) {
        s.stats.nodes += 1;
        let n = self.cols;
        let left = s.edges.len() - depth;
        if n > s.count + 2 * left + 1 {
            s.stats.pruned_flexible += 1;
            return;
        }
        if left == 0 {
            self.leaf(s);
            return;
        }
        let edge = s.edges[depth];
        // Keep this node's complement for the second branch.
        let base = s.saved.len();
        let size = (n - s.count) * n;
        s.saved.extend_from_slice(&s.comp[..size]);
        for (end, choice) in [JointChoice::A, JointChoice::B].into_iter().enumerate() {
            let (count, uncertain) = (s.count, s.uncertain_full);
            if end == 1 && count < n {
                s.comp[..size].copy_from_slice(&s.saved[base..base + size]);
            }
            self.add_joint(s, edge, end);
            let pruned = if s.count == n && count < n {
                if self.certified(s, n) {
                    s.stats.pruned_rigid += 1;
                    true
                } else {
                    s.uncertain_full = true;
                    false
                }
            } else {
                false
            };
            if !pruned {
                s.choice[edge] = choice;
                self.descend(s, depth + 1);
                s.choice[edge] = JointChoice::None;
            }
            s.count = count;
            s.uncertain_full = uncertain;
        }
        s.saved.truncate(base);
    }

    fn leaf(&self, s: &mut Search<'_>) {
        s.stats.leaves += 1;
        let n = self.cols;
        // count ≤ N − 2: dof ≥ 2 (an upper bound of the numerical rank, see module docs).
        // count = N with the certificate never reaches a leaf (pruned above).
        if s.count + 1 < n {
            return;
        }
        debug_assert!(s.count < n || s.uncertain_full);
        if s.count + 1 == n {
            // ‖J‖_F² of this leaf bounds λ_max: the zero threshold analyze would use.
            let threshold = self.settings.rel_tol * self.frobenius_sq(s).max(1.0);
            if self.certified_with(s, n - 1, threshold) {
                s.stats.certified += 1;
                s.stats.mobility_one += 1;
                let motion = self.null_vector(s);
                (s.visit)(Leaf {
                    joints: &s.choice,
                    motion: &motion,
                    analysed: false,
                });
                return;
            }
        }
        s.stats.analyses += 1;
        let Ok(mech) = Mechanism::new(self.cell, &s.choice) else {
            s.stats.failures += 1;
            return;
        };
        match analyze(&mech, &mech.rest, self.settings) {
            Ok(mob) if mob.dof == 1 => {
                if let Some(motion) = &mob.motion {
                    s.stats.mobility_one += 1;
                    (s.visit)(Leaf {
                        joints: &s.choice,
                        motion: &motion.vector,
                        analysed: true,
                    });
                }
            }
            Ok(_) => {}
            Err(_) => s.stats.failures += 1,
        }
    }

    /// The unit vector orthogonal to a basis of N − 1 rows (the complement's one vector), as
    /// a full state vector signed the way `mobility` signs motions.
    fn null_vector(&self, s: &Search<'_>) -> DVec {
        let n = self.cols;
        debug_assert_eq!(s.count + 1, n);
        let v = &s.comp[..n];
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut full = DVec::zeros(n + 3);
        for (c, x) in v.iter().enumerate() {
            full[c + 3] = x / norm;
        }
        let rate = area_rate(&self.reference, &self.reference.rest, &full);
        let flip = if rate.abs() > 1e-9 {
            rate < 0.0
        } else {
            full[full.iamax()] < 0.0
        };
        if flip {
            full = -full;
        }
        full
    }

    /// Adds the two rows of a joint at end `end` (0 = A, 1 = B) of `edge`.
    fn add_joint(&self, s: &mut Search<'_>, edge: usize, end: usize) {
        let pair = &self.rows[edge][end];
        let norms = self.row_norm[edge][end];
        self.add_row(s, &pair[0], norms[0]);
        self.add_row(s, &pair[1], norms[1]);
    }

    /// Appends `row` (Euclidean norm `norm`) to the basis when its residual, its projection on
    /// the complement, is not below `DEPENDENT_REL_TOL · norm`; the complement loses that
    /// direction (one Householder reflection of its coordinates). No allocation.
    fn add_row(&self, s: &mut Search<'_>, row: &[(usize, f64)], norm: f64) {
        let n = self.cols;
        let k = s.count;
        if k == n || norm == 0.0 {
            return;
        }
        let d = n - k;
        // The row's coordinates in the complement (sparse products).
        let u = &mut s.coords[..d];
        for (x, cj) in u.iter_mut().zip(s.comp.chunks_exact(n)) {
            *x = row.iter().map(|&(c, v)| cj[c] * v).sum();
        }
        let rho = u.iter().map(|x| x * x).sum::<f64>().sqrt();
        if rho <= DEPENDENT_REL_TOL * norm {
            return;
        }
        // Slot k's R row changes: R⁻¹'s row k (and any after it) must be recomputed.
        s.l_valid = s.l_valid.min(k);
        // R's new row: the row's coefficients on the basis, then its residual.
        let (basis, _) = s.q.split_at(k * n);
        let rrow = &mut s.r[k * n..(k + 1) * n];
        for (x, qj) in rrow.iter_mut().zip(basis.chunks_exact(n)) {
            *x = row.iter().map(|&(c, v)| qj[c] * v).sum();
        }
        rrow[k] = rho;
        for x in &mut rrow[k + 1..] {
            *x = 0.0;
        }
        // Householder reflection H = I − β v vᵀ with v = u + sign(u₀) ρ e₀, so H u = −sign(u₀) ρ e₀:
        // (C H)'s first vector is −sign(u₀) C u / ρ, the new basis direction, and the others
        // span the new complement.
        let sign = if u[0] < 0.0 { -1.0 } else { 1.0 };
        u[0] += sign * rho;
        let beta = 1.0 / (rho * u[0].abs());
        let w = &mut s.image;
        w.fill(0.0);
        for (&vj, cj) in u.iter().zip(s.comp.chunks_exact(n)) {
            for (x, y) in w.iter_mut().zip(cj) {
                *x += vj * y;
            }
        }
        for (&vj, cj) in u.iter().zip(s.comp.chunks_exact_mut(n)) {
            let f = beta * vj;
            for (x, y) in cj.iter_mut().zip(w.iter()) {
                *x -= f * y;
            }
        }
        let qk = &mut s.q[k * n..(k + 1) * n];
        for (x, y) in qk.iter_mut().zip(&s.comp[..n]) {
            *x = -sign * y;
        }
        // Drop the first vector: the last one takes its place.
        if d > 1 {
            s.comp.copy_within((d - 1) * n..d * n, 0);
        }
        s.count = k + 1;
    }

    /// The rigidity certificate of a full basis (see module docs).
    fn certified(&self, s: &mut Search<'_>, n: usize) -> bool {
        let threshold = s.threshold_sq;
        self.certified_with(s, n, threshold)
    }

    /// True when the leading `size` selected rows have σ_min(R)² ≥ margin · `threshold`, via
    /// σ_min(R) ≥ 1/‖R⁻¹‖_F.
    fn certified_with(&self, s: &mut Search<'_>, size: usize, threshold: f64) -> bool {
        let n = self.cols;
        // Rows of R⁻¹ by forward substitution, column by column within a row: entry (i, c)
        // is (δ_ic − Σ_{j=c}^{i−1} r[i][j] · l[j][c]) / r[i][i], the same operations in the
        // same order as solving R x = e_c, so the values do not depend on when they are made.
        for i in s.l_valid..size {
            for c in 0..=i {
                let mut acc = if i == c { 1.0 } else { 0.0 };
                for j in c..i {
                    acc -= s.r[i * n + j] * s.l[j * n + c];
                }
                s.l[i * n + c] = acc / s.r[i * n + i];
            }
            s.l_sq[i] = s.l[i * n..=i * n + i].iter().map(|x| x * x).sum();
        }
        s.l_valid = s.l_valid.max(size);
        let inv_sq: f64 = s.l_sq[..size].iter().sum();
        inv_sq.is_finite() && inv_sq > 0.0 && 1.0 / inv_sq >= RIGID_MARGIN * threshold
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::CellDims;
    use crate::tiling::{Family, Tiling};

    #[test]
    fn rotating_squares_mask_keeps_the_named_design() {
        let f = Family::from_number(76).unwrap();
        let cell = UnitCell::new(&Tiling::default_for(f), CellDims::new(2, 2).unwrap()).unwrap();
        let ex = Expander::new(&cell, MobilitySettings::default()).unwrap();
        assert_eq!(ex.columns(), 13);
        let (found, stats) = ex.expand_collect(0xFF);
        assert_eq!(stats.configurations, 256);
        let named = crate::topology::named_design("rotating-squares").unwrap();
        assert!(found.contains(&named.joints));
        assert_eq!(stats.mobility_one as usize, found.len());
    }

    /// The one-choice certificate the deduplication uses certifies exactly the leaves the
    /// expansion certifies, with the same motion bit for bit, and nothing else.
    #[test]
    fn certified_motion_is_the_certified_leaf() {
        for (n, a, b, mask) in [(76, 2, 2, 0xFFu32), (28, 1, 1, 0x3FF), (44, 1, 1, 0xF)] {
            let f = Family::from_number(n).unwrap();
            let cell =
                UnitCell::new(&Tiling::default_for(f), CellDims::new(a, b).unwrap()).unwrap();
            let ex = Expander::new(&cell, MobilitySettings::default()).unwrap();
            let mut certified = Vec::new();
            ex.expand(mask, &mut |leaf| {
                if !leaf.analysed {
                    certified.push((leaf.joints.to_vec(), leaf.motion.clone()));
                }
            });
            assert!(!certified.is_empty(), "IH{n}");
            let edges: Vec<usize> = (0..cell.edges.len())
                .filter(|k| mask >> k & 1 == 1)
                .collect();
            let mut found = 0;
            for bits in 0u32..1 << edges.len() {
                let mut joints = vec![JointChoice::None; cell.edges.len()];
                for (i, &e) in edges.iter().enumerate() {
                    joints[e] = if bits >> i & 1 == 0 {
                        JointChoice::A
                    } else {
                        JointChoice::B
                    };
                }
                let known = certified.iter().find(|(j, _)| *j == joints);
                match (ex.certified_motion(&joints), known) {
                    (Some(v), Some((_, w))) => {
                        assert!(v
                            .iter()
                            .zip(w.iter())
                            .all(|(x, y)| x.to_bits() == y.to_bits()));
                        found += 1;
                    }
                    (None, None) => {}
                    (v, w) => panic!("IH{n} {joints:?}: {} vs {}", v.is_some(), w.is_some()),
                }
            }
            assert_eq!(found, certified.len(), "IH{n}");
            let mut welded = certified[0].0.clone();
            welded[edges[0]] = JointChoice::Both;
            assert!(ex.certified_motion(&welded).is_none());
            assert!(ex.certified_motion(&welded[1..]).is_none());
        }
    }

    /// Certified leaves carry the motion `analyze` would give, sign included.
    #[test]
    fn certified_motion_equals_analysed_motion() {
        for (n, a, b, mask) in [(76, 2, 2, 0xFFu32), (28, 1, 1, 0x3FF), (44, 1, 1, 0xF)] {
            let f = Family::from_number(n).unwrap();
            let cell =
                UnitCell::new(&Tiling::default_for(f), CellDims::new(a, b).unwrap()).unwrap();
            let ex = Expander::new(&cell, MobilitySettings::default()).unwrap();
            let mut checked = 0;
            ex.expand(mask, &mut |leaf| {
                let mech = Mechanism::new(&cell, leaf.joints).unwrap();
                let mob = analyze(&mech, &mech.rest, MobilitySettings::default()).unwrap();
                assert_eq!(mob.dof, 1);
                let v = &mob.motion.as_ref().unwrap().vector;
                let rate = mob.motion.as_ref().unwrap().area_rate;
                let err = if rate.abs() > 1e-9 {
                    (v - leaf.motion).norm()
                } else {
                    // No area change: the sign follows the largest component, which ties
                    // within roundoff for symmetric motions, in `analyze` as here.
                    (v - leaf.motion).norm().min((v + leaf.motion).norm())
                };
                assert!(err < 1e-8, "IH{n} {:?}", leaf.joints);
                checked += usize::from(!leaf.analysed);
            });
            assert!(checked > 0, "IH{n}");
        }
    }
}

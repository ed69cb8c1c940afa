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
//!   entries are the sparse products q_j · row, made only when a certificate needs them);
//! - R⁻¹ row by row, for the certificates below (the last joint's rows are first bounded in
//!   O(N), and solved only when the bound does not decide, see `certified_with`).
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
use crate::mobility::{analyze, MobilitySettings};
use crate::topology::JointChoice;
use serde::Serialize;

mod factor;

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

/// Which Jacobian row: row `index` (0 or 1) of the joint at end `end` (0 = A, 1 = B) of `edge`.
#[derive(Debug, Clone, Copy, Default)]
struct RowId {
    edge: usize,
    end: usize,
    index: usize,
}

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
    /// Lower-triangular factor: selected row i = Σ_j r[i][j] q_j (N × N, row-major). Its
    /// diagonal is made when a row is added; the entries before it are valid in the leading
    /// `r_valid` rows.
    r: Vec<f64>,
    r_valid: usize,
    /// The Jacobian row in each slot of the basis.
    slot_rows: Vec<RowId>,
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
            r_valid: 0,
            slot_rows: vec![RowId::default(); n],
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

    /// The sparse row `id`.
    fn row(&self, id: RowId) -> &[(usize, f64)] {
        &self.rows[id.edge][id.end][id.index]
    }

    /// Adds the two rows of a joint at end `end` (0 = A, 1 = B) of `edge`.
    fn add_joint(&self, s: &mut Search<'_>, edge: usize, end: usize) {
        for index in 0..2 {
            self.add_row(s, RowId { edge, end, index });
        }
    }
}

#[cfg(test)]
mod tests;

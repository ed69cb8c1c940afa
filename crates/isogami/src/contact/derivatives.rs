//! Gradient and Hessian of the barrier energy, assembled term by term over the few state
//! variables each vertex–edge term touches.

use super::barrier::barrier;
use super::distance::{point_edge_derivatives, Mat6, Vec6};
use super::local::{PairVars, TermJacobian, MAX_LOCAL};
use super::model::ContactModel;
use super::narrow::{for_each_close, shifted_into, VertexEdge};
use super::psd::project_psd;
use super::verlet::PairCache;
use crate::kinematics::Mechanism;
use crate::math::{DMat, DVec, Real, Vec2};
use nalgebra::{SMatrix, SVector};

type LocalVec = SVector<Real, MAX_LOCAL>;
type LocalMat = SMatrix<Real, MAX_LOCAL, MAX_LOCAL>;

/// What happens to the barrier's local Hessians before they are added.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum HessianProjection {
    /// Each vertex–edge term's local Hessian projected to positive semi-definite (negative
    /// eigenvalues clamped to 0), as IPC does: the sum is PSD, Newton directions descend.
    #[default]
    PerTermPsd,
    /// The sum of a pair's terms projected once: also PSD, closer to the exact Hessian and
    /// cheaper (one small eigen-decomposition per pair in contact instead of per term).
    PerPairPsd,
    /// The exact Hessian, indefinite in general (for derivative checks).
    Exact,
}

impl ContactModel {
    /// Adds ∇E_coll(q) to `grad` and the barrier Hessian, each term's local Hessian projected
    /// to positive semi-definite, to `hess` (both over the whole state, length 3n + 4).
    ///
    /// q must be intersection-free (finite [`ContactModel::energy`]); terms at zero distance
    /// are skipped. Nothing is added when `mech`, q, `grad` or `hess` do not fit the model.
    pub fn add_gradient_hessian(
        &self,
        mech: &Mechanism,
        q: &DVec,
        grad: &mut DVec,
        hess: &mut DMat,
    ) {
        self.add_derivatives(mech, q, grad, hess, HessianProjection::PerTermPsd);
    }

    /// [`ContactModel::add_gradient_hessian`] with a choice of Hessian treatment. The
    /// gradient is exact either way. The chain rule includes ∂²x/∂θ² = −R(θ)s.
    pub fn add_derivatives(
        &self,
        mech: &Mechanism,
        q: &DVec,
        grad: &mut DVec,
        hess: &mut DMat,
        projection: HessianProjection,
    ) {
        self.add_derivatives_from(mech, q, grad, hess, projection, None);
    }

    /// [`ContactModel::add_derivatives`] with candidate pairs from `cache`.
    pub(crate) fn add_derivatives_cached(
        &self,
        mech: &Mechanism,
        q: &DVec,
        grad: &mut DVec,
        hess: &mut DMat,
        projection: HessianProjection,
        cache: &mut PairCache,
    ) {
        self.add_derivatives_from(mech, q, grad, hess, projection, Some(cache));
    }

    fn add_derivatives_from(
        &self,
        mech: &Mechanism,
        q: &DVec,
        grad: &mut DVec,
        hess: &mut DMat,
        projection: HessianProjection,
        cache: Option<&mut PairCache>,
    ) {
        let Some(placed) = self.place(mech, q) else {
            return;
        };
        let n = self.layout.len();
        if grad.len() != n || hess.nrows() != n || hess.ncols() != n {
            return;
        }
        let dhat = self.settings.dhat;
        let mut pairs = Vec::with_capacity(64);
        if self
            .for_each_pair(cache, &placed, dhat, |p| pairs.push(p))
            .is_err()
        {
            return;
        }
        let mut other = Vec::new();
        let mut close = Vec::new();
        for pair in &pairs {
            let shift = placed.shift(pair.offset);
            let (ta, tb) = (&placed.tiles[pair.a], &placed.tiles[pair.b]);
            if !ta.aabb.near(&tb.aabb.shifted(shift), dhat) {
                continue;
            }
            shifted_into(&tb.world, shift, &mut other);
            close.clear();
            for_each_close(&ta.world, &other, dhat, |c| close.push(c));
            if close.is_empty() {
                continue;
            }
            let vars = PairVars::new(self.layout, pair);
            let polys = [&ta.world[..], &other[..]];
            let arms = [&ta.arms[..], &tb.arms[..]];
            let (mut pair_g, mut pair_h) = (LocalVec::zeros(), LocalMat::zeros());
            for c in &close {
                let Some((g, h)) = self.term(&vars, polys, arms, c) else {
                    continue;
                };
                if projection == HessianProjection::PerTermPsd {
                    scatter(&vars, &g, &h, true, grad, hess);
                } else {
                    pair_g += g;
                    pair_h += h;
                }
            }
            if projection != HessianProjection::PerTermPsd {
                let project = projection == HessianProjection::PerPairPsd;
                scatter(&vars, &pair_g, &pair_h, project, grad, hess);
            }
        }
    }

    /// Local gradient and exact local Hessian (over `vars`, padded to the maximum size) of
    /// one vertex–edge barrier term, or `None` at zero distance.
    fn term(
        &self,
        vars: &PairVars,
        polys: [&[Vec2]; 2],
        arms: [&[Vec2]; 2],
        c: &VertexEdge,
    ) -> Option<(LocalVec, LocalMat)> {
        let (vs, es) = (c.vertex_side, 1 - c.vertex_side);
        let ne = polys[es].len();
        let (e0, e1) = (c.edge, (c.edge + 1) % ne);
        let dd = point_edge_derivatives(&polys[vs][c.vertex], &polys[es][e0], &polys[es][e1])?;
        let bv = barrier(dd.d, self.settings.dhat, self.settings.stiffness);
        // Over the positions (p, a, b): ∇b = b′∇d, ∇²b = b″∇d∇dᵀ + b′∇²d.
        let g6: Vec6 = dd.grad * bv.db;
        let h6: Mat6 = dd.grad * dd.grad.transpose() * bv.d2b + dd.hess * bv.db;
        let points = [
            (vs, arms[vs][c.vertex]),
            (es, arms[es][e0]),
            (es, arms[es][e1]),
        ];
        let mut jac = TermJacobian::zeros();
        for (k, (side, arm)) in points.iter().enumerate() {
            vars.write_rows(*side, arm, &mut jac, 2 * k);
        }
        let g = jac.transpose() * g6;
        let mut h = jac.transpose() * h6 * jac;
        // Second derivative of each position: ∂²x/∂θ² = −R(θ)s = −arm.
        for (k, (side, arm)) in points.iter().enumerate() {
            let th = vars.theta_slot(*side);
            h[(th, th)] -= g6[2 * k] * arm.x + g6[2 * k + 1] * arm.y;
        }
        Some((g, h))
    }
}

/// Adds a local gradient and (optionally projected) local Hessian into the global ones.
fn scatter(
    vars: &PairVars,
    g: &LocalVec,
    h: &LocalMat,
    project: bool,
    grad: &mut DVec,
    hess: &mut DMat,
) {
    let m = vars.len;
    for i in 0..m {
        grad[vars.global[i]] += g[i];
    }
    let mut local = DMat::from_fn(m, m, |i, j| h[(i, j)]);
    if project {
        match project_psd(&local) {
            Some(p) => local = p,
            // Only non-finite entries make this fail; such a term has no usable curvature.
            None => return,
        }
    }
    for i in 0..m {
        for j in 0..m {
            hess[(vars.global[i], vars.global[j])] += local[(i, j)];
        }
    }
}

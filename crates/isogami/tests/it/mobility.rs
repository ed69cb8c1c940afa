//! Kinematics and mobility: exact derivatives against finite differences, analytic
//! mechanisms, and invariance of the counts under scaling and rotation.

use crate::common;

use common::{cell_of, perturbed, perturbed_params, random_joints, rotating_squares, Rng};
use isogami::cell::CellDims;
use isogami::kinematics::Mechanism;
use isogami::math::{DMat, DVec};
use isogami::mobility::{analyze, MobilitySettings};
use isogami::tiling::Family;
use isogami::topology::JointChoice;

fn fd_jacobian(m: &Mechanism, q: &DVec, h: f64) -> DMat {
    let n = q.len();
    let c0 = m.residual(q);
    let mut jac = DMat::zeros(c0.len(), n);
    for k in 0..n {
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[k] += h;
        qm[k] -= h;
        jac.set_column(k, &((m.residual(&qp) - m.residual(&qm)) / (2.0 * h)));
    }
    jac
}

fn fd_hessian(m: &Mechanism, q: &DVec, h: f64) -> DMat {
    let n = q.len();
    let mut hess = DMat::zeros(n, n);
    for k in 0..n {
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[k] += h;
        qm[k] -= h;
        hess.set_column(k, &((m.gradient(&qp) - m.gradient(&qm)) / (2.0 * h)));
    }
    hess
}

/// Designs with joints across cell boundaries, self-translate joints and welded edges.
fn sample_mechanisms() -> Vec<Mechanism> {
    let mut rng = Rng::new(11);
    let mut out = vec![rotating_squares().2];
    for n in [1, 7, 28, 41, 56, 90] {
        let f = Family::from_number(n).unwrap();
        let p = if f.param_count() > 0 {
            perturbed_params(&mut rng, f, 0.05)
        } else {
            vec![]
        };
        let cell = cell_of(f, &p, "2x1".parse().unwrap());
        let mut joints = random_joints(&mut rng, cell.edges.len());
        joints[0] = JointChoice::Both;
        out.push(Mechanism::new(&cell, &joints).unwrap());
    }
    out
}

#[test]
fn jacobian_matches_finite_differences() {
    let mut rng = Rng::new(12);
    for m in sample_mechanisms() {
        for _ in 0..3 {
            let q = perturbed(&mut rng, &m.rest, 0.2);
            let err = (m.jacobian(&q) - fd_jacobian(&m, &q, 1e-6)).abs().max();
            assert!(err < 1e-8, "jacobian error {err}");
        }
    }
}

#[test]
fn hessian_matches_finite_differences_of_gradient() {
    let mut rng = Rng::new(13);
    for m in sample_mechanisms() {
        for _ in 0..3 {
            // Far from rest, so the residual terms Σ c_k ∇²c_k matter.
            let q = perturbed(&mut rng, &m.rest, 0.3);
            let exact = m.hessian(&q);
            let gn = {
                let j = m.jacobian(&q);
                j.transpose() * j
            };
            let err = (&exact - fd_hessian(&m, &q, 1e-6)).abs().max();
            assert!(err < 1e-6, "hessian error {err}");
            if !m.joints.is_empty() {
                assert!(
                    (&exact - gn).abs().max() > 1e-4,
                    "second-order terms must be present"
                );
            }
        }
    }
}

#[test]
fn gradient_matches_finite_differences_of_energy() {
    let mut rng = Rng::new(14);
    for m in sample_mechanisms() {
        let q = perturbed(&mut rng, &m.rest, 0.3);
        let g = m.gradient(&q);
        for k in 0..q.len() {
            let h = 1e-6;
            let (mut qp, mut qm) = (q.clone(), q.clone());
            qp[k] += h;
            qm[k] -= h;
            let fd = (m.energy(&qp) - m.energy(&qm)) / (2.0 * h);
            assert!(
                (fd - g[k]).abs() < 1e-7 * (1.0 + g[k].abs()),
                "dE/dq{k}: {fd} vs {}",
                g[k]
            );
        }
    }
}

#[test]
fn closed_state_satisfies_every_joint() {
    for f in Family::all() {
        let cell = cell_of(f, &f.default_params(), CellDims::MINIMAL);
        let joints = vec![JointChoice::Both; cell.edges.len()];
        let m = Mechanism::new(&cell, &joints).unwrap();
        let r = m.residual(&m.rest).amax();
        assert!(r < 1e-9, "{f}: {r}");
    }
}

#[test]
fn rotating_squares_has_one_counter_rotating_mode() {
    let (_, cell, m) = rotating_squares();
    let mob = analyze(&m, &m.rest, MobilitySettings::default()).unwrap();
    assert_eq!(mob.dof, 1);
    assert!(mob.gap_decades.unwrap() > 10.0, "gap {:?}", mob.gap_decades);
    let motion = mob.motion.unwrap();
    // The motion is in the null space of J.
    assert!((m.jacobian(&m.rest) * &motion.vector).amax() < 1e-12);
    // Relative to the mean rotation, chessboard neighbours turn by equal and opposite amounts.
    let omega: Vec<f64> = motion.tiles.iter().map(|t| t.omega).collect();
    let mean = omega.iter().sum::<f64>() / omega.len() as f64;
    let dev0 = omega[0] - mean;
    assert!(dev0.abs() > 0.1);
    for (i, t) in cell.tiles.iter().enumerate() {
        let even = (t.copy[0] + t.copy[1]) % 2 == 0;
        let expected = if even { dev0 } else { -dev0 };
        assert!(
            (omega[i] - mean - expected).abs() < 1e-12,
            "tile {i}: {omega:?}"
        );
    }
    // The sheet opens isotropically: u̇ ⟂ rotation-free part equal for u and w.
    assert!(motion.area_rate > 0.0);
    let (u, w) = (cell.u, cell.w);
    let du = isogami::math::vec2(motion.u[0], motion.u[1]);
    let dw = isogami::math::vec2(motion.w[0], motion.w[1]);
    // Strain rate: symmetric part of L with [du dw] = L [u w] is a multiple of the identity.
    let l = isogami::math::Mat2::from_columns(&[du, dw])
        * isogami::math::Mat2::from_columns(&[u, w])
            .try_inverse()
            .unwrap();
    let d = (l + l.transpose()) * 0.5;
    assert!(
        (d[(0, 0)] - d[(1, 1)]).abs() < 1e-12 && d[(0, 1)].abs() < 1e-12,
        "{d}"
    );
}

#[test]
fn welded_and_free_sheets() {
    for n in [76, 28, 7, 41] {
        let f = Family::from_number(n).unwrap();
        for dims in ["1x1", "2x2"] {
            let cell = cell_of(f, &f.default_params(), dims.parse().unwrap());
            let both = Mechanism::new(&cell, &vec![JointChoice::Both; cell.edges.len()]).unwrap();
            assert_eq!(
                analyze(&both, &both.rest, Default::default()).unwrap().dof,
                0,
                "{f} {dims}"
            );
            let none = Mechanism::new(&cell, &vec![JointChoice::None; cell.edges.len()]).unwrap();
            let mob = analyze(&none, &none.rest, Default::default()).unwrap();
            assert_eq!(mob.dof, 3 * (cell.tiles.len() - 1) + 4, "{f} {dims}");
            assert!(mob.motion.is_some());
        }
    }
}

#[test]
fn counts_do_not_depend_on_scale_or_rotation() {
    let mut rng = Rng::new(16);
    let mut histogram = [0usize; 4];
    for f in Family::all().step_by(3) {
        let cell = cell_of(f, &f.default_params(), CellDims::MINIMAL);
        for _ in 0..4 {
            let joints = random_joints(&mut rng, cell.edges.len());
            let base = Mechanism::new(&cell, &joints).unwrap();
            let b = analyze(&base, &base.rest, Default::default()).unwrap();
            histogram[b.dof.min(3)] += 1;
            for (scale, angle) in [(1000.0, 0.0), (1.0, 0.7), (1e-3, -2.1)] {
                let moved = cell.transformed(scale, angle);
                let m = Mechanism::new(&moved, &joints).unwrap();
                let r = analyze(&m, &m.rest, Default::default()).unwrap();
                assert_eq!(r.dof, b.dof, "{f} scale {scale} angle {angle}");
                for (x, y) in r.eigenvalues.iter().zip(&b.eigenvalues) {
                    assert!((x - y).abs() < 1e-9 * (1.0 + y.abs()), "{f}: {x} vs {y}");
                }
            }
        }
    }
    // The sample must cover rigid, one-DOF and floppy designs to mean anything.
    assert!(
        histogram[0] > 0 && histogram[1] > 0 && histogram[2] + histogram[3] > 0,
        "{histogram:?}"
    );
}

#[test]
fn every_mode_is_a_null_vector_of_the_jacobian() {
    let mut rng = Rng::new(17);
    for f in Family::all() {
        let cell = cell_of(f, &f.default_params(), CellDims::MINIMAL);
        let joints = random_joints(&mut rng, cell.edges.len());
        let m = Mechanism::new(&cell, &joints).unwrap();
        let mob = analyze(&m, &m.rest, Default::default()).unwrap();
        let jac = m.jacobian(&m.rest);
        assert_eq!(mob.modes.len(), mob.dof);
        for mode in &mob.modes {
            assert!((mode.vector.norm() - 1.0).abs() < 1e-12);
            assert!(mode.vector.rows(0, 3).amax() == 0.0, "tile 0 is fixed");
            assert!((&jac * &mode.vector).amax() < 1e-6, "{f}: |Jv| too large");
        }
        assert!(mob.eigenvalues.windows(2).all(|w| w[0] <= w[1]));
    }
}

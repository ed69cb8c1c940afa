"""Measure functions against independent numpy computations, and their bad inputs."""

import math

import numpy as np
import pytest

import isogami

RNG = np.random.default_rng(11)


def random_f():
    while True:
        f = np.eye(2) + 0.4 * RNG.standard_normal((2, 2))
        if np.linalg.det(f) > 0.1:
            return f


def sym_sqrt(m):
    w, v = np.linalg.eigh(m)
    return v @ np.diag(np.sqrt(w)) @ v.T


def test_deformation_gradient_maps_closed_to_current_vectors():
    for _ in range(20):
        u0, w0 = RNG.standard_normal(2), RNG.standard_normal(2)
        if abs(u0[0] * w0[1] - u0[1] * w0[0]) < 0.2:
            continue
        f_true = random_f()
        F = isogami.deformation_gradient(u0, w0, f_true @ u0, f_true @ w0)
        assert F.shape == (2, 2) and np.allclose(F, f_true, atol=1e-12)


def test_polar_decomposition_matches_numpy():
    for _ in range(20):
        F = random_f()
        R, U = isogami.polar(F)
        assert np.allclose(U, sym_sqrt(F.T @ F), atol=1e-12)
        assert np.allclose(R @ U, F, atol=1e-12)
        assert np.allclose(R.T @ R, np.eye(2), atol=1e-12) and np.linalg.det(R) > 0
    R, U = isogami.polar([[1.0, 0.0], [0.0, 1.0]])
    assert np.array_equal(R, np.eye(2)) and np.array_equal(U, np.eye(2))


def test_expansions_directions_profiles_and_area():
    for _ in range(20):
        F = random_f()
        _, U = isogami.polar(F)
        lo, hi = isogami.principal_expansions(U)
        assert np.allclose([lo, hi], np.linalg.eigvalsh(U) - 1, atol=1e-12)
        a = isogami.principal_direction(U)
        assert -math.pi / 2 < a <= math.pi / 2
        assert abs(isogami.directional_expansion(U, a) - hi) < 1e-12
        assert abs(isogami.directional_expansion(U, a + math.pi / 2) - lo) < 1e-12
        p = isogami.expansion_profile(U, samples=64)
        assert p.shape == (64, 2) and np.allclose(p[:, 0], np.arange(64) * 2 * math.pi / 64)
        d = np.stack([np.cos(p[:, 0]), np.sin(p[:, 0])], 1)
        assert np.allclose(p[:, 1], np.einsum("ij,jk,ik->i", d, U - np.eye(2), d), atol=1e-12)
        assert abs(isogami.area_ratio(F) - np.linalg.det(F)) < 1e-12


def test_poisson_ratio():
    assert isogami.poisson_ratio(0.3, 0.3) == -1.0
    assert isogami.poisson_ratio(-0.1, 0.2) == pytest.approx(0.5)
    assert isogami.poisson_ratio(0.1, 0.0) is None
    assert isogami.poisson_ratio(float("nan"), 0.2) is None


def test_measures_of_a_deployment_agree_with_the_functions():
    run = isogami.deploy(isogami.SAMPLE_OPENING_DESIGNS[3])
    for k in (0, len(run) // 2, len(run) - 1):
        F = run.F[k]
        R, U = isogami.polar(F)
        assert np.allclose(U, run.U[k], atol=1e-12)
        assert np.allclose(isogami.principal_expansions(U), run.principal_expansions[k], atol=1e-12)
        assert abs(isogami.area_ratio(F) - run.area_ratio[k]) < 1e-12
        (u0, w0), (u, w) = run.tiling_vectors[0], run.tiling_vectors[k]
        assert np.allclose(isogami.deformation_gradient(u0, w0, u, w), F, atol=1e-9)


@pytest.mark.parametrize(
    "call,error",
    [
        (lambda: isogami.polar([[1, 0], [0, -1]]), isogami.MeasureError),
        (lambda: isogami.polar([[0, 0], [0, 0]]), isogami.MeasureError),
        (lambda: isogami.polar([[float("nan"), 0], [0, 1]]), ValueError),
        (lambda: isogami.polar([[1, 0, 0], [0, 1, 0]]), ValueError),
        (lambda: isogami.polar("F"), ValueError),
        (lambda: isogami.polar(None), TypeError),
        (lambda: isogami.deformation_gradient([1, 0], [2, 0], [1, 0], [0, 1]), isogami.MeasureError),
        (lambda: isogami.deformation_gradient([1, 0], [0, 1], [float("inf"), 0], [0, 1]), ValueError),
        (lambda: isogami.principal_expansions([[1, 0], [0, float("nan")]]), ValueError),
        (lambda: isogami.principal_direction([[1, 0], [float("inf"), 1]]), ValueError),
        (lambda: isogami.directional_expansion(np.eye(2), float("nan")), ValueError),
        (lambda: isogami.expansion_profile(np.eye(2), samples=1), isogami.SettingsError),
        (lambda: isogami.expansion_profile(np.eye(2), samples=-1), ValueError),  # not a bare OverflowError
        (lambda: isogami.area_ratio([[1, 0], [0, float("nan")]]), ValueError),
        (lambda: isogami.poisson_ratio("a", 1.0), TypeError),
    ],
)
def test_bad_measure_inputs(call, error):
    with pytest.raises(error):
        call()

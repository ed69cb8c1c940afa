"""Mobility: DOF, spectrum and gap (numpy), first-order motions, equal to `isogami analyze`."""

import numpy as np
import pytest

import isogami
from conftest import assert_same


@pytest.mark.parametrize("spec", isogami.SAMPLE_OPENING_DESIGNS[:6] + ["IH90::1x1:xxx", "IH90::1x1:a--"])
def test_analysis_equals_the_cli(cli, spec):
    want = cli("analyze", "--design", spec, "--json", "--no-margins")
    a = isogami.analyze(spec)
    assert isinstance(a, isogami.Analysis)
    assert all(isinstance(m, isogami.Motion) for m in a.modes)
    assert_same(a.to_dict(), want)
    assert a.dof == want["dof"] and a.design == want["design"]
    assert (a.tiles, a.edges, a.joints) == (want["tiles"], want["edges"], want["joints"])
    assert np.allclose(a.eigenvalues, want["eigenvalues"], rtol=1e-12, atol=1e-12)
    assert isinstance(a.spectrum, np.ndarray) and np.array_equal(a.spectrum, a.eigenvalues)
    assert a.threshold == pytest.approx(want["threshold"], rel=1e-12)
    assert a.gap_decades == (None if want["gap_decades"] is None else pytest.approx(want["gap_decades"], rel=1e-12))
    if want["motion"] is None:
        assert a.motion is None
    else:
        m = a.motion
        t = np.array([[v["vx"], v["vy"], v["omega"]] for v in want["motion"]["tiles"]])
        assert np.allclose(m.tiles, t, rtol=0, atol=1e-12)
        assert np.allclose(m.u, want["motion"]["u"], rtol=0, atol=1e-12)
        assert m.area_rate == pytest.approx(want["motion"]["area_rate"], rel=1e-12, abs=1e-12)
    assert len(a.modes) == a.dof == len(want["modes"])


def test_one_dof_motion_is_a_unit_null_vector():
    a = isogami.analyze("rotating-squares")
    assert a.dof == 1 and a.gap_decades > 6
    z, nz = a.gap
    assert z == a.largest_zero < a.threshold <= a.smallest_nonzero == nz
    assert np.count_nonzero(a.eigenvalues < a.threshold) == a.dof
    v = a.motion.vector
    assert abs(np.linalg.norm(v) - 1) < 1e-12 and np.allclose(v[:3], 0)  # tile 0 held
    assert a.motion.area_rate > 0  # signed to open
    # Rotating squares, tile 0 held: its two neighbours turn alike, the diagonal square
    # (same chessboard colour as tile 0) not at all relative to it.
    omega = a.motion.tiles[:, 2]
    assert abs(omega[1]) > 0.1 and abs(omega[1] - omega[2]) < 1e-12
    assert abs(omega[0]) < 1e-12 and abs(omega[3]) < 1e-12
    assert "dof 1" in repr(a) and "Motion" in repr(a.motion)


def test_rigid_and_underconstrained_designs():
    rigid = isogami.analyze("IH90::1x1:xxx")
    assert rigid.dof == 0 and rigid.motion is None and rigid.modes == [] and rigid.gap.size == 0
    assert rigid.largest_zero is None and rigid.gap_decades is None
    loose = isogami.analyze("IH76::2x2:bbbb----")
    assert loose.dof == len(loose.modes) > 1
    # Several DOF: the opening motion is the fastest-opening unit combination of the modes.
    basis = np.array([m.vector for m in loose.modes])
    v = loose.motion.vector
    assert abs(np.linalg.norm(v) - 1) < 1e-12
    assert np.allclose(basis.T @ (basis @ v), v, atol=1e-9)  # in the span of the modes
    assert loose.motion.area_rate >= max(m.area_rate for m in loose.modes) - 1e-12


@pytest.mark.parametrize("tol", [0.0, 1.0, -1e-9, float("nan"), float("inf")])
def test_bad_tolerance_is_a_settings_error(tol):
    with pytest.raises(isogami.SettingsError, match="mobility tolerance"):
        isogami.analyze("rotating-squares", tol=tol)


def test_tolerance_changes_the_count():
    spec = isogami.SAMPLE_OPENING_DESIGNS[1]
    loose = isogami.analyze(spec, tol=0.5)
    assert loose.dof >= isogami.analyze(spec).dof


def test_bad_design_arguments():
    with pytest.raises(TypeError, match="design must be"):
        isogami.analyze(12)
    with pytest.raises(isogami.DesignError):
        isogami.analyze("IH90::1x1:a")

"""Families: the 81 isohedral types with parameters, parameter ranges, prototiles, samples."""

import numpy as np
import pytest

import isogami
from conftest import assert_same


def test_families_equal_the_cli_listing(cli):
    want = cli("families", "--json")
    got = isogami.families()
    assert len(got) == 81 and all(isinstance(f, isogami.Family) for f in got)
    assert_same([f.info() for f in got], want)
    for f, w in zip(got, want):
        assert f.name == w["name"] and f.number == w["number"]
        assert f.param_count == w["param_count"] == len(f.default_params)
        assert f.default_params == w["default_params"]
        assert (f.vertex_count, f.aspect_count) == (w["vertex_count"], w["aspect_count"])
        assert f.edges == w["edges"]


def test_family_lookup_by_name_number_and_object():
    f = isogami.family("IH28")
    assert isogami.family("ih28") == f == isogami.family(28) == isogami.family("28")
    assert isogami.family(f) == f
    assert str(f) == "IH28" and hash(f) == hash(isogami.family(28))
    assert "IH28" in repr(f)


@pytest.mark.parametrize("bad", ["IH19", "IH94", "", "IH", "square", -1, 10**30])
def test_unknown_family_is_a_tiling_error(bad):
    with pytest.raises(isogami.TilingError, match="unknown tiling family"):
        isogami.family(bad)


def test_family_rejects_wrong_types():
    with pytest.raises(TypeError, match="family must be"):
        isogami.family(2.5)
    with pytest.raises(TypeError):
        isogami.family(None)
    with pytest.raises(TypeError):
        isogami.family(True)


def test_param_ranges_surround_the_defaults_and_hold_every_sample():
    for f in isogami.families():
        r = f.param_ranges()
        assert r.shape == (f.param_count, 2)
        d = np.array(f.default_params)
        assert np.all(r[:, 0] < d) and np.all(d < r[:, 1]), f.name
        wider = f.param_ranges(span=0.6)
        assert np.allclose(wider[:, 1] - wider[:, 0], 2 * (r[:, 1] - r[:, 0]))
        for p in f.sample_params(levels=3, max_samples=8):
            assert np.all(r[:, 0] - 1e-12 <= p) and np.all(p <= r[:, 1] + 1e-12), (f.name, p)


def test_sample_params_start_with_defaults_and_are_valid():
    f = isogami.family("IH28")
    samples = f.sample_params(levels=3, max_samples=10)
    assert samples[0] == f.default_params
    assert 1 < len(samples) <= 10
    assert len({tuple(s) for s in samples}) == len(samples)
    for p in samples:
        f.check_params(p)  # valid: no exception
    assert isogami.family("IH76").sample_params() == [[]]  # no parameters


@pytest.mark.parametrize(
    "kwargs", [dict(levels=1), dict(levels=17), dict(span=0.0), dict(span=float("nan")), dict(max_samples=0)]
)
def test_sample_params_settings_are_checked(kwargs):
    with pytest.raises(isogami.SettingsError):
        isogami.family("IH28").sample_params(**kwargs)
    if "span" in kwargs:
        with pytest.raises(isogami.SettingsError):
            isogami.family("IH28").param_ranges(span=kwargs["span"])


def test_prototile_and_parameter_checks():
    f = isogami.family("IH28")
    p = f.prototile()
    assert p.shape == (f.vertex_count, 2)
    x, y = p[:, 0], p[:, 1]
    assert 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0  # counter-clockwise
    moved = f.prototile([0.2, 0.6])
    assert moved.shape == p.shape and not np.allclose(moved, p)
    with pytest.raises(isogami.TilingError, match="takes 2 shape parameter"):
        f.check_params([0.1])
    with pytest.raises(isogami.TilingError, match="v1 is NaN"):
        f.check_params([0.1, float("nan")])
    with pytest.raises(isogami.TilingError, match="v0=-1 give.* self-intersecting"):
        f.prototile([-1.0, 0.5])
    with pytest.raises(TypeError):
        f.check_params("0.1,0.5")

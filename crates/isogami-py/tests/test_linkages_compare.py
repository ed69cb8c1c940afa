"""Linkages and the baseline comparison, equal to `isogami linkages` and `isogami compare`."""

import pytest

import isogami
from conftest import assert_same


@pytest.mark.parametrize("spec", ["rotating-squares"] + isogami.SAMPLE_OPENING_DESIGNS[1:6])
def test_linkages_equal_the_cli(cli, spec):
    want = cli("linkages", "--design", spec, "--json")
    got = isogami.linkages(spec)
    assert isinstance(got, isogami.Linkages)
    assert_same(got.to_dict(), want)
    assert got.signature == want["signature"]
    assert got.bars == [l["bars"] for l in want["linkages"]] and len(got) == len(want["linkages"])
    assert got.linkages == want["linkages"] and got.other_faces == want["other_faces"]
    assert {str(k): v for k, v in got.degree_histogram.items()} == want["degree_histogram"]
    tiles = isogami.design(spec).unit_cell().tile_count
    owners = got.tile_linkages()
    assert len(owners) == tiles
    for tile, ks in enumerate(owners):
        want_ks = [k for k, l in enumerate(want["linkages"]) if any(n[0] == tile for n in l["nodes"])]
        assert ks == want_ks


def test_rotating_squares_linkages():
    l = isogami.linkages(isogami.design("rotating-squares"))
    assert l.signature == "4×4-bar" and l.bars == [4, 4, 4, 4]
    assert "<svg" in l.svg() and l._repr_svg_() == l.svg() and "4×4-bar" in repr(l)


def test_linkages_bad_inputs():
    with pytest.raises(isogami.DesignError):
        isogami.linkages("IH90::1x1:a")
    with pytest.raises(TypeError):
        isogami.linkages(None)


def drop_times(rows):
    for row in rows:
        for r in row["results"]:
            r.pop("millis")
    return rows


@pytest.mark.parametrize("spec", ["rotating-squares", isogami.COMPARISON_DESIGNS[1]])
def test_compare_equals_the_cli(cli, spec):
    want = drop_times(cli("compare", "--design", spec, "--json"))[0]
    c = isogami.compare(spec)
    assert isinstance(c, isogami.Comparison)
    assert all(isinstance(r, isogami.MethodResult) for r in c.results)
    got = drop_times([c.to_dict()])[0]
    assert_same(got, want)
    assert c.design == want["design"] and c.dof == want["dof"] and len(c) == 3
    for r, w in zip(c.results, want["results"]):
        assert r.method == w["method"] and r.end_reason == w["end_reason"]["kind"]
        for name in ["final_t", "path_distance", "max_area_ratio", "max_area_t", "final_area_ratio",
                     "max_expansion", "min_expansion", "max_tile_rotation", "reached_peak_area",
                     "steps", "attempts"]:
            assert_same(getattr(r, name), w[name], name)
        assert r.millis > 0 and r.to_dict()["method"] == r.method
    assert c.result("ncm").method == "ncm" and "ncm" in repr(c)


def test_compare_with_settings_and_kerf(cli):
    want = drop_times(cli("compare", "--design", "rotating-squares", "--kerf", "0.03", "--json"))[0]
    by_kw = isogami.compare("rotating-squares", kerf=0.03)
    by_obj = isogami.compare("rotating-squares", isogami.DeploySettings(kerf=0.03, method="springs"))
    assert_same(drop_times([by_kw.to_dict()])[0], want)
    assert_same(drop_times([by_obj.to_dict()])[0], want)  # the method is ignored


def test_compare_bad_inputs():
    with pytest.raises(isogami.SettingsError):
        isogami.compare("rotating-squares", kerf=-1.0)
    with pytest.raises(isogami.DeployError):
        isogami.compare("IH90::1x1:xxx")
    with pytest.raises(isogami.SettingsError):
        isogami.compare("rotating-squares").result("bogus")
    with pytest.raises(TypeError):
        isogami.compare("rotating-squares", speed=3)

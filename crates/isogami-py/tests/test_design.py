"""Designs: from a name, a spec string, JSON (text or dict) or keyword arguments; checks."""

import json
import pickle

import pytest

import isogami
from conftest import assert_same

SQUARES = "IH76::2x2:bbbbaaaa"


def test_every_form_gives_the_same_design():
    by_name = isogami.design("rotating-squares")
    assert by_name.spec == SQUARES == str(by_name)
    assert isogami.Design.named("rotating-squares") == by_name
    assert isogami.Design.from_spec(SQUARES) == by_name
    assert isogami.design(SQUARES) == by_name
    assert isogami.Design.from_json(by_name.to_json()) == by_name
    assert isogami.Design.from_json(by_name.to_dict()) == by_name
    assert isogami.design(by_name.to_json()) == by_name
    assert isogami.Design(family="IH76", cell=(2, 2), joints="bbbbaaaa") == by_name
    assert isogami.Design("IH76", [], "2x2", list("bbbbaaaa")) == by_name
    assert isogami.Design(76, None, "2x2", ["b"] * 4 + ["a"] * 4) == by_name
    assert "rotating-squares" in isogami.NAMED_DESIGNS


def test_design_fields():
    d = isogami.design("IH28:0.2,0.6:1x1:ab-ba-ab-b")
    assert d.family == "IH28" and d.params == [0.2, 0.6] and d.cell == (1, 1)
    assert d.joints == "ab-ba-ab-b" and d.edge_count == 10 and d.joint_count == 7
    assert d.to_dict() == json.loads(d.to_json())
    assert d.to_dict()["joints"][0] == {"edge": 0, "at": "a"}
    assert isogami.Design("IH90", cell="1x1", joints="x--").joint_count == 2
    assert isogami.Design("IH90", cell="1x1", joints=["both", "none", "a"]).joints == "x-a"
    # Keyword form without parameters takes the family's defaults.
    assert isogami.Design("IH28", joints="-" * 10).params == isogami.family("IH28").default_params


def test_spec_round_trips_bit_for_bit():
    for spec in isogami.SAMPLE_OPENING_DESIGNS + isogami.COMPARISON_DESIGNS:
        d = isogami.design(spec)
        again = isogami.Design.from_spec(d.spec)
        assert again == d and again.params == d.params and again.spec == d.spec


def test_designs_are_hashable_picklable_and_immutable():
    a, b = isogami.design("rotating-squares"), isogami.design(SQUARES)
    assert hash(a) == hash(b) and len({a, b}) == 1
    assert a != isogami.design("IH90::1x1:aaa") and a != SQUARES
    assert pickle.loads(pickle.dumps(a)) == a
    with pytest.raises(AttributeError):
        a.joints = "aaaaaaaa"
    assert repr(a) == f"isogami.Design({SQUARES!r})"


def test_with_params_and_with_joints_are_checked():
    d = isogami.design("IH28:0.2,0.6:1x1:ab-ba-ab-b")
    assert d.with_params([0.25, 0.55]).params == [0.25, 0.55]
    assert d.with_params([0.25, 0.55]).joints == d.joints
    assert d.with_joints("a--b------").joints == "a--b------"
    with pytest.raises(isogami.TilingError):
        d.with_params([0.25])
    with pytest.raises(isogami.DesignError, match="10 unique edges"):
        d.with_joints("a-")


def test_unit_cell_geometry_and_svg(cli):
    d = isogami.design("IH28:0.2,0.6:1x1:ab-ba-ab-b")
    want = cli("cell", "--family", "IH28", "--params", "0.2,0.6", "--cell", "1x1", "--json")
    assert_same(d.unit_cell().to_dict(), want)
    g = d.geometry()
    assert g["family"] == "IH28" and g["cell"] == [1, 1]
    assert "".join(e["joint"] for e in g["edges"]) == d.joints
    assert len(g["tiles"]) == d.unit_cell().tile_count
    assert d.svg().count("<") > 10 and d._repr_svg_() == d.svg()


@pytest.mark.parametrize(
    "text,error,needle",
    [
        ("IH999::1x1:a", isogami.TilingError, "unknown tiling family"),
        ("nonsense", isogami.DesignError, "FAMILY:PARAMS:CELL:JOINTS"),
        ("IH28:nan,0.5:1x1:aaaaaaaaaa", isogami.TilingError, "NaN"),
        ("IH28:0.1,zz:1x1:aaaaaaaaaa", isogami.DesignError, "not a number"),
        ("IH28::9x9:a", isogami.CellError, "9x9"),
        ("IH90::1x1:aa", isogami.DesignError, "3 unique edges"),
        ("IH90::1x1:aqa", isogami.DesignError, "joint character"),
        ("IH28:-1,0.5:1x1:aaaaaaaaaa", isogami.TilingError, "v0=-1 give"),
        ("{bad json", isogami.DesignError, "design JSON"),
        ('{"family": "IH90", "cell": [1, 1], "joints": [{"edge": 7, "at": "a"}]}', isogami.DesignError, "out of range"),
        ("", isogami.DesignError, "FAMILY"),
    ],
)
def test_bad_designs_raise_the_library_error(text, error, needle):
    with pytest.raises(error, match=needle):
        isogami.design(text)
    assert issubclass(error, isogami.IsogamiError)


def test_bad_keyword_designs():
    with pytest.raises(TypeError, match="needs joints"):
        isogami.Design("IH90")
    with pytest.raises(isogami.DesignError):
        isogami.Design("IH90", joints=["a", "abc", "a"])
    with pytest.raises(TypeError, match="joints must be"):
        isogami.Design("IH90", joints=3)
    with pytest.raises(TypeError, match="cell must be"):
        isogami.Design("IH90", cell=1.5, joints="aaa")
    with pytest.raises(isogami.CellError):
        isogami.Design("IH90", cell=(300, 1), joints="aaa")
    with pytest.raises(TypeError):
        isogami.Design("IH90", params="x", joints="aaa")
    with pytest.raises(isogami.DesignError, match="no design is named"):
        isogami.Design.named("rotating-hexagons")
    with pytest.raises(TypeError, match="design JSON must be"):
        isogami.Design.from_json(42)
    with pytest.raises(TypeError):
        isogami.design(None)

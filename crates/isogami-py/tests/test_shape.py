"""Shape-aware mobility from Python: the same answers as `isogami shape --json`, moved
designs that keep one DOF by the deployment binding, the rank-drop search, and errors."""

import pytest

import isogami

IH2 = "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:aa-aa-"
OFF = "IH2:0.12239750492,0.5,0.225335752741,0.24:1x1:aa-aa-"


def test_classification_equals_the_cli(cli):
    got = isogami.shape_mobility(IH2)
    assert got == cli("shape", "--design", IH2, "--json")
    assert got["class"] == "special" and len(got["constraints"]) == 1
    generic = isogami.shape_mobility("IH28:0.588675134594,0.35:1x1:a--a-b-bbb")
    assert generic["class"] == "generic" and generic["constraints"] == []


def test_following_keeps_one_dof_and_matches_the_cli(cli):
    moved = isogami.follow_shape(IH2, 2, 0.25)
    assert isinstance(moved, isogami.Design)
    assert moved.params[2] == 0.25 and abs(moved.params[3] - 0.25) < 1e-9
    assert str(moved) == cli("shape", "--design", IH2, "--set", "2=0.25", "--json")["spec"]
    assert isogami.analyze(moved).dof == 1
    assert isogami.deploy(moved).max_expansion > 0.05
    # Moving p2 alone breaks the motion.
    alone = isogami.design(IH2).with_params([0.12239750492, 0.5, 0.25, 0.225335752741])
    assert isogami.analyze(alone).dof == 0


def test_rank_drop_finds_a_moving_shape():
    assert isogami.analyze(OFF).dof == 0
    found = isogami.rank_drop_shape(OFF)
    assert found is not None and isogami.analyze(found).dof == 1
    assert isogami.rank_drop_shape("rotating-squares") is None  # no shape parameters


@pytest.mark.parametrize(
    "call, error, message",
    [
        (lambda: isogami.shape_mobility(OFF), isogami.ShapeError, "0 degrees of freedom"),
        (lambda: isogami.follow_shape(IH2, 7, 0.1), isogami.ShapeError, "parameter 7 does not exist"),
        (lambda: isogami.follow_shape(IH2, 0, float("nan")), isogami.ShapeError, "not a finite number"),
        (lambda: isogami.follow_shape("IH16:0.216506350946:1x1:-a-a-aaaa", 0, 0.22), isogami.ShapeError, "fixed by"),
        (lambda: isogami.shape_mobility(3), TypeError, "design must be"),
    ],
)
def test_errors(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_param_ranges_bound_the_shapes_that_build():
    # IH59's old slider (default ± 0.5) was ill-shaped at 16 of 21 positions: the range is
    # the part that builds, and just outside it the design is refused.
    spec = "IH59:0.030263157895:1x1:aaaa"
    (r,) = isogami.param_ranges_of(spec)
    assert r["index"] == 0 and r["lo"] <= r["value"] <= r["hi"]
    for x in [r["lo"] + (r["hi"] - r["lo"]) * k / 10 for k in range(11)]:
        isogami.design(f"IH59:{x:.12g}:1x1:aaaa")  # builds
    if not r["hi_open"]:
        with pytest.raises(isogami.IsogamiError):
            isogami.deploy(f"IH59:{r['hi'] + 10 * r['tol']:.12g}:1x1:aaaa")
    lo, hi = r["well_shaped"]
    assert r["lo"] <= lo <= r["value"] <= hi <= r["hi"]
    assert isogami.param_ranges_of(spec, kerf=5.0) is None


def test_families_describe_their_parameters():
    info = isogami.family("IH28").info()
    effects = info["param_effects"]
    assert [e["index"] for e in effects] == list(range(info["param_count"]))
    assert all(e["description"] for e in effects)

"""Every result type pickles (issue 23 item 14): ProcessPoolExecutor, joblib and dask send
results between processes with pickle. Each round trip must give an equal object whose
arrays and reports equal the original's."""

import pickle
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import isogami


def round_trip(obj):
    back = pickle.loads(pickle.dumps(obj))
    assert type(back) is type(obj)
    assert back == obj
    return back


def test_values_round_trip():
    d = isogami.design("rotating-squares")
    round_trip(d)
    f = round_trip(isogami.family("IH28"))
    assert f.name == "IH28"
    s = round_trip(isogami.DeploySettings(method="ncm", kerf=0.03, max_steps=123))
    assert (s.method, s.kerf, s.max_steps) == ("ncm", 0.03, 123)
    c = round_trip(d.unit_cell())
    assert np.array_equal(c.centroids, d.unit_cell().centroids)
    other = isogami.cell("IH28", cell=(2, 1))
    assert other != d.unit_cell()  # equality is not always true


def test_deployment_round_trip():
    run = isogami.deploy("rotating-squares", frames=7, kerf=0.02, method="ncm")
    back = round_trip(run)
    assert len(back) == 7 and back.method == "ncm" and back.kerf == 0.02
    assert np.array_equal(back.F, run.F)
    assert np.array_equal(back.tile_poses, run.tile_poses)
    assert back.to_json() == run.to_json()
    # A different run is not equal: the equality looks at the report.
    assert isogami.deploy("rotating-squares", frames=5) != run
    all_steps = isogami.deploy("rotating-squares", frames="all")
    assert len(round_trip(all_steps)) == len(all_steps)


def test_analysis_and_motions_round_trip():
    a = isogami.analyze("rotating-squares", tol=1e-8)
    back = round_trip(a)
    assert np.array_equal(back.eigenvalues, a.eigenvalues)
    m = round_trip(a.motion)
    assert np.array_equal(m.tiles, a.motion.tiles)
    for mode in a.modes:
        assert np.array_equal(round_trip(mode).u, mode.u)


def test_linkages_and_comparison_round_trip():
    link = round_trip(isogami.linkages("rotating-squares"))
    assert link.signature == isogami.linkages("rotating-squares").signature
    comp = isogami.compare("rotating-squares", max_steps=40)
    back = round_trip(comp)
    # Exact: the wall-clock times come back too (not a second run).
    assert [r.millis for r in back.results] == [r.millis for r in comp.results]
    r = round_trip(comp.result("ncm"))
    assert r.to_dict() == comp.result("ncm").to_dict()


def test_finite_results_round_trip():
    sheet = isogami.finite_sheet("rotating-squares", "3x3")
    assert np.array_equal(round_trip(sheet).tiles, sheet.tiles)
    run = isogami.deploy_sheet("rotating-squares", "3x3", frames=4)
    back = round_trip(run)
    assert np.array_equal(back.poses, run.poses)
    assert round_trip(run.sheet) == sheet
    pull = isogami.pull_sheet("rotating-squares", "3x3", frames=3)
    assert np.array_equal(round_trip(pull).poses, pull.poses)
    assert round_trip(pull.sheet) == pull.sheet


def test_database_results_round_trip(quick_db):
    with isogami.open_database(quick_db) as db:
        records = db.designs(limit=3)
        assert records
        for rec in records:
            back = round_trip(rec)
            assert back.to_dict() == rec.to_dict()
        stored = db.design(records[0].spec)
        back = round_trip(stored)
        assert back.report() == stored.report() and back.linkages() == stored.linkages()
        assert back.record == stored.record


def _area(run):
    return float(run.area_ratio.max())


def test_results_cross_process_boundaries():
    with ProcessPoolExecutor(max_workers=2) as pool:
        runs = list(pool.map(isogami.deploy, ["rotating-squares", "rotating-squares"]))
    assert all(isinstance(r, isogami.Deployment) for r in runs)
    assert runs[0] == isogami.deploy("rotating-squares")
    assert f"{_area(runs[1]):.4g}" == "2"


def test_inverse_result_round_trip(quick_db):
    got = isogami.inverse("area; tiles<=4", quick_db, top=1, budget=6, samples=0)
    back = round_trip(got)
    # Exact: the same wall time and report, not a second run.
    assert back.seconds == got.seconds and back.to_dict() == got.to_dict()
    assert back.designs == got.designs and back.objectives == got.objectives


# Issue 42 item 19: a computed result pickles as its data, so unpickling runs no computation
# (it used to run the call that made it again: 4-6 s for a SheetPull). Every computed result
# type is made here by the rule "every entry point that computes, and every part of a result
# that is itself a result (a sheet of a sheet run, the motion and modes of an analysis)".
def _computed_results():
    a = isogami.analyze("rotating-squares")
    run = isogami.deploy_sheet("rotating-squares", "3x3", frames=3)
    pull = isogami.pull_sheet("rotating-squares", "3x3", frames=3)
    return {
        "Deployment": isogami.deploy(isogami.SAMPLE_OPENING_DESIGNS[1], frames=6),
        "Deployment(all)": isogami.deploy("rotating-squares", frames="all"),
        "Analysis": a,
        "Motion": a.motion,
        "Motion(mode)": a.modes[0],
        "Linkages": isogami.linkages(isogami.SAMPLE_OPENING_DESIGNS[1]),
        "FiniteSheet": isogami.finite_sheet("rotating-squares", "3x3"),
        "FiniteSheet(raw)": isogami.finite_sheet("rotating-squares", "3x3", complete=False),
        "SheetDeployment": run,
        "SheetDeployment.sheet": run.sheet,
        "SheetPull": pull,
        "SheetPull.sheet": pull.sheet,
    }


def _arrays(obj):
    """Every public attribute of `obj` that is a numpy array, by name."""
    out = {}
    for name in dir(obj):
        if name.startswith("_"):
            continue
        value = getattr(obj, name)
        if isinstance(value, np.ndarray):
            out[name] = value
    return out


def test_unpickling_a_result_computes_nothing():
    results = _computed_results()
    assert set(type(r).__name__ for r in results.values()) >= {
        "Deployment", "Analysis", "Motion", "Linkages", "FiniteSheet", "SheetDeployment",
        "SheetPull",
    }
    before = isogami._isogami._compute_calls()
    isogami.deploy("rotating-squares", frames=3)
    assert isogami._isogami._compute_calls() > before  # the counter sees a computation
    for label, obj in results.items():
        data = pickle.dumps(obj)
        before = isogami._isogami._compute_calls()
        back = pickle.loads(data)
        assert isogami._isogami._compute_calls() == before, f"{label} computed on unpickling"
        assert type(back) is type(obj) and back == obj, label
        arrays = _arrays(obj)
        got = _arrays(back)
        assert got.keys() == arrays.keys(), label
        for name, value in arrays.items():
            assert got[name].dtype == value.dtype, (label, name)
            assert np.array_equal(got[name], value, equal_nan=True), (label, name)
        assert repr(back) == repr(obj), label
        # And a second trip gives the same bytes: nothing is lost on the way.
        assert pickle.dumps(back) == data, label


def test_unpickled_deployment_still_draws():
    run = isogami.deploy("rotating-squares", frames=4)
    back = pickle.loads(pickle.dumps(run))
    assert back.frame_svgs(width=100) == run.frame_svgs(width=100)
    assert back._repr_svg_() == run._repr_svg_()


def test_a_pickle_of_another_state_layout_is_refused():
    for label, obj in _computed_results().items():
        restore, args = obj.__reduce__()
        cls, tag, data, arrays = args
        assert isinstance(data, bytes) and all(isinstance(a, bytes) for a in arrays), label
        assert restore(*args) == obj, label
        with pytest.raises(pickle.UnpicklingError, match="state layout"):
            restore(cls, tag + "-other", data, arrays)
        with pytest.raises(pickle.UnpicklingError, match=cls):
            restore(cls, tag, data[: len(data) // 2], arrays)

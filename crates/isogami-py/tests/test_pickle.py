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

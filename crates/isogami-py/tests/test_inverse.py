"""Inverse design from Python: the same run as `isogami inverse` (JSON equal but for the wall
time), targets as text, JSON or dict, constraints met, every refined design valid when
re-deployed here, saving into the database, progress, stopping and one-line errors."""

import json
import math
import shutil

import pytest

import isogami

SMALL = dict(top=2, budget=6, confirm=6, triage=4)


def without_time(d):
    d = dict(d)
    d.pop("seconds")
    return d


def cli_inverse(cli, db, target, *flags):
    return cli("inverse", "--db", str(db), "--target", target, "--json", *flags)


def test_a_run_equals_the_cli(cli, quick_db):
    got = isogami.inverse("area; tiles<=4", quick_db, **SMALL)
    assert isinstance(got, isogami.InverseResult)
    want = cli_inverse(
        cli, quick_db, "area; tiles<=4", "--top", "2", "--budget", "6", "--confirm", "6", "--triage", "4"
    )
    assert without_time(got.to_dict()) == without_time(want)
    assert got.target == want["target"] and len(got) == len(want["results"]) == 2
    assert [str(d) for d in got.designs] == [r["after"]["spec"] for r in want["results"]]
    assert got.objectives == [r["after"]["objective"] for r in want["results"]]
    assert str(got.best) == want["results"][0]["after"]["spec"]
    assert got.seconds > 0 and "InverseResult" in repr(got)


def test_the_target_may_be_text_json_or_a_dict(quick_db):
    as_dict = {"terms": [{"goal": {"kind": "area"}, "weight": 1.0}], "constraints": {"max_tiles": 4}}
    a = isogami.inverse("area; tiles<=4", quick_db, **SMALL).to_dict()
    b = isogami.inverse(as_dict, quick_db, **SMALL).to_dict()
    c = isogami.inverse(json.dumps(as_dict), quick_db, **SMALL).to_dict()
    assert without_time(a) == without_time(b) == without_time(c)


def test_an_open_database_serves_as_well_as_a_path(quick_db):
    with isogami.open_database(quick_db) as db:
        a = isogami.inverse("isotropic", db, **SMALL)
    b = isogami.inverse("isotropic", str(quick_db), **SMALL)
    assert without_time(a.to_dict()) == without_time(b.to_dict())


def test_constraints_hold_and_refined_designs_redeploy_to_their_measures(quick_db):
    result = isogami.inverse("expansion(0); families=IH28,IH27; tiles<=4", quick_db, **SMALL)
    assert len(result) >= 1
    for r, design in zip(result.to_dict()["results"], result.designs):
        assert design.family in ("IH28", "IH27") and design.unit_cell().tile_count <= 4
        assert r["after"]["objective"] <= r["before"]["objective"]
        # Re-deployed by the deployment binding at the kerf it was scored with: the largest
        # expansion along x over the motion, dᵀ(U − I)d for d = x, is the negated objective.
        # Designs are scored on the catalogue's frames (the database's frame_count), as the
        # stored reports are; every step's values can only reach further.
        frames = isogami.open_database(quick_db).settings["frame_count"]
        run = isogami.deploy(design, kerf=r["after"]["kerf"], frames=frames)
        assert run.dof == 1 and run.end_reason == r["after"]["measures"]["end_reason"]
        along_x = float((run.U[:, 0, 0] - 1.0).max())
        assert math.isclose(along_x, -r["after"]["objective"], rel_tol=1e-9, abs_tol=1e-12)
        assert math.isclose(run.max_area_ratio, r["after"]["measures"]["max_area_ratio"], rel_tol=1e-9)
        every = isogami.deploy(design, kerf=r["after"]["kerf"], frames="all")
        assert float((every.U[:, 0, 0] - 1.0).max()) >= along_x - 1e-12
        assert every.max_area_ratio >= run.max_area_ratio - 1e-12


def test_save_stores_the_refined_designs_once(quick_db, tmp_path):
    db = tmp_path / "copy.db"
    shutil.copyfile(quick_db, db)
    first = isogami.inverse("area; tiles<=4", db, save=True, **SMALL).to_dict()
    assert [s["saved"] for s in first["saved"]] == [True] * len(first["results"])
    with isogami.open_database(db) as opened:
        for s in first["saved"]:
            stored = opened.design(s["spec"])
            assert stored is not None and stored.record.origin == "user"
    # The saved designs are candidates now; any of them found again is not saved twice.
    again = isogami.inverse("area; tiles<=4", db, save=True, **SMALL).to_dict()
    before_specs = {s["spec"] for s in first["saved"]}
    repeated = [s for s in again["saved"] if s["spec"] in before_specs]
    assert repeated and all(not s["saved"] and s["note"] == "already in the database" for s in repeated)
    # Without save the database is not written.
    before = db.read_bytes()
    isogami.inverse("area; tiles<=4", db, **SMALL)
    assert db.read_bytes() == before


def test_progress_reports_every_stage_and_can_stop(quick_db):
    seen = []
    isogami.inverse("area", quick_db, progress=seen.append, **SMALL)
    stages = [p["stage"] for p in seen]
    assert {"confirm", "triage", "refine", "verify"} <= set(stages)
    wrong = [p for p in seen if not (0 <= p["done"] and (p["stage"] == "refine" or p["done"] <= p["total"]))]
    assert wrong == []
    last = seen[-1]["leaders"]
    assert last and all(a["objective"] <= b["objective"] for a, b in zip(last, last[1:]))
    assert last[0]["objective"] == seen[-1]["best"]
    bests = [p["best"] for p in seen if p["best"] is not None]
    assert bests and all(b <= a + 1e-15 for a, b in zip(bests, bests[1:]))  # best only improves

    calls = []
    with pytest.raises(isogami.CancelledError, match="progress callback returned False"):
        isogami.inverse("area", quick_db, progress=lambda p: calls.append(p) or len(calls) < 5, **SMALL)
    assert len(calls) == 5

    class Boom(Exception):
        pass

    def explode(p):
        raise Boom("from the callback")

    with pytest.raises(Boom):
        isogami.inverse("area", quick_db, progress=explode, **SMALL)
    with pytest.raises(isogami.CancelledError, match="timeout"):
        isogami.inverse("area", quick_db, timeout=1e-6, **SMALL)


@pytest.mark.parametrize(
    "target, kwargs, error, message",
    [
        ("bigness", {}, isogami.InverseError, "unknown goal 'bigness'"),
        ("lock(0.1)", {}, isogami.InverseError, "lock takes"),
        ("{not json", {}, isogami.InverseError, "target JSON"),
        ("area; families=IH999", {}, isogami.IsogamiError, "IH999"),
        ("area", {"top": 0}, isogami.InverseError, "top 0"),
        ("area", {"confirm": 0}, isogami.InverseError, "confirm must be at least 1"),
        ("area", {"kerf": float("nan")}, isogami.InverseError, "kerf"),
        ("area", {"budget": 10**7}, isogami.InverseError, "budget"),
        ("area; families=IH1", {}, isogami.InverseError, "families=IH1 removes"),
        ("isotropic; tiles>=40", {}, isogami.InverseError, "tiles>=40 removes"),
        (42, {}, TypeError, "target must be a str"),
        ("area", {"progress": 3}, TypeError, "progress must be callable"),
    ],
)
def test_bad_requests_are_one_line_errors(quick_db, target, kwargs, error, message):
    with pytest.raises(error, match=message.replace("(", r"\(").replace(")", r"\)")) as caught:
        isogami.inverse(target, quick_db, **{**SMALL, **kwargs})
    assert "\n" not in str(caught.value)


def test_the_verdict_says_whether_the_target_is_met(quick_db):
    missed = isogami.inverse("lock(6.07,6.07)", quick_db, **SMALL)
    assert missed.met is False
    assert missed.verdict.startswith("target NOT met: lock(6.07,6.07) is ")
    goal = missed.to_dict()["results"][0]["verdict"]["goals"][0]
    assert goal["met"] is False and goal["value"] > 5 and goal["tolerance"] == 0.01
    assert missed.verdict == missed.to_dict()["results"][0]["verdict"]["summary"]
    most = isogami.inverse("area", quick_db, **SMALL)
    assert most.met is None and most.verdict.startswith("no value to meet")


def test_bad_databases_are_refused(tmp_path):
    with pytest.raises(isogami.StoreError, match="missing.db"):
        isogami.inverse("area", tmp_path / "missing.db")
    with pytest.raises(TypeError, match="database must be"):
        isogami.inverse("area", 3.5)

"""Design databases: opened read-only and queried with the browser's filters (the store's
own query types); results checked against filtering every record in Python, and the stored
reports against fresh deployments and the CLI."""

import math
import pickle
import shutil
from pathlib import Path

import pytest

import isogami
from conftest import assert_same


@pytest.fixture(scope="module")
def db(quick_db):
    with isogami.open_database(quick_db) as d:
        yield d


@pytest.fixture(scope="module")
def every(db):
    return db.designs()


def test_every_design_and_the_stats_equal_the_cli(cli, quick_db, db, every):
    stats = db.stats()
    want = cli("db", "stats", "--db", str(quick_db), "--json")
    assert_same(stats, want)
    assert len(every) == len(db) == stats["designs"] == db.count() > 10
    assert all(isinstance(r, isogami.Record) for r in every)
    assert [r.spec for r in every] == sorted(r.spec for r in every)  # default order: spec
    assert len({r.spec for r in every}) == len(every)
    assert db.tool_version == stats["tool_version"]
    assert db.settings["frame_count"] > 1 and Path(db.path) == Path(quick_db)


def test_facet_selection_equals_filtering_every_record(db, every):
    for behaviour in ["isotropic_auxetic", "anisotropic_auxetic", "orthotropic_positive_poisson"]:
        got = db.designs(behaviour=behaviour)
        assert [r.spec for r in got] == [r.spec for r in every if r.behaviour == behaviour]
    fams = sorted({r.family for r in every})[:2]
    got = db.designs(family=fams)
    assert [r.spec for r in got] == [r.spec for r in every if r.family in fams]
    tiles = every[0].tile_count
    assert [r.spec for r in db.designs(tiles=tiles)] == [r.spec for r in every if r.tile_count == tiles]
    cell = every[0].cell
    for form in (cell, f"{cell[0]}x{cell[1]}", [cell]):
        assert [r.spec for r in db.designs(cell=form)] == [r.spec for r in every if r.cell == cell]
    sig = every[0].linkage_signature
    assert [r.spec for r in db.designs(linkage=sig)] == [r.spec for r in every if r.linkage_signature == sig]
    assert [r.spec for r in db.designs(end="contact_limit")] == [r.spec for r in every if r.end_reason == "contact_limit"]
    explored, user = db.designs(origin="explored"), db.designs(origin="user")
    assert [r.spec for r in explored] == [r.spec for r in every if r.origin == "explored"]
    assert [r.spec for r in user] == [r.spec for r in every if r.origin == "user"]
    assert len(explored) + len(user) == len(every) and explored
    # Several facets hold together.
    both = db.designs(family=fams, behaviour="isotropic_auxetic")
    assert [r.spec for r in both] == [r.spec for r in every if r.family in fams and r.behaviour == "isotropic_auxetic"]


def test_ranges_sort_and_pages(db, every):
    lo = sorted(r.max_area_ratio for r in every)[len(every) // 2]
    got = db.designs(range={"max_area_ratio": (lo, None)}, sort="-max_area_ratio")
    want = sorted((r for r in every if r.max_area_ratio >= lo), key=lambda r: -r.max_area_ratio)
    assert [r.max_area_ratio for r in got] == [r.max_area_ratio for r in want]
    for form in (["max_area_ratio:1.2:1.6"], [("max_area_ratio", 1.2, 1.6)], "max_area_ratio:1.2:1.6"):
        got = db.designs(range=form)
        assert [r.spec for r in got] == [r.spec for r in every if 1.2 <= r.max_area_ratio <= 1.6]
    # Designs without the measure never pass a range on it.
    got = db.designs(range={"poisson_min": (None, 0.0)})
    assert [r.spec for r in got] == [r.spec for r in every if r.poisson_min is not None and r.poisson_min <= 0]
    page = db.designs(sort="steps", limit=5, offset=3)
    ordered = sorted(every, key=lambda r: r.steps)
    assert [r.steps for r in page] == [r.steps for r in ordered[3:8]]
    assert len(db.designs(limit=1)) == 1
    assert db.count(behaviour="isotropic_auxetic") == sum(r.behaviour == "isotropic_auxetic" for r in every)


def test_query_objects_and_where(db, every):
    q = isogami.Query(behaviour="isotropic_auxetic", sort="-max_area_ratio")
    best = db.designs(q, limit=3)
    iso = sorted((r for r in every if r.behaviour == "isotropic_auxetic"), key=lambda r: -r.max_area_ratio)
    # Ties keep insertion order, so compare the sorted values.
    assert [r.max_area_ratio for r in best] == [r.max_area_ratio for r in iso[:3]]
    assert all(r.behaviour == "isotropic_auxetic" for r in best)
    narrower = q.where(range={"max_area_ratio": (1.5, None)})
    assert all(r.max_area_ratio >= 1.5 for r in db.designs(narrower))
    assert q.to_dict()["behaviours"] == ["isotropic_auxetic"] and q.to_dict()["limit"] is None
    assert "isotropic_auxetic" in repr(q)


def test_facet_counts_and_scatter(db, every):
    counts = dict(db.facet_counts("behaviour"))
    for k, n in counts.items():
        assert n == sum(r.behaviour == k for r in every)
    assert sum(counts.values()) == len(every)
    # Disjunctive: a facet's own selection does not narrow its counts.
    assert dict(db.facet_counts("behaviour", behaviour="isotropic_auxetic")) == counts
    fam = dict(db.facet_counts("family", behaviour="isotropic_auxetic"))
    assert sum(fam.values()) == counts["isotropic_auxetic"]
    cells = db.facet_counts("cell")
    assert all(isinstance(v, list) and len(v) == 2 for v, _ in cells)
    s = db.scatter("max_expansion", "min_expansion", behaviour="anisotropic_auxetic")
    chosen = [r for r in every if r.behaviour == "anisotropic_auxetic"]
    assert sorted(s["spec"]) == sorted(r.spec for r in chosen)
    by_spec = {r.spec: r for r in chosen}
    for spec, x, y in zip(s["spec"], s["x"], s["y"]):
        assert (x, y) == (by_spec[spec].max_expansion, by_spec[spec].min_expansion)
    assert len(db.scatter("v0", "kerf", limit=2)["x"]) <= 2


def test_stored_design_reads_back_and_redeploys(db, every):
    best = max((r for r in every if r.behaviour == "isotropic_auxetic"), key=lambda r: r.max_area_ratio)
    stored = db.design(best.spec)
    assert isinstance(stored, isogami.StoredDesign) and best.spec in repr(stored)
    assert stored.record.spec == best.spec and stored.record.to_dict() == best.to_dict()
    report = stored.report()
    assert report["design"] == best.spec and report["max_area_ratio"] == best.max_area_ratio
    links = stored.linkages()
    assert links["signature"] == best.linkage_signature
    # The exploration deploys with default settings and its frame count.
    fresh = isogami.deploy(best.design(), frames=db.settings["frame_count"])
    assert_same(fresh.report(), report)
    assert db.design(best.design()).record.spec == best.spec
    assert db.design("IH90::1x1:---") is None


def test_records(every):
    r = every[0]
    d = r.to_dict()
    assert d["spec"] == r.spec and d["cell"] == list(r.cell) and d["family"] == r.family
    assert d["behaviour"] == r.behaviour and d["params"] == r.params
    assert r.design().spec == r.spec and r.origin in ("explored", "user")
    assert r.spec in repr(r)
    for x in every:
        assert math.isfinite(x.max_area_ratio) and x.steps >= 2 and x.dof >= 1
        if x.origin == "explored":
            assert x.dof == 1 and x.method == "rigid-modes"


def test_dataframe(db, every):
    pd = pytest.importorskip("pandas")
    df = db.dataframe(behaviour="isotropic_auxetic", sort="-max_area_ratio")
    iso = [r for r in every if r.behaviour == "isotropic_auxetic"]
    assert isinstance(df, pd.DataFrame) and len(df) == len(iso)
    assert list(df.columns)[:4] == ["spec", "origin", "family", "cell"]
    assert df["max_area_ratio"].is_monotonic_decreasing
    assert set(df["spec"]) == {r.spec for r in iso}
    assert all("x" in c for c in df["cell"])
    assert len(db.dataframe(limit=2)) == 2


@pytest.mark.parametrize(
    "filters,error,needle",
    [
        (dict(family="IH999"), isogami.QueryError, "family"),
        (dict(behaviour="wobbly"), isogami.QueryError, "behaviour"),
        (dict(cell="9x9"), isogami.QueryError, "cell"),
        (dict(origin="alien"), isogami.QueryError, "origin"),
        (dict(range={"max_area_ratio": (float("nan"), None)}), isogami.QueryError, "not a finite number"),
        (dict(range={"max_area_ratio": (2.0, 1.0)}), isogami.QueryError, "empty range"),
        (dict(range={"nope": (1, 2)}), isogami.QueryError, "unknown measure"),
        (dict(range="max_area_ratio:1"), isogami.QueryError, "measure:min:max"),
        (dict(range=["max_area_ratio:x:"]), isogami.QueryError, "not a number"),
        (dict(range={"v9": (0, 1)}), isogami.QueryError, "v9"),
        (dict(sort="-colour"), isogami.QueryError, "sort"),
        (dict(limit=0), isogami.QueryError, "limit"),
        (dict(offset=-1), isogami.QueryError, "offset"),
        (dict(colour="red"), TypeError, "unknown filter 'colour'"),
        (dict(family=2.5), TypeError, "family"),
        (dict(sort=3), TypeError, "sort"),
        (dict(limit="many"), TypeError, "limit"),
        (dict(range={"max_area_ratio": 1.5}), TypeError, "pair"),
    ],
)
def test_bad_filters(db, filters, error, needle):
    with pytest.raises(error, match=needle):
        db.designs(**filters)
    assert issubclass(isogami.QueryError, isogami.StoreError)


def test_bad_calls(db):
    with pytest.raises(isogami.QueryError, match="unknown facet"):
        db.facet_counts("colour")
    with pytest.raises(isogami.QueryError):
        db.scatter("max_expansion", "nope")
    with pytest.raises(TypeError):
        db.designs(query="family=IH2")
    with pytest.raises(TypeError):
        db.design(42)


def test_opening_refuses_what_is_not_a_database(tmp_path, quick_db):
    with pytest.raises(isogami.StoreError, match="no such database"):
        isogami.open_database(tmp_path / "missing.db")
    text = tmp_path / "notes.db"
    text.write_text("not a database at all, just some words\n" * 40)
    with pytest.raises(isogami.StoreError, match="not an isogami database"):
        isogami.open_database(text)
    (tmp_path / "empty.db").write_bytes(b"")
    with pytest.raises(isogami.StoreError, match="empty file"):
        isogami.Database(tmp_path / "empty.db")
    with pytest.raises(ValueError, match="quick"):
        isogami.open_database(quick_db, check="thorough")
    with pytest.raises(TypeError):
        isogami.open_database(3.5)
    # Reading never writes: the file is unchanged after a full check and queries.
    copy = tmp_path / "copy.db"
    shutil.copy(quick_db, copy)
    before = copy.read_bytes()
    d = isogami.open_database(copy, check="full")
    d.designs(sort="-max_area_ratio")
    d.close()
    assert copy.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["copy.db", "empty.db", "notes.db"]
    with pytest.raises(ValueError, match="closed"):
        d.designs()


def test_finite_sheet_columns_filter_and_sort_like_the_records(db, every):
    explored = [r for r in every if r.origin == "explored"]
    assert explored and all(r.finite_raw_dof is not None and r.finite_raw_dof >= 1 for r in explored)
    assert all(r.finite_covered is None or 0.5 <= r.finite_covered <= 1.0 for r in every)
    assert all(r.to_dict()["finite_covered"] == r.finite_covered for r in every)
    got = db.designs(range={"finite_raw_dof": (1, 1)})
    assert [r.spec for r in got] == [r.spec for r in every if r.finite_raw_dof == 1]
    got = db.designs(range="finite_covered:0.9:", sort="-finite_covered")
    want = sorted(
        (r for r in every if r.finite_covered is not None and r.finite_covered >= 0.9),
        key=lambda r: -r.finite_covered,
    )
    assert [r.finite_covered for r in got] == [r.finite_covered for r in want]
    # Missing values sort last either way.
    ordered = db.designs(sort="finite_covered")
    missing = [r.finite_covered is None for r in ordered]
    assert missing == sorted(missing)


def test_margins_and_buildable_first(db, every):
    explored = [r for r in every if r.origin == "explored"]
    assert explored and all(r.open_t is not None and 0.0 <= r.open_t <= 1.0 for r in explored)
    assert all(r.end_area_ratio <= r.max_area_ratio * (1 + 1e-12) for r in explored)
    fab = 0.0025  # isogami::catalog::FABRICATION_TOLERANCE
    for r in every:
        rule = (
            r.finite_covered is not None
            and r.open_t is not None
            and (r.shape_tolerance is None or r.shape_tolerance >= fab)
        )
        assert r.buildable == rule, r.spec
    assert 0 < sum(r.buildable for r in every) < len(every)
    got = db.designs(sort="-max_area_ratio", lead="buildable")
    flags = [r.buildable for r in got]
    assert flags == sorted(flags, reverse=True), "buildable designs first"
    for part in (True, False):
        areas = [r.max_area_ratio for r in got if r.buildable == part]
        assert areas == sorted(areas, reverse=True)
    plain = db.designs(sort="-max_area_ratio", lead="all")
    assert [r.spec for r in plain] == [r.spec for r in db.designs(sort="-max_area_ratio")]
    special = db.designs(range="shape_tolerance:0:0")
    assert [r.spec for r in special] == sorted(r.spec for r in every if r.shape_tolerance == 0)
    with pytest.raises(isogami.QueryError, match="lead"):
        db.designs(lead="first")


def test_cell_twins_are_stored_once_and_found_by_every_spec(cli_raw, tmp_path):
    """The same design found on a 1×2 and a 2×1 cell is one record that lists its other cell;
    its other spec finds it. Families by a rule: every family whose 1×2 and 2×1 cells both
    have at most 8 unique edges."""
    def edges(f, cell):
        try:
            return isogami.cell(f, None, cell).edge_count
        except isogami.CellError:
            return None

    chosen = [f.name for f in isogami.families()
              if all((edges(f, c) or 99) <= 8 for c in ("1x2", "2x1"))]
    assert len(chosen) >= 3, chosen
    path = tmp_path / "twins.db"
    done = cli_raw("explore", "--families", ",".join(chosen), "--cells", "1x2,2x1",
                   "--max-edges", "8", "--samples", "4", "--db", str(path))
    assert done.returncode == 0, done.stderr
    with isogami.open_database(path, check="full") as db:
        twins = db.stats()["cell_twins"]
        assert twins > 0
        records = db.designs(limit=1000)
        assert len(records) == db.count()
        with_twins = [db.design(r.spec) for r in records]
        with_twins = [s for s in with_twins if s.other_cells]
        assert sum(len(s.other_cells) for s in with_twins) == twins
        stored = {r.spec for r in records}
        for s in with_twins:
            for other in s.other_cells:
                assert other not in stored
                found = db.design(other)
                assert found.record.spec == s.record.spec and other in found.other_cells
                assert other.split(":")[:2] == s.record.spec.split(":")[:2]
                assert other.split(":")[2] != s.record.spec.split(":")[2]
            assert pickle.loads(pickle.dumps(s)).other_cells == s.other_cells

"""numpy and pandas inputs are accepted wherever a plain value is (issue 23 item 15), and
negative or huge integers give one clear message naming the argument with the value as
given, never a wrapped one or a bare OverflowError (item 16)."""

import numpy as np
import pytest

import isogami


def test_numpy_integers_name_families_and_cells():
    assert isogami.family(np.int64(28)).name == "IH28"
    assert isogami.family(np.int32(1)).name == "IH1"
    assert isogami.cell("IH28", cell=(np.int64(2), np.int64(1))).cell == (2, 1)
    with pytest.raises(TypeError, match="family"):
        isogami.family(28.0)
    with pytest.raises(TypeError):
        isogami.family(True)


def test_export_patch_from_numpy(tmp_path):
    a = isogami.export("rotating-squares", "svg", patch=np.array([2, 3]), complete=False)
    b = isogami.export("rotating-squares", "svg", patch=(2, 3), complete=False)
    assert a == b
    c = isogami.export("rotating-squares", "svg", patch=[np.int64(2), np.int64(3)], complete=False)
    assert c == b
    with pytest.raises(TypeError, match="patch"):
        isogami.export("rotating-squares", "svg", patch=np.array([2.5, 3.0]), complete=False)


def test_database_filters_take_collections(quick_db):
    pd = pytest.importorskip("pandas")
    with isogami.open_database(quick_db) as db:
        df = db.dataframe()
        fams = sorted(df.family.unique())[:2]
        want = sorted(r.spec for f in fams for r in db.designs(family=f))
        assert want
        for given in (df.family[df.family.isin(fams)].unique(), pd.Series(fams), set(fams),
                      np.array(fams), tuple(fams), fams):
            got = sorted(r.spec for r in db.designs(family=given))
            assert got == want, type(given)
        assert db.count(family=set(fams)) == len(want)


def test_records_deploy(quick_db):
    with isogami.open_database(quick_db) as db:
        rec = [r for r in db.designs() if r.dof >= 1][0]
        stored = db.design(rec.spec)
    run = isogami.deploy(rec, frames=3)
    assert run.design == rec.spec
    assert isogami.deploy(stored, frames=3).design == rec.spec
    assert isogami.analyze(rec).design == rec.spec


def test_measures_take_stacks_of_matrices():
    run = isogami.deploy("rotating-squares", frames=9)
    F = run.F
    ratios = isogami.area_ratio(F)
    assert ratios.shape == (9,)
    assert np.allclose(ratios, [isogami.area_ratio(f) for f in F])
    assert np.allclose(ratios, run.area_ratio)
    assert isinstance(isogami.area_ratio(F[3]), float)
    R, U = isogami.polar(F)
    assert R.shape == U.shape == (9, 2, 2)
    for k in range(9):
        r, u = isogami.polar(F[k])
        assert np.allclose(R[k], r) and np.allclose(U[k], u)
    e = isogami.principal_expansions(U)
    assert e.shape == (9, 2)
    assert np.allclose(e[4], isogami.principal_expansions(U[4]))
    assert isogami.principal_direction(U).shape == (9,)
    d = isogami.directional_expansion(U.reshape(3, 3, 2, 2), 0.3)
    assert d.shape == (3, 3)
    assert np.isclose(d[1, 1], isogami.directional_expansion(U[4], 0.3))
    with pytest.raises(ValueError, match="F must be a 2x2 matrix"):
        isogami.area_ratio(np.zeros((3, 3)))


@pytest.mark.parametrize("bad", [-1, 2**70])
def test_counts_name_the_argument(bad, quick_db):
    with pytest.raises(ValueError, match=rf"budget must be a non-negative int.*got {bad}\b"):
        isogami.inverse("isotropic_auxetic", quick_db, budget=bad)
    with pytest.raises(ValueError, match=rf"top .*got {bad}\b"):
        isogami.inverse("isotropic_auxetic", quick_db, top=bad)


def test_negative_and_huge_ints_are_shown_as_given():
    with pytest.raises(isogami.CellError, match=r"bad cell '-1x1'"):
        isogami.cell("IH28", cell=(-1, 1))
    with pytest.raises(isogami.CellError, match=r"bad cell '300x1'"):
        isogami.cell("IH28", cell=(300, 1))
    with pytest.raises(isogami.TilingError, match=r"'-1'"):
        isogami.family(-1)
    with pytest.raises(isogami.TilingError, match=str(2**64)):
        isogami.family(2**64)
    with pytest.raises(isogami.ExportError, match=r"patch \(-1, 2\)"):
        isogami.export("rotating-squares", "svg", patch=(-1, 2), complete=False)
    with pytest.raises(isogami.SettingsError, match=r"frame count -5"):
        isogami.deploy("rotating-squares", frames=-5)
    with pytest.raises(isogami.SettingsError, match=str(2**65)):
        isogami.deploy("rotating-squares", frames=2**65)


@pytest.mark.parametrize("bad", [-1, 2**64])
def test_other_counts_name_the_argument(bad):
    cases = [
        ("frames", lambda: isogami.deploy_sheet("rotating-squares", "3x3", frames=bad)),
        ("frames", lambda: isogami.pull_sheet("rotating-squares", "3x3", frames=bad)),
        ("frames", lambda: isogami.export("rotating-squares", "obj", frames=bad)),
        ("index", lambda: isogami.follow_shape("IH28", bad, 0.3)),
        ("samples", lambda: isogami.expansion_profile([[1, 0], [0, 1]], samples=bad)),
        ("samples", lambda: isogami.deploy("rotating-squares", frames=3).profile(samples=bad)),
    ]
    for name, call in cases:
        with pytest.raises(ValueError, match=rf"^{name} must be a non-negative int.*got {bad}$"):
            call()
    # The defaults still apply when the argument is left out.
    assert isogami.expansion_profile([[1, 0], [0, 1]]).shape == (180, 2)

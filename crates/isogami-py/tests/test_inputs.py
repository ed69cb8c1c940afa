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


# Issue 42 item 21: every numpy form of every pair argument is accepted (cell=np.array([2, 1])
# was refused, and graded's region). The pair arguments are found by a rule: every parameter
# of a public function or method whose name is one of PAIR_NAMES (the vocabulary the
# docstrings use for a pair or a short vector); the test fails when a public signature gains
# one the table below does not exercise. Each is called with every form FORMS makes of its
# plain tuple, and must give what the plain tuple gives.
PAIR_NAMES = {"cell", "patch", "region", "grips", "params", "u0", "w0", "u", "w"}


def _public_callables():
    for name in isogami.__all__:
        obj = getattr(isogami, name)
        if not callable(obj):
            continue
        yield name, obj
        if isinstance(obj, type):
            for m in dir(obj):
                if not m.startswith("_") and callable(getattr(obj, m)):
                    yield f"{name}.{m}", getattr(obj, m)


def _pair_parameters():
    import inspect

    found = set()
    for label, obj in _public_callables():
        try:
            params = inspect.signature(obj).parameters
        except (TypeError, ValueError):
            continue
        found |= {(label, p) for p in params if p in PAIR_NAMES}
    return found


def FORMS(plain):
    """Every form of a plain tuple of numbers a caller may hold."""
    ints = all(isinstance(v, int) for v in plain)
    dtypes = [np.int64, np.int32, np.uint8] if ints else [np.float64, np.float32]
    forms = [tuple(plain), list(plain)]
    for dt in dtypes:
        forms.append(np.array(plain, dtype=dt))
        forms.append(tuple(dt(v) for v in plain))
        forms.append([np.array(v, dtype=dt) for v in plain])  # 0-d arrays
    return forms


_PULL_GRIPS = (4, 31)
_IH28 = tuple(isogami.family("IH28").default_params)
# (label of the public callable, argument, plain value, call with the value)
CASES = [
    ("cell", "cell", (2, 1), lambda v: isogami.cell("IH28", cell=v)),
    ("cell", "params", _IH28, lambda v: isogami.cell("IH28", params=v)),
    ("Design", "cell", (2, 2), lambda v: isogami.Design(family="IH76", cell=v, joints="bbbbaaaa")),
    ("Design", "params", _IH28, lambda v: isogami.Design("IH28", v, (1, 1), "a" * 10)),
    ("Design.with_params", "params", _IH28,
     lambda v: isogami.Design("IH28", None, (1, 1), "a" * 10).with_params(v)),
    ("Family.check_params", "params", _IH28, lambda v: isogami.family("IH28").check_params(v)),
    ("Family.prototile", "params", _IH28, lambda v: isogami.family("IH28").prototile(v)),
    ("graded", "region", (2, 2),
     lambda v: isogami.graded("rotating-squares", v, iterations=1, states=2)),
    ("export", "patch", (2, 3),
     lambda v: isogami.export("rotating-squares", "svg", patch=v, complete=False)),
    ("pull_sheet", "grips", _PULL_GRIPS,
     lambda v: isogami.pull_sheet("rotating-squares", "3x3", grips=v, frames=2)),
    ("deformation_gradient", "u0", (1.0, 0.0),
     lambda v: isogami.deformation_gradient(v, (0.0, 1.0), (1.0, 0.0), (0.5, 1.0))),
    ("deformation_gradient", "w0", (0.0, 1.0),
     lambda v: isogami.deformation_gradient((1.0, 0.0), v, (1.0, 0.0), (0.5, 1.0))),
    ("deformation_gradient", "u", (1.0, 0.0),
     lambda v: isogami.deformation_gradient((1.0, 0.0), (0.0, 1.0), v, (0.5, 1.0))),
    ("deformation_gradient", "w", (0.5, 1.0),
     lambda v: isogami.deformation_gradient((1.0, 0.0), (0.0, 1.0), (1.0, 0.0), v)),
]
# Parameters named like a pair that take something else (a str region of cells in mm; a
# matrix stack U, tested in test_measures_take_stacks_of_matrices).
NOT_PAIRS = {
    ("finite_sheet", "region"), ("deploy_sheet", "region"), ("pull_sheet", "region"),
    ("export", "region"),
    ("directional_expansion", "u"), ("expansion_profile", "u"), ("principal_direction", "u"),
    ("principal_expansions", "u"), ("Family.sample_params", "params"),
    ("Family.param_ranges", "params"),
}


def test_every_pair_parameter_is_exercised():
    covered = {(label, arg) for label, arg, _, _ in CASES} | NOT_PAIRS
    missing = _pair_parameters() - covered
    assert not missing, f"pair parameters without a numpy-form case: {sorted(missing)}"


def _same(a, b):
    if isinstance(a, np.ndarray):
        return np.array_equal(a, b)
    if isinstance(a, isogami.GradedRun):  # its JSON holds wall times: same outcome
        return repr(a) == repr(b)
    return a == b


@pytest.mark.parametrize("case", CASES, ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_every_numpy_form_of_a_pair_is_accepted(case):
    _, _, plain, call = case
    for form in FORMS(plain):
        # The plain tuple of the same values (float32 forms round the values).
        same_values = tuple(np.asarray(form).tolist())
        assert _same(call(form), call(same_values)), (type(form), form)


def test_a_query_pickles_for_pool_workers():
    import pickle

    q = isogami.Query(family=["IH28"], cell=(np.int64(2), np.int64(1)), limit=np.int64(5))
    back = pickle.loads(pickle.dumps(q))
    assert back == q and back.to_dict() == q.to_dict()
    assert isogami.Query(family=["IH1"]) != q

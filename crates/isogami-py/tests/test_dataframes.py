"""DataFrames for science (issue 23 item 18): a deployment as one row per frame, and a
database's shape parameters as one named float column each."""

import math

import numpy as np
import pytest

import isogami

pd = pytest.importorskip("pandas")


def test_deployment_dataframe_has_one_row_per_frame():
    run = isogami.deploy("rotating-squares", frames=8)
    df = run.dataframe()
    assert len(df) == len(run) == 8
    assert df.index.name == "frame" and list(df.index) == list(range(8))
    assert np.array_equal(df["t"].to_numpy(), run.t)
    assert np.array_equal(df["area_ratio"].to_numpy(), run.area_ratio)
    assert np.array_equal(df["min_expansion"].to_numpy(), run.principal_expansions[:, 0])
    assert np.array_equal(df["max_expansion"].to_numpy(), run.principal_expansions[:, 1])
    assert np.array_equal(df["clearance"].to_numpy(), run.clearance)
    assert df["area_ratio"].idxmax() == int(np.argmax(run.area_ratio))


def test_database_dataframe_has_named_parameter_columns(quick_db):
    with isogami.open_database(quick_db) as db:
        df = db.dataframe()
        records = db.designs()
    width = max(len(r.params) for r in records)
    assert width >= 1
    names = [f"param_{k}" for k in range(width)]
    assert list(df.columns[-width:]) == names
    by_spec = {r.spec: r for r in records}
    for _, row in df.iterrows():
        params = by_spec[row["spec"]].params
        for k, name in enumerate(names):
            if k < len(params):
                assert row[name] == params[k]
            else:
                assert math.isnan(row[name])

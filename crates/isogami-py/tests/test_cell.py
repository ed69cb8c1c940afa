"""Cells: the closed unit cell of a tiling, equal to `isogami cell --json`."""

import numpy as np
import pytest

import isogami
from conftest import assert_same

CASES = [("IH28", None, "1x1"), ("IH28", "0.2,0.6", "2x1"), ("IH76", None, "2x2"), ("IH90", None, "1x2"), ("IH6", None, "1x1")]


@pytest.mark.parametrize("family,params,cell", CASES)
def test_cell_equals_the_cli(cli, family, params, cell):
    args = ["cell", "--family", family, "--cell", cell, "--json"]
    if params:
        args += ["--params", params]
    want = cli(*args)
    p = [float(v) for v in params.split(",")] if params else None
    c = isogami.cell(family, p, cell)
    assert isinstance(c, isogami.Cell)
    assert_same(c.to_dict(), want)
    assert c.cell == tuple(int(v) for v in cell.split("x"))
    assert np.allclose(c.u, want["u"], rtol=0, atol=1e-12) and np.allclose(c.w, want["w"], rtol=0, atol=1e-12)
    assert c.tile_count == len(want["tiles"]) and c.edge_count == len(want["edges"])
    for poly, tile in zip(c.polygons, want["tiles"]):
        assert np.allclose(poly, tile["polygon"], rtol=0, atol=1e-12)
    assert c.aspects == [t["aspect"] for t in want["tiles"]]
    assert np.allclose(c.centroids, [t["centroid"] for t in want["tiles"]], rtol=0, atol=1e-12)
    e = want["edges"]
    assert c.edges.tolist() == [[x["tile_a"], x["edge_a"], x["tile_b"], x["edge_b"]] for x in e]
    assert c.offsets.tolist() == [x["offset"] for x in e]
    assert np.allclose(c.endpoints, [[x["a"], x["b"]] for x in e], rtol=0, atol=1e-12)
    assert abs(c.mean_edge_length - want["mean_edge_length"]) < 1e-12


def test_cell_geometry_is_consistent():
    c = isogami.cell("IH28", cell=(2, 1))
    area = abs(c.u[0] * c.w[1] - c.u[1] * c.w[0])
    tiles = sum(0.5 * abs(np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])) for p in c.polygons)
    assert abs(area - tiles) < 1e-9 * area  # the tiles cover the cell exactly
    assert c.edges.dtype == np.int64 and c.endpoints.shape == (c.edge_count, 2, 2)
    svg = c.svg()
    assert svg.startswith("<svg") or svg.lstrip().startswith("<?xml")
    assert "IH28" in repr(c)


def test_cell_svg_marks_joints_and_checks_them():
    c = isogami.cell("IH90")
    plain, jointed = c.svg(), c.svg("aaa")
    assert jointed != plain
    with pytest.raises(isogami.DesignError):
        c.svg("aa")
    with pytest.raises(isogami.DesignError):
        c.svg("aq?")


@pytest.mark.parametrize(
    "args,error",
    [
        (("IH999",), isogami.TilingError),
        (("IH28", [0.1]), isogami.TilingError),
        (("IH28", [float("inf"), 0.5]), isogami.TilingError),
        (("IH28", None, "5x1"), isogami.CellError),
        (("IH28", None, (0, 1)), isogami.CellError),
        (("IH28", None, "2by1"), isogami.CellError),
        (("IH28", None, 2), TypeError),
        (("IH28", "0.1,0.5"), TypeError),
    ],
)
def test_bad_cells_raise(args, error):
    with pytest.raises(error):
        isogami.cell(*args)

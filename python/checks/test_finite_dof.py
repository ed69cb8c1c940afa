"""Degrees of freedom of finite sheets (issue 22) counted with numpy from `isogami export`'s
kirigami-sim and tiles-json files (finite_dof.py), against `isogami sheet --json`.

The count never reads the sheet command's numbers: it builds the pin constraints' Jacobian
from the exported polygons and pins and takes its rank from numpy's singular values. Only the
comparison reads `raw_mobility` (and `completion.mobility` once export writes completed
sheets).
"""

import numpy as np
import pytest

import finite_dof as fd
from conftest import BIN

DESIGNS = [
    "rotating-squares",
    "IH44:0.5,0.027564102564:1x2:-aaabbaa",
    "IH2:0.04739750492,0.35,0.150335752741,0.150335752741:1x1:aa-aa-",
    "IH10::1x2:-aaaa-",
    "IH31::1x1:-baaaaabbb-a",
]
SIZES = ["2x2", "4x4"]
T = "0.3"


@pytest.fixture(scope="session")
def isogami():
    if not BIN.exists():
        pytest.fail(f"no isogami binary at {BIN}: build it (cargo build -p isogami-cli) or set "
                    "ISOGAMI_BIN")
    return BIN


# --- the count alone, on sheets made by hand --------------------------------------------------


def square(cx, cy, theta=0.0, half=0.5):
    c, s = np.cos(theta), np.sin(theta)
    corners = np.array([[half, -half], [half, half], [-half, half], [-half, -half]])
    return corners @ np.array([[c, s], [-s, c]]) + [cx, cy]


def test_two_tiles_on_one_pin_turn_about_it():
    polys = [square(0, 0), square(1, 1)]  # corner 1 of the first is corner 3 of the second
    got = fd.count_dof(polys, [(0, 1, 1, 3)])
    assert (got.rank, got.pieces, got.dof) == (2, 1, 1)
    assert got.pin_residual < 1e-15


def test_a_ring_of_four_squares_is_a_four_bar():
    # Squares of side 1 filling [-1, 1]^2; tile k's pins listed as (tile, corner) pairs.
    polys = [square(-0.5, -0.5), square(0.5, -0.5), square(-0.5, 0.5), square(0.5, 0.5)]

    def corner(tile, xy):
        return int(np.argmin(np.linalg.norm(polys[tile] - xy, axis=1)))

    def pins_at(pairs):
        return [(a, corner(a, xy), b, corner(b, xy)) for a, b, xy in pairs]

    # Pinned at the outer ends of the shared edges: each square is a bar between opposite
    # corners, the bars a parallelogram four-bar, one DOF.
    outer = pins_at([(0, 1, (0, -1)), (1, 3, (1, 0)), (3, 2, (0, 1)), (2, 0, (-1, 0))])
    got = fd.count_dof(polys, outer)
    assert (got.rank, got.dof) == (8, 1), got
    # Pinned as the closed cell of rotating squares (export --patch 1x1 --t 0): every bar lies
    # on the line y = 0, a singular four-bar with one more first-order DOF.
    flat = pins_at([(0, 1, (0, 0)), (0, 2, (-1, 0)), (1, 3, (1, 0)), (2, 3, (0, 0))])
    got = fd.count_dof(polys, flat)
    assert (got.rank, got.dof) == (7, 2), got
    assert got.gap_decades > 10


def test_pieces_and_the_one_frame_convention():
    polys = [square(0, 0), square(1, 1), square(5, 0), square(6, 1)]
    got = fd.count_dof(polys, [(0, 1, 1, 3), (2, 1, 3, 3)])
    assert (got.pieces, got.dof, got.dof_one_frame) == (2, 2, 5)


def test_the_count_does_not_depend_on_scale_or_placement():
    polys = [square(0, 0), square(1, 1), square(2, 0, 0.3)]
    pins = [(0, 1, 1, 3)]
    base = fd.count_dof(polys, pins)
    moved = fd.count_dof([1000.0 * p + [5e4, -3e4] for p in polys], pins)
    assert (moved.rank, moved.dof) == (base.rank, base.dof) == (2, 1)  # the loose tile: 0
    assert moved.dof_one_frame == 4  # ... or 3 in the one-frame convention
    assert moved.smallest_nonzero == pytest.approx(base.smallest_nonzero, rel=1e-9)


# --- export files against `isogami sheet` -----------------------------------------------------


@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("design", DESIGNS)
def test_raw_region_dof_matches_isogami_sheet(isogami, tmp_path, design, size):
    row = fd.compare(isogami, design, size, T, tmp_path)
    assert not row["problems"], row["problems"]
    mine, theirs = row["numpy"], row["isogami"]
    assert mine["tiles"] == theirs["tiles"] and mine["joints"] == theirs["joints"]
    assert mine["pieces"] == theirs["pieces"]
    assert mine["gap_decades"] >= fd.MIN_GAP_DECADES, mine
    assert mine["pin_residual"] < 1e-9, mine
    assert mine["dof_one_frame"] == theirs["dof"], (design, size, mine, theirs)
    # Asked at --t 0.3 directly, `isogami sheet` picks the state the export picked.
    direct = fd.isogami_sheet(isogami, design, size, float(T))
    assert direct["t"] == row["t_export"]
    assert direct["raw_mobility"]["dof"] == theirs["dof"]


@pytest.mark.parametrize("k", [1, 2, 3, 4, 6])
def test_rotating_squares_open_with_one_dof_and_closed_with_4k_minus_2(isogami, tmp_path, k):
    size = f"{k}x{k}"
    polys, pins, table = fd.export_sheet(isogami, "rotating-squares", size, T, tmp_path / "open")
    opened = fd.count_dof(polys, pins)
    assert table["t"] > 0 and opened.pieces == 1
    assert opened.dof == 1, opened
    polys, pins, table = fd.export_sheet(isogami, "rotating-squares", size, "0",
                                         tmp_path / "closed")
    closed = fd.count_dof(polys, pins)
    assert table["t"] == 0
    assert closed.tiles == 4 * k * k and closed.pieces == 1
    assert closed.dof == 4 * k - 2, closed
    assert closed.gap_decades >= fd.MIN_GAP_DECADES, closed
    sheet = fd.isogami_sheet(isogami, "rotating-squares", size, float(T))
    assert sheet["raw_closed_dof"] == closed.dof


def test_a_sheet_in_pieces_counts_the_other_pieces_as_free(isogami, tmp_path):
    # One cell of this design falls apart into two pinned pairs: 1 DOF in each pair; isogami
    # counts the second pair's free rigid motion too (the largest piece plus three per other).
    design = "IH44:0.5,0.027564102564:1x2:-aaabbaa"
    row = fd.compare(isogami, design, "1x1", T, tmp_path)
    assert not row["problems"], row["problems"]
    assert (row["numpy"]["pieces"], row["numpy"]["dof"]) == (2, 2)
    assert row["numpy"]["dof_one_frame"] == row["isogami"]["dof"] == 5


@pytest.mark.parametrize("design", DESIGNS)
def test_completed_sheet_dof_matches_isogami_sheet(isogami, tmp_path, design):
    try:
        fd.sheet_mode_flags(isogami, completed=True)
    except RuntimeError as e:
        pytest.skip(str(e))
    try:
        row = fd.compare(isogami, design, "4x4", T, tmp_path, completed=True)
    except RuntimeError as e:
        # No one-DOF sheet: the export refuses, and so does `isogami sheet`, for one reason.
        assert "no one-DOF sheet" in str(e), e
        done = fd.run([isogami, "sheet", "--design", design, "--region", "4x4", "--t", T])
        assert done.returncode == 2 and "no one-DOF sheet" in done.stderr, done.stderr
        return
    assert not row["problems"], row["problems"]
    # Counted by numpy from the exported files alone: the completed sheet has one DOF.
    assert row["numpy"]["dof_one_frame"] == 1, row
    assert row["numpy"]["dof_one_frame"] == row["isogami"]["dof"], row
    assert row["numpy"]["gap_decades"] >= fd.MIN_GAP_DECADES, row


@pytest.mark.parametrize("design,completed", [
    ("IH44:0.5,0.027564102564:1x2:-aaabbaa", False),  # raw: 15 extra modes, k doubles
    ("IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-", True),
])
def test_the_sparse_count_equals_the_dense_svd(isogami, tmp_path, design, completed):
    polys, pins, _ = fd.export_sheet(isogami, design, "4x4", T, tmp_path, completed=completed)
    dense = fd.count_dof(polys, pins, method="svd")
    sparse = fd.count_dof(polys, pins, method="sparse")
    assert (sparse.rank, sparse.dof, sparse.method) == (dense.rank, dense.dof, "sparse")
    assert sparse.gap_decades > fd.MIN_GAP_DECADES
    # The same smallest non-zero singular value, to the solvers' accuracy.
    assert abs(sparse.smallest_nonzero / dense.smallest_nonzero - 1) < 1e-6

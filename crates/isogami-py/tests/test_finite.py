"""Finite sheets from Python: the same analysis as `isogami sheet --json`, numpy arrays that
agree with it, a completed sheet's rank checked with numpy, the finite deployment, errors."""

import numpy as np
import pytest

import isogami

IH44 = "IH44:0.5,0.027564102564:1x2:-aaabbaa"


def test_the_sheet_equals_the_cli(cli):
    sheet = isogami.finite_sheet(IH44, "4x4")
    assert isinstance(sheet, isogami.FiniteSheet)
    report = cli("sheet", "--design", IH44, "--region", "4x4", "--json")
    assert sheet.report() == report
    completion = report["completion"]
    assert sheet.completed and sheet.dof == 1
    assert sheet.raw_dof == report["raw_mobility"]["dof"] > 1
    assert sheet.tiles.shape == (len(completion["sheet"]["tiles"]), 3)
    assert sheet.tiles.dtype == np.int64
    first = completion["sheet"]["tiles"][0]
    assert list(sheet.tiles[0]) == [first["cell"][0], first["cell"][1], first["tile"]]
    assert sheet.joints.shape == (len(completion["sheet"]["joints"]), 3)
    assert sheet.covered_fraction == completion["report"]["covered_fraction"]
    assert len(sheet.removed) == len(completion["report"]["removed"])
    assert len(sheet.added) == len(completion["report"]["added"])
    # Every extra mode of the raw region names rows of raw_tiles.
    assert len(sheet.floppy_tiles) == len(report["raw_mobility"]["floppy"])
    for mode in sheet.floppy_tiles:
        assert mode.size and mode.max() < len(sheet.raw_tiles)
    assert set(sheet.loose_tiles.tolist()) <= set(range(len(sheet.raw_tiles)))
    assert sheet.raw_closed_dof >= sheet.raw_dof and sheet.closed_dof >= 1
    assert sheet.region == "4x4" and 0 < sheet.t <= 1 and sheet.design == IH44
    assert "FiniteSheet(" in repr(sheet)


def test_a_raw_sheet_has_its_own_count():
    raw = isogami.finite_sheet(IH44, "4x4", complete=False)
    assert not raw.completed and raw.dof == raw.raw_dof > 1
    assert raw.covered_fraction == 1.0 and raw.removed.shape == (0, 3)
    assert (raw.tiles == raw.raw_tiles).all()


def test_the_finite_deployment_follows_the_periodic_sheet(cli):
    run = isogami.deploy_sheet(IH44, "4x4", frames=12)
    assert isinstance(run, isogami.SheetDeployment)
    assert run.one_dof_throughout and run.sheet.dof == 1
    assert run.max_position_deviation <= 1e-6 and run.max_angle_deviation <= 1e-6
    n = len(run.sheet.tiles)
    assert run.poses.shape == (12, n, 3)
    assert run.t.shape == run.step.shape == run.hull_area_ratio.shape == run.clearance.shape == (12,)
    assert run.stretches.shape == (12, 2) and (run.stretches[:, 0] >= run.stretches[:, 1]).all()
    assert run.t[0] == 0.0 and run.t[-1] == 1.0
    assert run.hull_area_ratio[0] == pytest.approx(1.0)
    assert run.max_hull_area_ratio >= run.hull_area_ratio.max()
    assert run.max_hull_area_ratio >= run.periodic_hull_area_ratio * (1 - 1e-3)
    assert run.end_reason in {"contact_limit", "max_steps", "step_size_exhausted"}
    assert run.steps >= 2
    # The same numbers as the command line's JSON.
    report = cli("sheet", "--design", IH44, "--region", "4x4", "--deploy", "--frames", "12", "--json")
    assert run.report() == report
    assert "SheetDeployment(" in repr(run)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: isogami.finite_sheet(IH44, "0x3"), "region"),
        (lambda: isogami.finite_sheet(IH44, "disc:-1"), "region"),
        (lambda: isogami.finite_sheet(IH44, "6x6", t=0.0), "t = 0"),
        (lambda: isogami.finite_sheet(IH44, "6x6", min_cover=2.0), "covered"),
        (lambda: isogami.deploy_sheet(IH44, "4x4", complete=False), "degrees of freedom"),
        (lambda: isogami.deploy_sheet(IH44, "4x4", frames=1), "frames"),
        (lambda: isogami.deploy_sheet(IH44, "4x4", t=1.5), "t = 1.5"),
    ],
)
def test_bad_requests_raise_finite_error(call, message):
    with pytest.raises(isogami.FiniteError, match=message):
        call()


IH9 = "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-"


def test_a_pulled_raw_sheet_leaves_the_motion_and_equals_the_cli(cli):
    run = isogami.pull_sheet(IH9, "2x2", complete=False, frames=6)
    assert isinstance(run, isogami.SheetPull)
    assert run.dof > 1 and not run.sheet.completed
    assert run.poses.shape == (6, len(run.sheet.tiles), 3)
    assert run.deviation.shape == run.extension.shape == run.periodic_t.shape == (6,)
    assert run.max_deviation == pytest.approx(run.deviation.max())
    assert run.max_deviation > 0.01 and len(run.leaving) > 0
    assert run.leaves["dof"] > 1
    report = cli("sheet", "--design", IH9, "--region", "2x2", "--raw", "--pull", "--frames", "6", "--json")
    assert run.report() == report
    assert "SheetPull(" in repr(run)


def test_a_pulled_one_dof_sheet_follows_the_motion():
    run = isogami.pull_sheet("rotating-squares", "3x3", complete=False, grips=(0, 35), frames=5)
    assert run.grips == (0, 35) and run.dof == 1
    assert run.leaves is None and run.max_deviation < 1e-6
    # The grips' distance grows monotonically while the squares turn.
    assert all(b >= a for a, b in zip(run.extension, run.extension[1:]))


@pytest.mark.parametrize(
    "kwargs, message",
    [(dict(grips=(0, 0)), "grips"), (dict(grips=(0, 10**6)), "grips"), (dict(frames=1), "frames")],
)
def test_bad_pulls_raise_finite_error(kwargs, message):
    with pytest.raises(isogami.FiniteError, match=message):
        isogami.pull_sheet("rotating-squares", "2x2", complete=False, **kwargs)

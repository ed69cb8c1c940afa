"""Graded sheets from Python: the same JSON as `isogami graded --json` (to the byte but for
the run's seconds), numpy arrays that agree with it, SVG targets, area-ratio field targets
(each cell's asked and achieved ratio as the CLI's JSON gives them), exports equal to
`isogami export --sheet`'s files byte for byte, progress that can stop the run, errors in the
package's classes, save/load and pickle round trips."""

import json
import os
import pickle
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import isogami

RHOMBUS = "polygon:0,-1;1.3,0;0,1;-1.3,0"

# The rhombus drawn in an SVG file: tall in y-down coordinates, turned a quarter turn.
RHOMBUS_SVG = """<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">
  <g transform="translate(50 50) rotate(90) scale(20)">
    <path d="M 0 -1.3 L 1 0 L 0 1.3 L -1 0 Z"/>
  </g>
</svg>
"""


def without_seconds(text):
    """The JSON text with the run's wall time blanked (the one number that differs)."""
    return re.sub(r'"seconds": [^,\n]+', '"seconds": 0', text)


@pytest.fixture(scope="module")
def run():
    return isogami.graded("rotating-squares", (2, 2), RHOMBUS, iterations=60)


def test_the_json_is_the_clis(run, cli_raw):
    assert isinstance(run, isogami.GradedRun)
    done = cli_raw(
        "graded", "--design", "rotating-squares", "--region", "2x2", "--allow-failed",
        "--target", RHOMBUS, "--iterations", "60", "--json",
    )
    assert done.returncode == 0, done.stderr
    assert without_seconds(run.to_json() + "\n") == without_seconds(done.stdout.decode())
    whole = json.loads(run.to_json())
    assert run.report() == whole["report"] and run.path_check() == whole["path"]
    assert run.reached == whole["path"]["reached"]
    assert run.verdict() == whole["verdict"] and run.fit() == whole["fit"]
    assert run.passed == (whole["verdict"]["opens"] and whole["verdict"]["meets_target"])
    assert run.joint_gap == whole["report"]["joint_gap"]
    assert run.max_outline_error == whole["report"]["max_outline_error"]
    assert "GradedRun(" in repr(run) and "16 tiles" in repr(run)


def test_the_defaults_are_the_clis(cli_raw):
    """The signature's defaults (from the library at run time, shown by help()) are the ones
    `isogami graded --help` shows."""
    import inspect

    shown = cli_raw("graded", "--help").stdout.decode()
    defaults = inspect.signature(isogami.graded).parameters
    for name in ["states", "iterations"]:
        found = re.search(rf"--{name} <\w+>\s+[^\[]*\[default: (\d+)\]", shown)
        assert found, f"--{name} in {shown}"
        assert defaults[name].default == int(found.group(1)), name
    assert defaults["target"].default == "disc" and "[default: disc]" in shown


def test_the_arrays_agree_with_the_json(run):
    sheet = json.loads(run.to_json())["sheet"]
    n = len(sheet["tiles"])
    assert run.design == sheet["design"] and run.length_scale == sheet["length_scale"]
    assert run.tiles.shape == (n, 3) and run.tiles.dtype == np.int64
    assert list(run.tiles[0]) == [*sheet["tiles"][0]["cell"], sheet["tiles"][0]["tile"]]
    assert run.nodes.shape == (len(sheet["nodes"]), 2)
    assert np.array_equal(run.nodes, np.array(sheet["nodes"]))
    assert [list(t) for t in run.tile_nodes] == [t["nodes"] for t in sheet["tiles"]]
    assert np.array_equal(run.joints, np.array([[j["a"], j["b"], j["node"]] for j in sheet["joints"]]))
    assert np.array_equal(run.poses, np.array([[p["x"], p["y"], p["theta"]] for p in sheet["opened"]]))
    assert run.states.shape == (len(sheet["path"]), n, 3)
    assert len(run.closed) == len(run.opened) == n
    for i in range(n):
        closed, opened = run.closed[i], run.opened[i]
        assert np.array_equal(closed, run.nodes[run.tile_nodes[i]])
        # Opened tiles are rigid copies of their closed shapes, placed by their pose.
        x, y, theta = run.poses[i]
        c, s = np.cos(theta), np.sin(theta)
        placed = (closed - closed[0]) @ np.array([[c, s], [-s, c]]) + [x, y]
        assert np.allclose(opened, placed, atol=1e-12)
    # The pins' gap, recomputed from the opened polygons, is the report's.
    gap = 0.0
    for a, b, node in run.joints:
        pa = run.opened[a][list(run.tile_nodes[a]).index(node)]
        pb = run.opened[b][list(run.tile_nodes[b]).index(node)]
        gap = max(gap, float(np.hypot(*(pa - pb))))
    assert gap == pytest.approx(run.joint_gap, rel=1e-9, abs=1e-15)
    # The target outline at its fitted scale: the rhombus's four corners, wide along x.
    assert run.target.shape == (4, 2)
    width, height = np.abs(run.target).max(axis=0)
    assert width / height == pytest.approx(1.3)


def test_an_svg_target_is_the_outline_drawn(run, tmp_path, cli_raw):
    path = tmp_path / "rhombus.svg"
    path.write_text(RHOMBUS_SVG)
    drawn = isogami.graded("rotating-squares", "2x2", f"@{path}", iterations=60)
    done = cli_raw(
        "graded", "--design", "rotating-squares", "--region", "2x2", "--allow-failed",
        "--target", f"@{path}", "--iterations", "60", "--json",
    )
    assert done.returncode == 0, done.stderr
    assert without_seconds(drawn.to_json() + "\n") == without_seconds(done.stdout.decode())
    # The same corners as the typed rhombus (in some order) and the same fit.
    for corner in run.target:
        assert np.abs(drawn.target - corner).sum(axis=1).min() < 1e-9
    assert drawn.max_outline_error == pytest.approx(run.max_outline_error, rel=1e-6)


def test_progress_is_called_and_can_stop_the_run():
    heard = []
    isogami.graded("rotating-squares", (2, 2), iterations=20, progress=lambda i, c: heard.append((i, c)))
    assert len(heard) >= 5
    assert all(isinstance(i, int) and isinstance(c, float) for i, c in heard)
    assert [i for i, _ in heard] == sorted(i for i, _ in heard)
    # The cost at each stage's weights (they stiffen from stage to stage).
    assert all(np.isfinite(c) and c >= 0 for _, c in heard)

    calls = []

    def stop_at_three(iteration, cost):
        calls.append(iteration)
        return len(calls) < 3

    with pytest.raises(isogami.CancelledError, match="progress callback returned False"):
        isogami.graded("rotating-squares", (2, 2), iterations=60, progress=stop_at_three)
    assert len(calls) == 3

    def fail(iteration, cost):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        isogami.graded("rotating-squares", (2, 2), iterations=60, progress=fail)
    with pytest.raises(TypeError, match=r"progress must be callable \(iteration, cost\)"):
        isogami.graded("rotating-squares", (2, 2), progress=42)
    with pytest.raises(isogami.CancelledError, match="timeout"):
        isogami.graded("rotating-squares", (2, 2), iterations=60, timeout=1e-3)


CTRL_C = """
import signal, sys
signal.signal(signal.SIGINT, signal.default_int_handler)
import isogami
print("ready", flush=True)
try:
    isogami.graded("rotating-squares", (6, 6), "ellipse:3,1", states=16, iterations=10**6)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""


@pytest.mark.skipif(os.name != "posix", reason="sends SIGINT")
def test_ctrl_c_interrupts_a_graded_run():
    child = subprocess.Popen([sys.executable, "-c", CTRL_C], stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "ready"
        time.sleep(0.5)
        child.send_signal(signal.SIGINT)
        out, _ = child.communicate(timeout=120)
    finally:
        if child.poll() is None:
            child.kill()
    assert out.strip() == "interrupted"
    assert child.returncode == 0


def test_bad_requests_raise_with_the_librarys_message(tmp_path):
    two = tmp_path / "two.svg"
    two.write_text('<svg xmlns="http://www.w3.org/2000/svg"><rect width="9" height="9"/><circle r="3"/></svg>')
    for kwargs, error, message in [
        (dict(target="blob"), isogami.FiniteError, "bad target: a target is disc"),
        (dict(target="ellipse:1,0"), isogami.FiniteError, "semi-axes"),
        (dict(target=f"@{two}"), isogami.FiniteError, r"bad target: the SVG has 2 shapes \(<rect>, <circle>\)"),
        (dict(target=f"@{tmp_path / 'missing.svg'}"), isogami.FiniteError, "bad target: cannot read .*missing.svg"),
        (dict(region=(0, 2)), isogami.FiniteError, "region"),
        (dict(region="2by2"), ValueError, "RxC"),
        (dict(states=0), isogami.SettingsError, "states"),
        (dict(t=1.5), isogami.SettingsError, "t = 1.5"),
        (dict(iterations=0), ValueError, "iterations"),
    ]:
        with pytest.raises(error, match=message):
            isogami.graded("rotating-squares", **{"region": (2, 2), **kwargs})
    with pytest.raises(isogami.IsogamiError, match="IH99"):
        isogami.graded("IH99::1x1:a", (2, 2))


def test_save_and_load_round_trip(run, tmp_path, cli_raw):
    path = tmp_path / "sheet.json"
    run.save(path)
    assert path.read_text() == run.to_json() + "\n"
    loaded = isogami.load_graded(path)
    assert isinstance(loaded, isogami.GradedRun)
    assert loaded == run and loaded.to_json() == run.to_json()
    assert loaded.report() == run.report() and loaded.path_check() == run.path_check()
    for name in ["nodes", "tiles", "joints", "poses", "states", "target"]:
        assert np.array_equal(getattr(loaded, name), getattr(run, name)), name
    assert all(np.array_equal(a, b) for a, b in zip(loaded.opened, run.opened))
    assert pickle.loads(pickle.dumps(run)) == run
    # What the CLI's --out writes loads too, and says the same.
    out = tmp_path / "cli.json"
    done = cli_raw(
        "graded", "--design", "rotating-squares", "--region", "2x2", "--allow-failed",
        "--target", RHOMBUS, "--iterations", "60", "--out", str(out),
    )
    assert done.returncode == 0, done.stderr
    from_cli = isogami.load_graded(str(out))
    assert from_cli.to_json() + "\n" == out.read_text()
    assert without_seconds(from_cli.to_json()) == without_seconds(run.to_json())
    # Files that are not a graded run.
    bad = tmp_path / "bad.json"
    for text, message in [
        ("not json", "not JSON"),
        ('{"sheet": {}}', "no \"report\" object"),
        (json.dumps({**json.loads(run.to_json()), "sheet": {**json.loads(run.to_json())["sheet"], "opened": []}}),
         "opened poses"),
    ]:
        bad.write_text(text)
        with pytest.raises(isogami.FiniteError, match=message):
            isogami.load_graded(bad)
    with pytest.raises(isogami.FiniteError, match="cannot read"):
        isogami.load_graded(tmp_path / "missing.json")


FIELD = "field:1.3,1.7,90"


@pytest.fixture(scope="module")
def field_run():
    return isogami.graded("rotating-squares", (3, 3), FIELD, iterations=40)


def test_a_field_target_gives_each_cells_ratio_as_the_clis_json(field_run, cli_raw):
    done = cli_raw(
        "graded", "--design", "rotating-squares", "--region", "3x3", "--allow-failed",
        "--target", FIELD, "--iterations", "40", "--json",
    )
    assert done.returncode == 0, done.stderr
    assert without_seconds(field_run.to_json() + "\n") == without_seconds(done.stdout.decode())
    cli = json.loads(done.stdout)
    cells = cli["field"]
    assert len(cells) == cli["report"]["field_cells"] >= 4
    assert len({round(c["target"], 9) for c in cells}) >= 2, "a ramp asks the cells for different ratios"
    assert field_run.field_targets.tolist() == [c["target"] for c in cells]
    assert field_run.field_ratios.tolist() == [c["ratio"] for c in cells]
    assert field_run.field_cells.shape == (len(cells), 4, 2)
    assert field_run.field_cells.tolist() == [c["opened"] for c in cells]
    assert field_run.max_field_error == cli["report"]["max_field_error"]
    worst = np.abs(field_run.field_ratios - field_run.field_targets).max()
    assert worst == pytest.approx(field_run.max_field_error, abs=1e-12)
    assert all(1.3 - 1e-9 <= t <= 1.7 + 1e-9 for t in field_run.field_targets)
    assert "field within" in repr(field_run)
    # The keyword says the same; an outline run has no field.
    keyword = isogami.graded("rotating-squares", (3, 3), field=(1.3, 1.7, 90), iterations=40)
    assert without_seconds(keyword.to_json()) == without_seconds(field_run.to_json())
    # Saved and loaded, the cells stay.
    loaded = pickle.loads(pickle.dumps(field_run))
    assert loaded.field_ratios.tolist() == field_run.field_ratios.tolist()


def test_an_outline_run_has_no_field(run):
    assert run.max_field_error is None
    assert run.field_targets.shape == (0,) and run.field_cells.shape == (0, 4, 2)
    assert "field" not in json.loads(run.to_json())


def test_export_is_the_clis_file_byte_for_byte(run, field_run, tmp_path, cli_raw):
    for name, graded in [("rhombus", run), ("field", field_run)]:
        sheet = tmp_path / f"{name}.json"
        graded.save(sheet)
        for fmt, kwargs, flags in [
            ("svg", dict(hinge_mm=1.2), ["--hinge-mm", "1.2"]),
            ("dxf", dict(edge_mm=15), ["--edge-mm", "15"]),
            ("stl", {}, []),
            ("fold", dict(t="open", frames=4), ["--t", "open", "--frames", "4"]),
        ]:
            mine = graded.export(fmt, **kwargs)
            assert isinstance(mine, bytes) and mine
            out = tmp_path / f"{name}.{fmt}"
            done = cli_raw("export", "--sheet", str(sheet), "--format", fmt, *flags, "--out", str(out))
            assert done.returncode == 0, done.stderr
            assert mine == out.read_bytes(), (name, fmt)
    stl = run.export("stl")
    triangles = int.from_bytes(stl[80:84], "little")
    assert triangles > 0 and len(stl) == 84 + 50 * triangles
    assert re.search(rb"\n\s*0\r?\nSECTION\r?\n\s*2\r?\nHEADER\r?\n", run.export("dxf"))
    # A folder format: every file the CLI writes into its folder.
    folder = tmp_path / "sim"
    done = cli_raw("export", "--sheet", str(tmp_path / "rhombus.json"), "--format", "kirigami-sim", "--out", str(folder))
    assert done.returncode == 0, done.stderr
    files = run.export("kirigami-sim")
    assert files == {p.name: p.read_bytes() for p in folder.iterdir()}
    # A loaded run exports the same bytes.
    assert isogami.load_graded(tmp_path / "rhombus.json").export("svg") == run.export("svg")


def test_bad_fields_and_exports_raise_one_line_errors(run):
    for call, error, message in [
        (lambda: isogami.graded("rotating-squares", (2, 2), field=(0.5, 1.5)), isogami.FiniteError, "above 1"),
        (lambda: isogami.graded("rotating-squares", (2, 2), "field:1.2"), isogami.FiniteError, "field:FROM,TO"),
        (lambda: isogami.graded("rotating-squares", (2, 2), field=(1.2,)), TypeError, r"\(from, to\)"),
        (lambda: isogami.graded("rotating-squares", (2, 2), field="1.2,1.8"), TypeError, "field must be"),
        (lambda: isogami.graded("rotating-squares", (2, 2), "ellipse:1.2,1", field=(1.2, 1.8)), TypeError, "not both"),
        (lambda: isogami.graded("rotating-squares", (1, 1), field=(1.2, 1.8), iterations=5), isogami.FiniteError, "2x2"),
        (lambda: run.export("png"), isogami.ExportError, "unknown export format"),
        (lambda: run.export("svg", edge_mm=-1), isogami.ExportError, "-1"),
        (lambda: run.export("svg", edge_mm=10, width_mm=10), TypeError, "not both"),
        (lambda: run.export("svg", gap_mm=0.3), TypeError, "gap_mm does not apply"),
        (lambda: run.export("svg", t=1.5), isogami.ExportError, r"\[0, 1\]"),
        (lambda: run.export("svg", t="later"), isogami.ExportError, "'open'"),
        (lambda: run.export("fold", frames=1), isogami.ExportError, "frames"),
    ]:
        with pytest.raises(error, match=message) as caught:
            call()
        assert "\n" not in str(caught.value), str(caught.value)


def test_the_verdict_is_the_librarys_and_the_tolerance_and_fall_back_reach_it():
    """The verdict a run carries is the one `isogami graded` prints (its `text`), judged at
    the tolerance asked; `fall_back=False` gives the sheet graded towards the target itself
    (rotating squares, 2x2 cells, an L: it does not open), the default the nearest that does.
    A bad tolerance is the library's refusal as an exception."""
    ell = "polygon:0,0;2,0;2,1;1,1;1,2;0,2"
    exact = isogami.graded("rotating-squares", (2, 2), ell, fall_back=False)
    verdict = exact.verdict()
    assert verdict["target_fraction"] == 1.0 and not verdict["opens"] and not exact.passed
    assert "does NOT open along one motion" in verdict["text"]
    near = isogami.graded("rotating-squares", (2, 2), ell)
    assert near.verdict()["opens"] and 0 < near.verdict()["target_fraction"] < 1
    assert near.fit()["hausdorff"] == near.verdict()["error"]
    loose = isogami.graded("rotating-squares", (2, 2), ell,
                           tolerance=near.verdict()["error"] * 1.01)
    assert loose.passed and loose.verdict()["meets_target"]
    with pytest.raises(isogami.IsogamiError, match="tolerance"):
        isogami.graded("rotating-squares", (2, 2), tolerance=0.0)
    with pytest.raises(isogami.IsogamiError, match="unreachable target"):
        isogami.graded("rotating-squares", (2, 2), "ellipse:100,1")

"""Export: every library format, byte for byte what `isogami export` writes, and the checks
of every export setting."""

import json

import pytest

import isogami

FORMATS = [f["name"] for f in isogami.export_formats()]


def cli_export(cli_raw, tmp_path, design, fmt, *flags):
    out = tmp_path / f"out-{fmt}"
    done = cli_raw("export", "--design", design, "--format", fmt, "--out", str(out), *flags)
    assert done.returncode == 0, done.stderr.decode()
    if out.is_dir():
        return {p.name: p.read_bytes() for p in out.iterdir()}
    return out.read_bytes()


def test_formats_are_the_library_list():
    formats = isogami.export_formats()
    names = [f["name"] for f in formats]
    assert len(names) == len(set(names)) >= 7
    for expected in ["svg", "dxf", "stl", "3mf", "fold", "obj", "tiles-csv", "tiles-json", "kirigami-sim"]:
        assert expected in names
    groups = {f["name"]: f["settings"] for f in formats}
    assert groups["svg"] == groups["dxf"] == "laser" and groups["stl"] == groups["3mf"] == "print"
    assert groups["fold"] == groups["obj"] == "none"
    for f in formats:
        assert f["description"] and f["media_type"]
        assert f["extension"] is None or f["extension"].isalnum()


@pytest.mark.parametrize("fmt", FORMATS)
def test_every_format_equals_the_cli(cli_raw, tmp_path, fmt):
    want = cli_export(cli_raw, tmp_path, "rotating-squares", fmt, "--patch", "3x2")
    got = isogami.export("rotating-squares", fmt, patch="3x2")
    if isinstance(want, dict):
        assert isinstance(got, dict) and got == want
    else:
        assert isinstance(got, bytes) and got == want


@pytest.mark.parametrize(
    "flags,kwargs",
    [
        (["--format", "fold", "--t", "open", "--frames", "5", "--kerf", "0.02"], dict(format="fold", t="open", frames=5, kerf=0.02)),
        (["--format", "obj", "--t", "0.5", "--width-mm", "150", "--patch", "2x4"], dict(format="obj", t=0.5, width_mm=150.0, patch=(2, 4))),
        (["--format", "svg", "--material", "felt", "--hinge-mm", "2", "--labels", "--cut-colour", "#ff00ff"],
         dict(format="svg", material="felt", hinge_mm=2.0, labels=True, cut_colour="#ff00ff")),
        (["--format", "dxf", "--material", "card", "--kerf-mm", "0.15", "--margin-mm", "8", "--edge-mm", "30"],
         dict(format="dxf", material="card", kerf_mm=0.15, margin_mm=8.0, edge_mm=30.0)),
        (["--format", "tiles-csv", "--t", "1"], dict(format="tiles-csv", t=1.0)),
        (["--format", "stl", "--thickness-mm", "3", "--hinge-mm", "1.2", "--gap-mm", "0.5", "--lamella-mm", "0.6", "--nozzle-mm", "0.45"],
         dict(format="stl", thickness_mm=3.0, hinge_mm=1.2, gap_mm=0.5, lamella_mm=0.6, nozzle_mm=0.45)),
        (["--format", "3mf", "--t", "open", "--edge-mm", "15"], dict(format="3mf", t="open", edge_mm=15.0)),
    ],
)
def test_settings_equal_the_cli(cli_raw, tmp_path, flags, kwargs):
    # An isostatic sample (no one-DOF sheet): the rectangle as it is, both ways.
    spec = isogami.SAMPLE_OPENING_DESIGNS[2]
    fmt = flags[1]
    extra = [] if "--patch" in flags else ["--patch", "2x2"]
    want = cli_export(cli_raw, tmp_path, spec, fmt, *flags[2:], *extra, "--raw")
    kw = dict(kwargs, complete=False)
    kw.setdefault("patch", "2x2")
    got = isogami.export(isogami.design(spec), kw.pop("format"), **kw)
    assert got == want


def test_exported_files_read_back():
    fold = json.loads(isogami.export("rotating-squares", "fold", patch=(2, 2), frames=4))
    assert fold["file_spec"] and len(fold["file_frames"]) >= 3
    table = json.loads(isogami.export("rotating-squares", "tiles-json", patch=(2, 3)))
    assert len(table["tiles"] if isinstance(table, dict) else table) == 2 * 3 * 4
    csv = isogami.export("rotating-squares", "tiles-csv", patch=(1, 1)).decode()
    assert len(csv.strip().splitlines()) == 1 + 4
    sim = isogami.export("rotating-squares", "kirigami-sim", patch=(2, 2))
    assert all(isinstance(v, bytes) and v for v in sim.values()) and len(sim) >= 3
    svg = isogami.export("rotating-squares", "svg", creator="my lab").decode()
    assert "<svg" in svg and 'width="' in svg and "mm" in svg


@pytest.mark.parametrize(
    "kwargs,error,needle",
    [
        (dict(format="png"), isogami.ExportError, "png"),
        (dict(format="obj", patch="0x3"), isogami.ExportError, "patch"),
        (dict(format="obj", patch=(50, 2)), isogami.ExportError, "at most"),
        (dict(format="obj", patch="big"), isogami.ExportError, "ROWSxCOLS"),
        (dict(format="obj", patch=(-1, 2)), isogami.ExportError, "patch"),
        (dict(format="obj", edge_mm=float("nan")), isogami.ExportError, "edge length"),
        (dict(format="obj", width_mm=-3.0), isogami.ExportError, "width"),
        (dict(format="obj", t=1.5), isogami.ExportError, "t = 1.5"),
        (dict(format="obj", t="closed"), isogami.ExportError, "open"),
        (dict(format="fold", frames=1), isogami.ExportError, "frames"),
        (dict(format="svg", material="wood"), isogami.ExportError, "material 'wood'"),
        (dict(format="svg", hinge_mm=-1.0), isogami.ExportError, "hinge"),
        (dict(format="svg", cut_colour="black!"), isogami.ExportError, "colour"),
        (dict(format="stl", hinge_mm=0.2), isogami.ExportError, "nozzle"),
        (dict(format="stl", lamella_mm=5.0), isogami.ExportError, "lamella"),
        (dict(format="3mf", gap_mm=float("nan")), isogami.ExportError, "gap_mm"),
        (dict(format="stl", material="card"), TypeError, "material does not apply to format stl"),
        (dict(format="svg", gap_mm=0.3), TypeError, "gap_mm does not apply to format svg"),
        (dict(format="obj", hinge_mm=1.0), TypeError, "hinge_mm does not apply"),
        (dict(format="fold", labels=True), TypeError, "labels does not apply"),
        (dict(format="obj", kerf=0.9), isogami.SettingsError, "kerf"),
        (dict(format="obj", edge_mm=10.0, width_mm=100.0), TypeError, "not both"),
        (dict(format="obj", t=[0.5]), TypeError, "t must be"),
        (dict(format="obj", patch=2.5), TypeError, "patch"),
        (dict(format="obj", frames="x"), TypeError, "frames"),
    ],
)
def test_bad_export_settings(kwargs, error, needle):
    fmt = kwargs.pop("format")
    with pytest.raises(error, match=needle):
        isogami.export("rotating-squares", fmt, **kwargs)


def test_export_bad_designs():
    with pytest.raises(isogami.DeployError, match="rigid"):
        isogami.export("IH90::1x1:xxx", "obj")
    with pytest.raises(isogami.DesignError):
        isogami.export("IH90::1x1:x", "obj")
    with pytest.raises(TypeError):
        isogami.export(None, "obj")


IH44 = "IH44:0.5,0.027564102564:1x2:-aaabbaa"


def test_the_completed_sheet_is_the_default_and_complete_false_is_raw(cli_raw, tmp_path):
    done = isogami.export(IH44, "tiles-json", patch="4x4")
    raw = isogami.export(IH44, "tiles-json", patch="4x4", complete=False)
    assert done == cli_export(cli_raw, tmp_path, IH44, "tiles-json", "--patch", "4x4")
    assert raw == cli_export(cli_raw, tmp_path, IH44, "tiles-json", "--patch", "4x4", "--raw")
    cells = lambda data: {tuple(t["cell"]) for t in json.loads(data)["tiles"]}
    assert cells(raw) == {(i, j) for i in range(4) for j in range(4)}
    # IH44's 4x4 rectangle flops at its boundary: the completion adds ring tiles outside it.
    assert cells(done) - cells(raw)
    # No one-DOF sheet in the region: the default export is refused, the raw one written.
    isostatic = "IH10::2x2:--a--aa-a-bb"
    with pytest.raises(isogami.FiniteError, match="no one-DOF sheet"):
        isogami.export(isostatic, "obj")
    assert isogami.export(isostatic, "obj", complete=False).startswith(b"#")


@pytest.mark.parametrize("region", ["3x5", "disc:70", "polygon:0,0;100,0;0,80"])
def test_a_region_is_exported_as_the_cli_exports_it(cli_raw, tmp_path, region):
    for complete, flag in [(True, ()), (False, ("--raw",))]:
        data = isogami.export(IH44, "tiles-json", region=region, complete=complete)
        assert data == cli_export(cli_raw, tmp_path, IH44, "tiles-json", "--region", region, *flag)
        tiles = {(tuple(t["cell"]), t["tile"]) for t in json.loads(data)["tiles"]}
        sheet = isogami.finite_sheet(IH44, region, complete=complete)
        assert len(tiles) == len(sheet.tiles)


def test_a_region_is_checked_before_any_work():
    with pytest.raises(TypeError, match="patch or region"):
        isogami.export(IH44, "obj", patch="4x4", region="4x4")
    with pytest.raises(isogami.FiniteError, match="radius"):
        isogami.export(IH44, "obj", region="disc:-1")
    with pytest.raises(isogami.ExportError, match="edge length"):
        isogami.export(IH44, "obj", region="disc:40", width_mm=100)

"""Exports of a graded sheet (issue 25: `isogami graded --out`, then `isogami export --sheet`)
read by libraries that are not ours: ezdxf reads the laser DXF, trimesh, manifold3d and
lib3mf read the meshes as one closed manifold solid, shapely finds no two tiles of the closed
cut sheet (nor of the opened sheet) overlapping, and numpy places the sheet's own nodes and
poses where the tile table says its tiles are."""

import json
import subprocess

import ezdxf
import lib3mf
import numpy as np
import pytest
import trimesh
from shapely import set_precision
from shapely.geometry import Point, Polygon
from shapely.ops import unary_union

from conftest import BIN, PRINT, print_flags
import geometry
from test_print_meshes import check_solid, read_3mf

# A 2x2-cell rotating-squares sheet graded towards a disc, with the optimiser's default
# iterations (a few seconds in a debug build): a sheet whose path check opens it along one
# motion.
GRADED = ["graded", "--design", "rotating-squares", "--region", "2x2", "--states", "4",
          "--allow-failed"]
EDGE_MM = 20.0
KERF_MM = 0.2  # the laser default


class GradedFiles:
    """The graded sheet and its exports, each made once."""

    def __init__(self, folder):
        self.folder = folder
        self.sheet_path = folder / "sheet.json"
        done = subprocess.run([str(BIN), *GRADED, "--out", str(self.sheet_path)],
                              capture_output=True, text=True, timeout=300)
        assert done.returncode == 0, done.stderr
        with open(self.sheet_path) as f:
            self.run = json.load(f)
        self.paths = {}

    def path(self, fmt, *extra):
        key = (fmt, *extra)
        if key not in self.paths:
            out = self.folder / f"sheet-{len(self.paths)}.{fmt}"
            flags = print_flags() if fmt in ("stl", "3mf") else []
            done = subprocess.run(
                [str(BIN), "export", "--sheet", str(self.sheet_path), "--format", fmt,
                 "--out", str(out), "--edge-mm", str(EDGE_MM), *flags, *extra],
                capture_output=True, text=True, timeout=300)
            assert done.returncode == 0, f"{fmt}: {done.stderr}"
            self.paths[key] = out
        return self.paths[key]

    def table(self, *extra):
        return geometry.load_table(self.path("tiles-json", *extra))


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    if not BIN.exists():
        pytest.fail(f"no isogami binary at {BIN}: build it (cargo test --workspace --no-run)")
    return GradedFiles(tmp_path_factory.mktemp("graded"))


def sheet_polygons(run, poses=None):
    """Every tile's polygon from the sheet's nodes, closed or placed by poses (numpy)."""
    sheet = run["sheet"]
    nodes = np.array(sheet["nodes"], dtype=float)
    polys = []
    for i, tile in enumerate(sheet["tiles"]):
        corners = nodes[tile["nodes"]]
        if poses is not None:
            p = poses[i]
            c, s = np.cos(p["theta"]), np.sin(p["theta"])
            rot = np.array([[c, -s], [s, c]])
            corners = (corners - corners[0]) @ rot.T + np.array([p["x"], p["y"]])
        polys.append(corners)
    return polys


def mm_per_unit(run):
    """Millimetres per sheet unit at EDGE_MM: the mean closed edge, each edge once."""
    sheet = run["sheet"]
    nodes = np.array(sheet["nodes"], dtype=float)
    edges = set()
    for tile in sheet["tiles"]:
        n = tile["nodes"]
        for k in range(len(n)):
            edges.add(tuple(sorted((n[k], n[(k + 1) % len(n)]))))
    mean = np.mean([np.linalg.norm(nodes[a] - nodes[b]) for a, b in edges])
    return EDGE_MM / mean


def placed(polys, scale):
    lo = np.min(np.vstack(polys), axis=0)
    return [(p - lo) * scale for p in polys]


def assert_no_overlap(polys, what):
    shapes = [Polygon(p) for p in polys]
    for i, a in enumerate(shapes):
        assert a.is_valid and a.area > 0, f"{what}: tile {i}"
        for j in range(i + 1, len(shapes)):
            shared = a.intersection(shapes[j]).area
            assert shared < 1e-6 * a.area, f"{what}: tiles {i} and {j} overlap by {shared} mm²"
    union = unary_union(shapes).area
    assert union == pytest.approx(sum(s.area for s in shapes), rel=1e-9), what


def test_the_graded_sheet_opens_along_one_motion(graded):
    # The premise of the checks below: the file is a graded sheet that really opens.
    assert graded.run["path"]["reached"] is True
    assert len(graded.run["sheet"]["tiles"]) == 16


def test_closed_and_opened_tiles_are_the_sheets_own_and_do_not_overlap(graded):
    run = graded.run
    scale = mm_per_unit(run)
    closed = graded.table()
    opened = graded.table("--t", "open")
    assert closed["unit"] == "mm" and closed["t"] == 0 and opened["t"] == 1
    assert closed["edge_mm"] == pytest.approx(EDGE_MM)
    want_closed = placed(sheet_polygons(run), scale)
    want_opened = placed(sheet_polygons(run, run["sheet"]["opened"]), scale)
    got = {}
    for name, table, want in (("closed", closed, want_closed), ("opened", opened, want_opened)):
        got[name] = [np.array(row["polygon_mm"]) for row in table["tiles"]]
        assert len(got[name]) == len(want)
        for g, w in zip(got[name], want):
            np.testing.assert_allclose(g, w, atol=1e-9)
        # No two tiles overlap: the closed sheet is a tiling, the opened one a mechanism's
        # state that its path check found free of overlaps.
        assert_no_overlap(got[name], name)
    # The cut sheet is one piece without holes. Tiles sharing an edge carry its ends from their
    # own poses, equal to ~1e-14 mm but not bit for bit: the union snaps them to a 1e-6 mm grid
    # (a real gap would be far wider).
    whole = unary_union([set_precision(Polygon(p), 1e-6) for p in got["closed"]])
    assert whole.geom_type == "Polygon" and not whole.interiors
    # Pins meet in the opened sheet (to the optimiser's reported gap).
    gap = run["report"]["joint_gap"] * scale + 1e-9
    sheet = run["sheet"]
    for j in sheet["joints"]:
        va = sheet["tiles"][j["a"]]["nodes"].index(j["node"])
        vb = sheet["tiles"][j["b"]]["nodes"].index(j["node"])
        assert np.linalg.norm(got["opened"][j["a"]][va] - got["opened"][j["b"]][vb]) <= gap


def test_dxf_reads_audits_and_cuts_along_the_closed_tiles(graded):
    doc = ezdxf.readfile(graded.path("dxf"))
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    assert doc.header["$INSUNITS"] == 4  # millimetres
    assert {"CUT", "SCORE", "OUTLINE"} <= {layer.dxf.name for layer in doc.layers}
    msp = doc.modelspace()
    outlines = list(msp.query('POLYLINE LWPOLYLINE[layer=="OUTLINE"]'))
    assert len(outlines) == 1, "one outline round a sheet without holes"
    assert outlines[0].is_closed
    ring = Polygon([tuple(v)[:2] for v in outlines[0].points()])
    assert ring.is_valid
    # The DXF is in the closed sheet's millimetres (its bounding box at the origin); the
    # outline runs kerf/2 outside it, mitred.
    tiles = [Polygon(p) for p in placed(sheet_polygons(graded.run), mm_per_unit(graded.run))]
    sheet = unary_union(tiles)
    grown = sheet.buffer(KERF_MM / 2, join_style="mitre", mitre_limit=20.0)
    assert ring.symmetric_difference(grown).area < 1e-4 * grown.area
    # Every cut line lies on an edge two closed tiles share (a cut that meets the sheet's
    # edge runs on along its line to the outline, kerf/2 outside).
    shared = unary_union([a.intersection(b) for i, a in enumerate(tiles)
                          for b in tiles[i + 1:] if a.intersection(b).length > 0])
    cuts = list(msp.query('LINE[layer=="CUT"]'))
    assert cuts
    for line in cuts:
        a, b = line.dxf.start, line.dxf.end
        for p in (a, b):
            q = Point(p.x, p.y)
            assert min(shared.distance(q), ring.exterior.distance(q)) < 1e-3, (a, b)
        if (a - b).magnitude > KERF_MM:
            mid = Point((a.x + b.x) / 2, (a.y + b.y) / 2)
            assert shared.distance(mid) < 1e-3, (a, b)


def test_stl_is_one_closed_solid_of_the_expected_volume(graded):
    table = graded.table()
    mesh = trimesh.load(graded.path("stl"), file_type="stl", force="mesh")
    check_solid(mesh, "graded", table)


def test_3mf_is_in_mm_and_the_same_solid(graded):
    table = graded.table()
    unit, meta, meshes = read_3mf(graded.path("3mf"))
    assert unit == lib3mf.ModelUnit.MilliMeter
    assert "isogami" in meta["Application"]
    for key, value in PRINT.items():
        assert f"{key}: {value:g}" in meta["Description"], (key, meta["Description"])
    assert len(meshes) == 1
    check_solid(meshes[0], "graded", table)

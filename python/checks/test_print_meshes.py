"""STL and 3MF of `isogami export`, read by trimesh, manifold3d and lib3mf: one closed,
manifold, consistently wound solid with the expected volume (shapely, from the tile table),
the asked size, millimetres and metadata in the 3MF, and exactly one hinge per joint."""

from functools import reduce

import numpy as np
import pytest
import trimesh
import manifold3d
import lib3mf
from shapely.ops import unary_union

from conftest import DESIGNS, PRINT, WIDTH_MM
import geometry


def manifold_of(mesh):
    m = manifold3d.Manifold(manifold3d.Mesh(
        vert_properties=np.asarray(mesh.vertices, dtype=np.float32),
        tri_verts=np.asarray(mesh.faces, dtype=np.uint32)))
    return m


def read_3mf(path):
    """Unit, metadata and the one mesh object of a 3MF file, through lib3mf."""
    wrapper = lib3mf.get_wrapper()
    model = wrapper.CreateModel()
    model.QueryReader("3mf").ReadFromFile(str(path))
    group = model.GetMetaDataGroup()
    meta = {}
    for k in range(group.GetMetaDataCount()):
        item = group.GetMetaData(k)
        meta[item.GetName()] = item.GetValue()
    objects = model.GetMeshObjects()
    meshes = []
    while objects.MoveNext():
        obj = objects.GetCurrentMeshObject()
        verts = np.array([list(v.Coordinates) for v in obj.GetVertices()], dtype=float)
        tris = np.array([list(t.Indices) for t in obj.GetTriangleIndices()], dtype=np.int64)
        meshes.append(trimesh.Trimesh(verts, tris, process=False))
    return model.GetUnit(), meta, meshes


def check_solid(mesh, design, table):
    assert mesh.is_watertight, design
    assert mesh.is_winding_consistent, design
    assert mesh.body_count == 1, design
    status = manifold_of(mesh).status()
    assert status == manifold3d.Error.NoError, f"{design}: manifold3d says {status}"
    assert mesh.volume > 0, design
    expected = geometry.expected_volume(table, PRINT)
    assert mesh.volume == pytest.approx(expected, rel=0.01), design
    lo, hi = mesh.bounds
    x0, y0, x1, y1 = geometry.shrunk_bounds(table, PRINT["gap_mm"])
    assert lo[:2] == pytest.approx([x0, y0], abs=1e-3), design
    assert hi[:2] == pytest.approx([x1, y1], abs=1e-3), design
    k0, l0, k1, l1 = geometry.kept_bounds(table)
    assert lo[0] >= k0 - 1e-3 and lo[1] >= l0 - 1e-3 and hi[0] <= k1 + 1e-3 and hi[1] <= l1 + 1e-3
    assert (lo[2], hi[2]) == pytest.approx((0.0, PRINT["thickness_mm"]), abs=1e-4)
    if design == "rotating-squares":
        # A straight outline: the sheet is exactly the asked width.
        assert hi[0] - lo[0] == pytest.approx(WIDTH_MM, abs=1e-3)


def section(mesh, z):
    """Polygons of the mesh's cross-section at height z, in the sheet's x, y: trimesh's
    closed section rings combined even-odd (a ring inside another is a hole)."""
    path = mesh.section(plane_origin=[0, 0, z], plane_normal=[0, 0, 1])
    to_plane = np.eye(4)
    to_plane[2, 3] = -z
    planar, _ = path.to_2D(to_2D=to_plane)
    rings = [p for p in planar.polygons_closed if p is not None]
    region = reduce(lambda a, b: a.symmetric_difference(b), rings)
    return list(getattr(region, "geoms", [region]))


@pytest.mark.parametrize("design", DESIGNS)
def test_stl_is_one_closed_solid_of_the_expected_volume_and_size(files, design):
    f = files(design)
    table = geometry.load_table(f.path("tiles-json"))
    mesh = trimesh.load(f.path("stl"), file_type="stl", force="mesh")
    check_solid(mesh, design, table)


@pytest.mark.parametrize("design", DESIGNS)
def test_3mf_is_in_mm_with_metadata_and_the_same_solid(files, design):
    f = files(design)
    table = geometry.load_table(f.path("tiles-json"))
    unit, meta, meshes = read_3mf(f.path("3mf"))
    assert unit == lib3mf.ModelUnit.MilliMeter
    for name in ("Title", "Designer", "Application", "Description"):
        assert meta.get(name), f"{design}: no {name} in {meta}"
    assert table["design"] in meta["Title"] and "isogami" in meta["Application"]
    for key, value in PRINT.items():
        assert f"{key}: {value:g}" in meta["Description"], (key, meta["Description"])
    assert len(meshes) == 1
    check_solid(meshes[0], design, table)


@pytest.mark.parametrize("design", DESIGNS)
def test_tiles_are_separate_above_the_lamella_and_one_piece_in_it(files, design):
    f = files(design)
    table = geometry.load_table(f.path("tiles-json"))
    mesh = trimesh.load(f.path("stl"), file_type="stl", force="mesh")
    kept = geometry.largest_piece(table)
    lam, top = PRINT["lamella_mm"], PRINT["thickness_mm"]
    upper = section(mesh, 0.5 * (lam + top))
    lower = section(mesh, 0.5 * lam)
    assert len(upper) == len(kept), f"{design}: {len(upper)} pieces above the lamella"
    assert len(lower) == 1, f"{design}: {len(lower)} pieces in the lamella layer"
    # The lamella layer outside the tiles: one neck per joint, hinge x gap, joining exactly
    # the joint's two tiles.
    tiles_up = unary_union(upper).buffer(1e-4)
    necks = [p for p in getattr(lower[0].difference(tiles_up), "geoms", [lower[0].difference(tiles_up)])
             if p.area > 0.1 * PRINT["hinge_mm"] * PRINT["gap_mm"]]
    pairs = geometry.joint_pairs(table, kept)
    assert len(necks) == len(pairs), f"{design}: {len(necks)} hinges for {len(pairs)} joints"
    neck_area = PRINT["hinge_mm"] * (PRINT["gap_mm"] - 2e-4)
    shrunk = geometry.shrunk_tiles(table, kept, PRINT["gap_mm"])
    owner = {}
    for k, poly in enumerate(upper):
        inside = [i for i, s in shrunk.items() if poly.contains(s.representative_point())]
        assert len(inside) == 1, f"{design}: section piece {k} holds tiles {inside}"
        owner[k] = inside[0]
    found = []
    for neck in necks:
        assert neck.area == pytest.approx(neck_area, rel=0.02), design
        touching = sorted(owner[k] for k, poly in enumerate(upper) if poly.distance(neck) < 1e-3)
        assert len(touching) == 2, f"{design}: a hinge touches tiles {touching}"
        found.append(tuple(touching))
    assert sorted(found) == pairs, design

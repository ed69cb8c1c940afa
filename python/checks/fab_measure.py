"""Sizes a user measures on fabrication files, taken from the files alone (issue 23 items
10-12): the gaps between printed tiles, the necks of the lamella hinges, the length and
neck of laser bridges.

Meshes are read by trimesh and cut by a plane; the cut's rings are combined even-odd into
shapely polygons. DXF files are read by ezdxf; each cut line is the beam's centreline, so
the burn is the line grown by half the kerf (round ends), and the outline polyline likewise.
Nothing here imports or mirrors the exporter's geometry.
"""

from functools import reduce

import ezdxf
import numpy as np
import trimesh
from shapely.geometry import LineString, Point
from shapely.ops import linemerge, unary_union
from shapely.strtree import STRtree


def section(mesh, z):
    """Polygons of the mesh's cross-section at height z (x, y of the sheet)."""
    path = mesh.section(plane_origin=[0, 0, z], plane_normal=[0, 0, 1])
    if path is None:
        return []
    to_plane = np.eye(4)
    to_plane[2, 3] = -z
    planar, _ = path.to_2D(to_2D=to_plane)
    rings = [p for p in planar.polygons_closed if p is not None]
    region = reduce(lambda a, b: a.symmetric_difference(b), rings)
    return [p for p in getattr(region, "geoms", [region]) if p.area > 0]


def load_mesh(path):
    return trimesh.load(str(path), force="mesh")


def smallest_gap(pieces, reach):
    """Smallest distance between two different pieces (each a printed tile at mid-thickness),
    with the pair's index and a point where it happens; pairs farther than `reach` are
    not looked at."""
    tree = STRtree(pieces)
    best = (float("inf"), None, None)
    for i, p in enumerate(pieces):
        for j in tree.query(p.buffer(reach)):
            if j > i:
                d = p.distance(pieces[j])
                if d < best[0]:
                    best = (d, (i, int(j)), p.centroid)
    return best


def necks(tiles, lamella):
    """Width of each lamella hinge: the parts of the lamella layer outside the tiles (each
    one joint's neck across the gap between its two tiles) and, per part, the distance
    between its two free sides (its boundary away from the tiles). Returns (widths, number
    of parts whose free boundary is not two sides)."""
    up = unary_union(tiles)
    touch = up.buffer(1e-4)
    widths, odd = [], 0
    rest = lamella.difference(up.buffer(1e-5))
    for part in getattr(rest, "geoms", [rest]):
        if part.area < 1e-6:
            continue
        free = part.boundary.difference(touch)
        if free.geom_type == "MultiLineString":
            # The ring's seam can split a side in two.
            free = linemerge(free)
        sides = [s for s in getattr(free, "geoms", [free]) if s.length > 1e-4]
        if len(sides) != 2:
            odd += 1
            continue
        widths.append(sides[0].distance(sides[1]))
    return widths, odd


def laser_bridges(dxf_path, table, kept_tiles, kerf, reach):
    """(length, neck, tiles) of every bridge of a laser DXF: the stretches of an edge shared
    by two tiles of the tile table (both among `kept_tiles`, those on the sheet) that no burn
    covers. Its length is the stretch's; its neck
    is the least width of material between the burns at its two ends (found within `reach`
    of it; a path through a third burn counts its two gaps)."""
    msp = ezdxf.readfile(str(dxf_path)).modelspace()
    lines = [LineString([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]])
             for e in msp.query('LINE[layer=="CUT"]')]
    for pl in msp.query('POLYLINE LWPOLYLINE[layer=="OUTLINE"]'):
        pts = [tuple(v)[:2] for v in pl.points()]
        lines.append(LineString(pts + [pts[0]]))
    burns = [ln.buffer(kerf / 2, quad_segs=16) for ln in lines]
    tree = STRtree(burns)
    key = lambda p: (round(p[0], 6), round(p[1], 6))
    owners = {}
    for row in table["tiles"]:
        poly = row["polygon_mm"]
        for i in range(len(poly)):
            a, b = key(poly[i]), key(poly[(i + 1) % len(poly)])
            owners.setdefault(frozenset((a, b)), []).append(row["id"])
    kept = set(kept_tiles)
    out = []
    for ends, tiles in owners.items():
        if len(tiles) != 2 or len(ends) != 2 or not kept.issuperset(tiles):
            continue
        edge = LineString(list(ends))
        near = [burns[i] for i in tree.query(edge)]
        left = edge.difference(unary_union(near)) if near else edge
        for bridge in getattr(left, "geoms", [left]):
            if bridge.length < 1e-6:
                continue
            out.append((bridge.length, bridge_neck(bridge, burns, tree, reach), sorted(tiles)))
    return out


def bridge_neck(bridge, burns, tree, reach):
    mid = bridge.interpolate(0.5, normalized=True)
    window = mid.buffer(reach)
    local = [burns[i].intersection(window) for i in tree.query(window)]
    merged = unary_union([g for g in local if not g.is_empty])
    comps = list(getattr(merged, "geoms", [merged]))
    ends = [Point(bridge.coords[0]), Point(bridge.coords[-1])]
    at = [[k for k, c in enumerate(comps) if c.distance(p) < 1e-6] for p in ends]
    if not at[0] or not at[1]:
        return float("nan")
    a, b = at[0][0], at[1][0]
    if a == b:
        return 0.0
    # Shortest path from a to b where walking inside a burn is free (Dijkstra, few nodes).
    n = len(comps)
    dist = [float("inf")] * n
    dist[a] = 0.0
    todo = set(range(n))
    while todo:
        u = min(todo, key=lambda k: dist[k])
        todo.discard(u)
        if u == b:
            break
        for v in todo:
            dist[v] = min(dist[v], dist[u] + comps[u].distance(comps[v]))
    return dist[b]

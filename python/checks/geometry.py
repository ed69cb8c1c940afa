"""Expected geometry of a printed sheet, computed with shapely from the tile table alone.

Independent of the Rust code: the sheet is the largest joint-connected piece of the tiles;
each tile loses gap/2 along the edges it shares with another printed tile (shapely's mitred
buffer of the neighbours, which agrees with a per-edge inset up to corner terms of order
gap^2); each joint adds a lamella neck hinge x gap x lamella.
"""

import json

from shapely.geometry import Polygon
from shapely.ops import unary_union
from shapely.strtree import STRtree


def load_table(path):
    with open(path) as f:
        return json.load(f)


def largest_piece(table):
    """Ids of the largest piece the joints hold together (lowest id wins a tie)."""
    nb = {row["id"]: row["neighbours"] for row in table["tiles"]}
    seen, pieces = set(), []
    for start in sorted(nb):
        if start in seen:
            continue
        piece, stack = [], [start]
        seen.add(start)
        while stack:
            t = stack.pop()
            piece.append(t)
            for u in nb[t]:
                if u not in seen:
                    seen.add(u)
                    stack.append(u)
        pieces.append(sorted(piece))
    best = max(pieces, key=lambda p: (len(p), -p[0]))
    return best


def joint_pairs(table, kept):
    """Sorted (a, b) pairs, one per joint between kept tiles."""
    keep = set(kept)
    pairs = []
    for row in table["tiles"]:
        a = row["id"]
        for b in row["neighbours"]:
            if a < b and a in keep and b in keep:
                pairs.append((a, b))
    return sorted(pairs)


def tile_polygons(table):
    return {row["id"]: Polygon(row["polygon_mm"]) for row in table["tiles"]}


def shrunk_tiles(table, kept, gap):
    """Kept tiles with gap/2 taken off the edges they share with other kept tiles."""
    polys = tile_polygons(table)
    ids = list(kept)
    tree = STRtree([polys[i] for i in ids])
    grown = {i: polys[i].buffer(gap / 2, join_style="mitre", mitre_limit=20.0) for i in ids}
    out = {}
    for i in ids:
        near = [ids[k] for k in tree.query(polys[i].buffer(gap))]
        cutters = [grown[j] for j in near if j != i and polys[j].distance(polys[i]) < 1e-6]
        out[i] = polys[i].difference(unary_union(cutters)) if cutters else polys[i]
    return out


def expected_volume(table, settings):
    kept = largest_piece(table)
    tiles = shrunk_tiles(table, kept, settings["gap_mm"])
    area = sum(p.area for p in tiles.values())
    joints = len(joint_pairs(table, kept))
    neck = settings["hinge_mm"] * settings["gap_mm"] * settings["lamella_mm"]
    return area * settings["thickness_mm"] + joints * neck


def kept_bounds(table):
    """Bounds of the printed tiles as designed."""
    kept = largest_piece(table)
    polys = tile_polygons(table)
    return unary_union([polys[i] for i in kept]).bounds


def shrunk_bounds(table, gap):
    """Bounds of the printed footprints: where two tiles meet on the outline the gap takes a
    notch out of it, which can move an extreme vertex inwards."""
    kept = largest_piece(table)
    return unary_union(list(shrunk_tiles(table, kept, gap).values())).bounds

"""Graded sheets of designs chosen by a rule, checked independently from the files written.

The rule: of every motion class of a database (`isogami db motions --all --json`), the
design with the largest area ratio among those whose 6x6 finite sheet completes to one DOF
(`finite_covered` stored); classes with no such design are left out. Each is graded
(`isogami graded --allow-failed --out`) towards every target at every region, and the file
is checked with shapely, not with isogami's code: every closed tile a valid polygon, no two
closed tiles overlapping, and no two tiles overlapping in any of the path's written states
(their poses applied to the closed tiles). The table gives isogami's verdict, the outline
error it reports and the deepest overlap shapely finds (edge lengths).

Usage: python3 graded_survey.py ISOGAMI_BINARY DATABASE OUT_FOLDER [REGION,...] [TARGET;...]
"""

import json
import math
import subprocess
import sys
import time
from pathlib import Path

from shapely.geometry import Polygon

# Overlaps shallower than this (edge lengths) are not counted: isogami's own tolerance.
OVERLAP_TOLERANCE = 1e-5

TARGETS = ["disc", "ellipse:2,1", "polygon:1,0;0.5,0.866;-0.5,0.866;-1,0;-0.5,-0.866;0.5,-0.866",
           "polygon:0,0;2,0;2,1;1,1;1,2;0,2", "field"]


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, **kw)


def chosen_designs(binary, db):
    """The rule of the module's documentation: [(motion class index, spec, area ratio)]."""
    motions = json.loads(run([binary, "db", "motions", "--db", db, "--all", "--json"]).stdout)
    rows, offset = [], 0
    while True:
        page = json.loads(run([binary, "db", "designs", "--db", db, "--json", "--lead", "all",
                               "--limit", "1000", "--offset", str(offset)]).stdout)
        rows += page["rows"]
        offset += len(page["rows"])
        if not page["rows"] or offset >= page["total"]:
            break
    out = []
    for k, motion in enumerate(motions):
        topologies = {v["topology"] for v in motion["variants"]}
        mine = [r for r in rows
                if r["topology"] in topologies and r.get("finite_covered") is not None]
        if mine:
            best = max(mine, key=lambda r: (r["max_area_ratio"], r["spec"]))
            out.append((k + 1, best["spec"], best["max_area_ratio"]))
    return out


def field_target(area_ratio):
    """A ramp over the middle of the design's periodic range."""
    lo = 1 + 0.3 * (area_ratio - 1)
    hi = 1 + 0.7 * (area_ratio - 1)
    return f"field:{lo:.4f},{hi:.4f}"


def closed_polygons(sheet):
    nodes = sheet["nodes"]
    return [Polygon([nodes[n] for n in t["nodes"]]) for t in sheet["tiles"]]


def posed_polygons(sheet, poses):
    nodes = sheet["nodes"]
    out = []
    for t, p in zip(sheet["tiles"], poses):
        f = nodes[t["nodes"][0]]
        c, s = math.cos(p["theta"]), math.sin(p["theta"])
        out.append(Polygon([(p["x"] + c * (nodes[n][0] - f[0]) - s * (nodes[n][1] - f[1]),
                             p["y"] + s * (nodes[n][0] - f[0]) + c * (nodes[n][1] - f[1]))
                            for n in t["nodes"]]))
    return out


def deepest_overlap(polys):
    """Deepest overlap of two of `polys`: the intersection's largest inscribed distance,
    estimated as its area over half its perimeter (a sliver's width)."""
    worst = 0.0
    for i in range(len(polys)):
        for j in range(i + 1, len(polys)):
            a, b = polys[i], polys[j]
            if not a.bounds or a.bounds[2] < b.bounds[0] or b.bounds[2] < a.bounds[0] \
                    or a.bounds[3] < b.bounds[1] or b.bounds[3] < a.bounds[1]:
                continue
            x = a.intersection(b)
            if x.area > 0:
                worst = max(worst, 2 * x.area / x.length)
    return worst


def check(run_json):
    """Shapely's findings on a written graded sheet: (invalid closed tiles, deepest closed
    overlap, deepest overlap along the path)."""
    sheet = run_json["sheet"]
    closed = closed_polygons(sheet)
    invalid = sum(not p.is_valid for p in closed)
    valid = [p for p in closed if p.is_valid]
    path = max((deepest_overlap(posed_polygons(sheet, s["poses"]))
                for s in run_json["path"]["states"]), default=0.0)
    return invalid, deepest_overlap(valid), path


def main():
    binary, db, out = sys.argv[1], sys.argv[2], Path(sys.argv[3])
    regions = sys.argv[4].split(",") if len(sys.argv) > 4 else ["3x3", "5x5"]
    targets = sys.argv[5].split(";;") if len(sys.argv) > 5 else TARGETS
    out.mkdir(parents=True, exist_ok=True)
    designs = chosen_designs(binary, db)
    print(f"{len(designs)} designs, one per motion class whose finite sheet completes",
          flush=True)
    print("class\tspec\tregion\ttarget\texit\tseconds\topens\tfraction\terror\t"
          "invalid\tclosed_overlap\tpath_overlap\tagree", flush=True)
    for k, spec, ratio in designs:
        for region in regions:
            for target in targets:
                text = field_target(ratio) if target == "field" else target
                f = out / f"c{k}-{region}-{targets.index(target)}.json"
                clock = time.time()
                done = run([binary, "graded", "--design", spec, "--region", region,
                            "--target", text, "--allow-failed", "--out", str(f)])
                seconds = time.time() - clock
                if done.returncode != 0:
                    line = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else ""
                    print(f"{k}\t{spec}\t{region}\t{text}\t{done.returncode}\t{seconds:.1f}\t"
                          f"refused: {line}", flush=True)
                    continue
                d = json.loads(f.read_text())
                v = d["verdict"]
                invalid, closed_overlap, path_overlap = check(d)
                clean = invalid == 0 and closed_overlap <= OVERLAP_TOLERANCE \
                    and path_overlap <= OVERLAP_TOLERANCE
                # isogami may fail a sheet shapely finds clean (pins, DOF), never the reverse.
                agree = clean or not v["opens"]
                print(f"{k}\t{spec}\t{region}\t{text}\t0\t{seconds:.1f}\t{v['opens']}\t"
                      f"{v['target_fraction']:.3f}\t{v['error']:.4f}\t{invalid}\t"
                      f"{closed_overlap:.2e}\t{path_overlap:.2e}\t{agree}", flush=True)


if __name__ == "__main__":
    main()

"""Issue 21's measurement: stored designs whose behaviour jumps under a 1e-9 move of one shape
parameter. For every stored shape, compares the edge table of `BIN cell` at the shape and at
+-1e-9 of each parameter; for the designs on shapes whose table changes, deploys them there and
at the moved shapes and lists those whose max area ratio moves by more than 1e-6.

usage: python3 find_jumps.py BIN DB OUT.tsv   (BIN: an isogami binary, DB: its database)
Run with a build from before issue 21 on its catalogue to list the designs the issue names;
then check them with check_jumps.py and a current build."""
import json, sqlite3, subprocess, sys
from concurrent.futures import ThreadPoolExecutor
bin_, db, out = sys.argv[1:4]
rows = sqlite3.connect(db).execute("SELECT spec FROM designs WHERE origin='explored'").fetchall()
specs = [r[0] for r in rows]
def cell(fam, params, dims):
    r = subprocess.run([bin_, "cell", "--family", fam, "--params", ",".join(params), "--cell", dims, "--json"], capture_output=True, text=True)
    if r.returncode: return None
    d = json.loads(r.stdout)
    return [(e["tile_a"], e["edge_a"], e["tile_b"], e["edge_b"], tuple(e["offset"])) for e in d["edges"]]
def moves(params):
    for i, p in enumerate(params):
        for s in (-1e-9, 1e-9):
            q = list(params); q[i] = repr(float(p) + s); yield q
shapes = sorted({tuple(s.split(":")[:3]) for s in specs})
def shape_jumps(sh):
    fam, ps, dims = sh
    params = ps.split(",") if ps else []
    base = cell(fam, params, dims)
    return sh, any(cell(fam, q, dims) not in (None, base) for q in moves(params))
with ThreadPoolExecutor(2) as ex:
    jumping = {sh for sh, j in ex.map(shape_jumps, shapes) if j}
print(f"{len(jumping)} of {len(shapes)} shapes change their edge table", file=sys.stderr)
def area(spec):
    r = subprocess.run([bin_, "deploy", "--design", spec, "--json", "--frame-count", "40"], capture_output=True, text=True)
    if r.returncode: return None
    return json.loads(r.stdout)["max_area_ratio"]
def design_jumps(spec):
    fam, ps, dims, joints = spec.split(":")
    params = ps.split(",") if ps else []
    a0 = area(spec)
    worst = 0.0
    for q in moves(params):
        a = area(":".join([fam, ",".join(q), dims, joints]))
        worst = max(worst, float("inf") if (a is None) != (a0 is None) else (abs(a - a0) if a is not None else 0.0))
    return spec, a0, worst
cand = [s for s in specs if tuple(s.split(":")[:3]) in jumping]
with ThreadPoolExecutor(2) as ex:
    res = list(ex.map(design_jumps, cand))
bad = [r for r in res if r[2] > 1e-6]
print(f"{len(bad)} of {len(specs)} designs change area ratio by > 1e-6 (of {len(cand)} on jumping shapes)", file=sys.stderr)
with open(out, "w") as f:
    for s, a0, w in bad: f.write(f"{s}\t{a0}\t{w}\n")

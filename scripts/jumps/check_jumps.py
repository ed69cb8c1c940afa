"""Issue 21's check: for each design listed (spec in the first column of each line), deploy
with BIN at its shape and at +-1e-9 of every parameter; a design whose max area ratio moves by
more than 1e-6 is printed as JUMP with `BIN shape`'s class (the issue accepts it when the shape
is special: one DOF only on a subset of shapes).

usage: python3 check_jumps.py BIN LIST"""
import json, subprocess, sys
bin_, listing = sys.argv[1:3]
specs = [l.split("\t")[0] for l in open(listing) if l.strip()]
def area(spec):
    r = subprocess.run([bin_, "deploy", "--design", spec, "--json", "--frame-count", "2"], capture_output=True, text=True)
    return json.loads(r.stdout)["max_area_ratio"] if r.returncode == 0 else None
bad = special = 0
for n, spec in enumerate(specs):
    fam, ps, dims, joints = spec.split(":")
    params = ps.split(",") if ps else []
    a0 = area(spec); worst = 0.0
    for i, p in enumerate(params):
        for s in (-1e-9, 1e-9):
            q = list(params); q[i] = repr(float(p) + s)
            a = area(":".join([fam, ",".join(q), dims, joints]))
            worst = max(worst, float("inf") if (a is None) != (a0 is None) else (abs(a - a0) if a is not None else 0.0))
    if worst > 1e-6:
        r = subprocess.run([bin_, "shape", "--design", spec, "--json"], capture_output=True, text=True)
        cls = json.loads(r.stdout)["class"] if r.returncode == 0 else "error"
        bad += 1; special += cls == "special"
        print("JUMP", spec, a0, worst, cls, flush=True)
print(f"{bad} of {len(specs)} listed designs move by more than 1e-6 in area ratio under a 1e-9 "
      f"move; {special} of them are special shapes", flush=True)

"""`isogami export --t open` of every stored design, checked from the exported files: the
area ratio of the written state, from the exported tile poses (the lattice vectors are tile 0
of the next cell over minus tile 0 of the first, at t = 0 and at `--t open`), against the
largest area ratio the database stores. Prints the worst relative difference and every design
above 1e-6. Usage: python3 python/checks/open_state.py ISOGAMI_BINARY DATABASE"""
import json, subprocess, sys, sqlite3, tempfile, os
bin_, db = sys.argv[1], sys.argv[2]
rows = sqlite3.connect(db).execute("select spec, max_area_ratio from designs order by id").fetchall()
def lattice_area(spec, t, path):
    out = subprocess.run([bin_, "export", "--design", spec, "--t", t, "--format", "tiles-json",
                          "--patch", "2x2", "--raw", "--out", path], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(out.stderr.strip())
    d = json.load(open(path))
    pos = {(tuple(x["cell"]), x["tile"]): (x["pose"]["x"], x["pose"]["y"]) for x in d["tiles"]}
    o = pos[((0, 0), 0)]; a = pos[((0, 1), 0)]; b = pos[((1, 0), 0)]
    u = (a[0] - o[0], a[1] - o[1]); w = (b[0] - o[0], b[1] - o[1])
    return abs(u[0] * w[1] - u[1] * w[0]), d["t"]
worst = 0.0; bad = []
with tempfile.TemporaryDirectory() as tmp:
    p = os.path.join(tmp, "o.json")
    for spec, stored in rows:
        a0, _ = lattice_area(spec, "0", p)
        a1, t = lattice_area(spec, "open", p)
        err = abs(a1 / a0 - stored) / stored
        worst = max(worst, err)
        if err > 1e-6:
            bad.append((spec, a1 / a0, stored))
print(f"{len(rows)} designs, worst relative difference {worst:.2e}, {len(bad)} above 1e-6")
for b in bad[:10]:
    print(b)

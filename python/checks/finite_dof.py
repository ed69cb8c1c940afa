"""Degrees of freedom of a finite kirigami sheet with a free boundary, counted with numpy from
the files `isogami export` writes (issue 22, finite sheets).

Independent of the Rust code: nothing here uses the numbers of `isogami sheet`. The sheet is
read from two export formats of the same patch:

- ``kirigami-sim`` (a folder): ``vertices.txt`` holds every tile's polygon at the exported
  state (mm, one tile per line, clockwise) and ``constraints.txt`` every pin as
  ``i p j q`` (1-based): vertex p of tile i is pinned to vertex q of tile j. These are the
  only files that say *where* each pin is on both of its tiles, which the count needs.
- ``tiles-json``: the exported state's t (full precision), each tile's cell and index in
  the cell (to compare the tile set with `isogami sheet`'s) and each tile's neighbours (one
  entry per joint), which are checked against ``constraints.txt``.

The count: tiles are rigid bodies with unknowns (x, y, theta) each, lengths in units of the
mean edge length L of the exported polygons (so tolerances do not depend on the mm scale).
A pin between vertex P_a of tile a and vertex P_b of tile b gives two rows of the first-order
constraint

    (dx_a + dtheta_a * J (P_a - c_a)) - (dx_b + dtheta_b * J (P_b - c_b)) = 0,

with c the tile's area centroid and J the rotation by +90 degrees. The singular values of
this dense Jacobian (numpy.linalg.svd) give its rank: values at most ``rel_tol`` times the
largest one count as zero, and the gap between the largest zero and the smallest non-zero
value (in decades) is reported so an ambiguous count shows itself. Then

    DOF = 3 * tiles - rank - 3 * pieces,

the motions left after taking out each piece's rigid motion (pieces: connected components of
the tiles by joints; a tile without joints is a piece of its own).

Script mode loops over many specs and compares with `isogami sheet`:

    python3 python/checks/finite_dof.py --bin target/release/isogami --specs specs.txt \
        --region 6x6 --t 0.3 [--completed]
"""

import argparse
import json
import math
import re
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

# Singular values at most this share of the largest count as zero. Exported coordinates are
# printed with full double precision, so the zeros sit near 1e-15 and the non-zeros of the
# designs checked far above 1e-8 (see the gap each count reports).
REL_TOL = 1e-9

# A count whose gap is below this many decades is reported as doubtful.
MIN_GAP_DECADES = 3.0


# ---------------------------------------------------------------------------------------------
# Reading the export files


def read_kirigami_sim(folder):
    """Polygons (list of (n, 2) arrays, counter-clockwise, mm) and pins (list of
    (tile_a, vertex_a, tile_b, vertex_b), 0-based, vertex indices into those polygons)."""
    folder = Path(folder)
    polys = []
    for line in (folder / "vertices.txt").read_text().splitlines():
        if not line.strip():
            continue
        xy = np.array([float(v) for v in line.split()], dtype=float)
        assert xy.size % 2 == 0 and xy.size >= 6, f"bad vertex line: {line!r}"
        polys.append(xy.reshape(-1, 2))
    # The file lists vertices clockwise; reverse to counter-clockwise, keeping a map from the
    # file's vertex index to ours: file vertex p (0-based) is vertex (n - p) % n of the
    # reversed polygon.
    ccw = [np.roll(p[::-1], 1, axis=0) for p in polys]
    pins = []
    for line in (folder / "constraints.txt").read_text().splitlines():
        if not line.strip():
            continue
        i, p, j, q = (int(v) for v in line.split())
        a, b = i - 1, j - 1
        na, nb = len(polys[a]), len(polys[b])
        pins.append((a, (na - (p - 1)) % na, b, (nb - (q - 1)) % nb))
    return ccw, pins


def read_tile_table(path):
    with open(path) as f:
        return json.load(f)


def check_files_agree(polys, pins, table, tol=1e-9):
    """The two formats describe the same patch: same tiles, same polygons, and each tile's
    neighbours are the pins' other tiles. Returns a list of problems (empty when they agree)."""
    problems = []
    rows = table["tiles"]
    if len(rows) != len(polys):
        return [f"tile count: kirigami-sim {len(polys)}, tiles-json {len(rows)}"]
    nb = [[] for _ in polys]
    for a, _, b, _ in pins:
        nb[a].append(b)
        nb[b].append(a)
    for k, row in enumerate(rows):
        if row["id"] != k:
            problems.append(f"tiles-json row {k} has id {row['id']}")
        poly = np.asarray(row["polygon_mm"], dtype=float)
        if poly.shape != polys[k].shape or np.max(np.abs(poly - polys[k])) > tol * (
            1.0 + np.max(np.abs(poly))
        ):
            problems.append(f"tile {k}: polygons differ between the formats")
        if sorted(nb[k]) != sorted(row["neighbours"]):
            problems.append(f"tile {k}: neighbours {sorted(row['neighbours'])} vs pins {sorted(nb[k])}")
    return problems


# ---------------------------------------------------------------------------------------------
# The count


def area_centroid(poly):
    x, y = poly[:, 0], poly[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = cross.sum() / 2.0
    if abs(area) < 1e-12 * max(1.0, np.abs(poly).max()) ** 2:
        return poly.mean(axis=0)
    cx = ((x + xn) * cross).sum() / (6.0 * area)
    cy = ((y + yn) * cross).sum() / (6.0 * area)
    return np.array([cx, cy])


def mean_edge_length(polys):
    lengths = np.concatenate([np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1) for p in polys])
    return float(lengths.mean())


def pieces_of(n, pins):
    """Connected components of n tiles joined by the pins (union-find)."""
    parent = list(range(n))

    def find(k):
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for a, _, b, _ in pins:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[ra] = rb
    return len({find(k) for k in range(n)})


def constraint_jacobian(polys, pins, scale=None):
    """Dense Jacobian (2 * pins) x (3 * tiles) of the pin constraints, lengths over `scale`
    (default: the mean edge length). Columns of tile k: 3k (x), 3k + 1 (y), 3k + 2 (theta)."""
    scale = mean_edge_length(polys) if scale is None else scale
    centres = [area_centroid(p) for p in polys]
    jac = np.zeros((2 * len(pins), 3 * len(polys)))
    for r, (a, va, b, vb) in enumerate(pins):
        for tile, vertex, sign in ((a, va, 1.0), (b, vb, -1.0)):
            rx, ry = (polys[tile][vertex] - centres[tile]) / scale
            c = 3 * tile
            jac[2 * r, c] += sign
            jac[2 * r + 1, c + 1] += sign
            jac[2 * r, c + 2] += -sign * ry
            jac[2 * r + 1, c + 2] += sign * rx
    return jac


@dataclass
class DofCount:
    tiles: int
    joints: int
    pieces: int
    rank: int
    # 3 * tiles - rank - 3 * pieces: every piece's rigid motion taken out.
    dof: int
    # Largest singular value, and the singular values either side of rel_tol * largest (all
    # relative to the largest). largest_zero is 0 when every zero is structural (fewer rows
    # than columns and no computed value below the threshold).
    s_max: float
    largest_zero: float
    smallest_nonzero: float
    gap_decades: float
    # Largest distance between the two vertices of a pin, over the mean edge length.
    pin_residual: float
    mean_edge_mm: float
    # "svd": numpy's dense SVD of J; "sparse": the smallest eigenvalues of JᵀJ by block
    # inverse iteration on scipy's SuperLU factor, for sheets too large for a dense SVD.
    method: str = "svd"

    @property
    def dof_one_frame(self):
        """3 * tiles - rank - 3: only the whole sheet's rigid motion taken out, so a piece
        other than the one held moves freely (3 more per extra piece). `isogami sheet`
        counts this way ("the largest piece plus three per other piece"); the two agree for
        a sheet in one piece."""
        return self.dof + 3 * (self.pieces - 1)

    @property
    def doubtful(self):
        return self.gap_decades < MIN_GAP_DECADES


# The rank threshold of the sparse method (relative singular value). It works on JᵀJ, whose
# rounding floor is about eps times its largest eigenvalue, i.e. sqrt(eps) ~ 1.5e-8 in singular
# values: the threshold sits two decades above that, and two below the smallest non-zero
# singular value seen on any completed sheet (1.3e-4).
SPARSE_REL_TOL = 1e-6

# Sheets with more unknowns than this are counted by the sparse method (a dense SVD of a
# 10x10 sheet of a large cell, ~3000 columns, takes half a minute).
DENSE_MAX_COLUMNS = 1500


def sparse_jacobian(polys, pins, scale):
    """The Jacobian of `constraint_jacobian`, as a scipy CSR matrix."""
    from scipy.sparse import coo_matrix

    centres = [area_centroid(p) for p in polys]
    rows, cols, vals = [], [], []
    for r, (a, va, b, vb) in enumerate(pins):
        for tile, vertex, sign in ((a, va, 1.0), (b, vb, -1.0)):
            rx, ry = (polys[tile][vertex] - centres[tile]) / scale
            c = 3 * tile
            rows += [2 * r, 2 * r + 1, 2 * r, 2 * r + 1]
            cols += [c, c + 1, c + 2, c + 2]
            vals += [sign, sign, -sign * ry, sign * rx]
    return coo_matrix((vals, (rows, cols)), shape=(2 * len(pins), 3 * len(polys))).tocsr()


def small_singular_values(jac, seed=0):
    """(largest singular value, the smallest ones ascending) of sparse `jac`: square roots of
    JᵀJ's eigenvalues, the largest by Lanczos, the smallest by block inverse iteration — a
    random block solved six times with a SuperLU factor of JᵀJ + εI (ε = 1e-12 of the largest
    eigenvalue, so the factor exists; a kernel direction grows by (λ + ε)/ε per solve against
    a mode of eigenvalue λ, 1e4 for the smallest non-zero ones seen, λ ~ 1e-8 of the largest),
    orthonormalised after each, then Rayleigh–Ritz. A block, not Lanczos: the kernel is a
    multiple eigenvalue, and single-vector Lanczos finds a multiple eigenvalue once. The
    block doubles until it holds at least two values above the rank threshold."""
    from scipy.sparse import identity
    from scipy.sparse.linalg import eigsh, splu

    gram = (jac.T @ jac).tocsc()
    size = gram.shape[0]
    top = float(eigsh(gram, k=1, which="LA", return_eigenvectors=False)[0])
    lu = splu((gram + 1e-12 * top * identity(size, format="csc")).tocsc())
    rng = np.random.default_rng(seed)
    k = 8
    while True:
        k = min(k, size)
        x = rng.standard_normal((size, k))
        for _ in range(6):
            x, _ = np.linalg.qr(lu.solve(x))
        ritz = x.T @ (gram @ x)
        vals = np.clip(np.linalg.eigvalsh(0.5 * (ritz + ritz.T)), 0.0, None)
        if (np.sqrt(vals / top) > SPARSE_REL_TOL).sum() >= 2 or k == size:
            return math.sqrt(top), np.sqrt(vals)
        k *= 2


def count_dof(polys, pins, rel_tol=REL_TOL, method=None):
    """Free-boundary degrees of freedom of tiles `polys` joined by `pins` (see the module docs).
    `method` "svd" (numpy's dense SVD) or "sparse" (`small_singular_values`); by default the
    dense SVD up to DENSE_MAX_COLUMNS unknowns."""
    n = len(polys)
    scale = mean_edge_length(polys)
    residual = max(
        (float(np.linalg.norm(polys[a][va] - polys[b][vb])) / scale for a, va, b, vb in pins),
        default=0.0,
    )
    pieces = pieces_of(n, pins)
    if not pins:
        return DofCount(n, len(pins), pieces, 0, 3 * n - 3 * pieces, 0.0, 0.0, math.inf,
                        math.inf, residual, scale)
    method = method or ("svd" if 3 * n <= DENSE_MAX_COLUMNS else "sparse")
    if method == "svd":
        s = np.linalg.svd(constraint_jacobian(polys, pins, scale), compute_uv=False)
        s_max = float(s[0])
        rel = s / s_max if s_max > 0 else s
        nonzero = rel > rel_tol
        rank = int(nonzero.sum())
    else:
        s_max, small = small_singular_values(sparse_jacobian(polys, pins, scale))
        rel = small / s_max
        nonzero = rel > max(rel_tol, SPARSE_REL_TOL)
        # The values not computed are all above the smallest computed non-zero one.
        rank = 3 * n - int((~nonzero).sum())
    largest_zero = float(rel[~nonzero].max()) if (~nonzero).any() else 0.0
    smallest_nonzero = float(rel[nonzero].min()) if nonzero.any() else 0.0
    if largest_zero > 0 and smallest_nonzero > 0:
        gap = math.log10(smallest_nonzero / largest_zero)
    else:
        gap = math.inf
    dof = 3 * n - rank - 3 * pieces
    return DofCount(n, len(pins), pieces, rank, dof, s_max, largest_zero, smallest_nonzero,
                    gap, residual, scale, method)


# ---------------------------------------------------------------------------------------------
# Running isogami


_HELP = {}


def export_flags(bin_path):
    """Long flags `isogami export --help` lists (cached per binary)."""
    key = str(bin_path)
    if key not in _HELP:
        done = subprocess.run([key, "export", "--help"], capture_output=True, text=True,
                              timeout=60)
        _HELP[key] = set(re.findall(r"^\s*(?:-\w, )?(--[a-z][a-z0-9-]*)", done.stdout, re.M))
    return _HELP[key]


def sheet_mode_flags(bin_path, completed):
    """Export flags that pick the raw rectangle or the completed sheet.

    Raw: `--raw` when the export knows it (once it writes the completed sheet by default),
    else nothing (the export has always written the raw rectangle). Completed: `--completed`
    or `--complete` if the export grows such a flag, else nothing when it lists `--raw` (the
    completed sheet is then the default); an export without either cannot write the completed
    sheet, which is an error rather than a silent comparison of the raw rectangle."""
    flags = export_flags(bin_path)
    if not completed:
        return ["--raw"] if "--raw" in flags else []
    for f in ("--completed", "--complete"):
        if f in flags:
            return [f]
    if "--raw" in flags:
        return []
    raise RuntimeError(
        f"{bin_path} export cannot write the completed sheet yet (its --help lists neither "
        "--raw nor --completed)"
    )


def run(args, timeout=300):
    for attempt in range(30):
        if Path(args[0]).exists():
            break
        time.sleep(2)  # the binary may be being rebuilt
    return subprocess.run([str(a) for a in args], capture_output=True, text=True,
                          timeout=timeout)


def export_sheet(bin_path, design, region, t, folder, completed=False):
    """Exports kirigami-sim and tiles-json of the sheet into `folder`; returns
    (polys, pins, table)."""
    folder = Path(folder)
    mode = sheet_mode_flags(bin_path, completed)
    out = {"kirigami-sim": folder / "ks", "tiles-json": folder / "tiles.json"}
    for fmt, path in out.items():
        done = run([bin_path, "export", "--design", design, "--format", fmt, "--out", path,
                    "--patch", region, "--t", t, *mode])
        if done.returncode != 0:
            raise RuntimeError(f"export {fmt} of {design}: {done.stderr.strip()}")
    polys, pins = read_kirigami_sim(out["kirigami-sim"])
    table = read_tile_table(out["tiles-json"])
    return polys, pins, table


def isogami_sheet(bin_path, design, region, t, raw=True):
    """`isogami sheet ... --json`, parsed."""
    args = [bin_path, "sheet", "--design", design, "--region", region, "--t", repr(float(t)),
            "--json"]
    if raw:
        args.append("--raw")
    done = run(args)
    if done.returncode != 0:
        raise RuntimeError(f"sheet of {design}: {done.stderr.strip()}")
    return json.loads(done.stdout)


def tile_keys(tiles):
    """Sorted (cell_i, cell_j, tile) of a list of tiles with `cell` and `tile` fields."""
    return sorted((r["cell"][0], r["cell"][1], r["tile"]) for r in tiles)


def compare(bin_path, design, region, t, folder, completed=False):
    """Counts the exported sheet's DOF and compares with `isogami sheet`. The export picks
    the accepted state nearest t; `isogami sheet` is then asked at the exported state's exact
    t, so both count the same state (the sheet command never takes the closed state, which
    the export can when the trajectory's first step is far from t).

    `isogami sheet` takes out one rigid motion for the whole sheet ("the largest piece plus
    three per other piece"), so its dof is compared with ``dof_one_frame``, which equals
    ``dof`` (3 * tiles - rank - 3 * pieces) for a sheet in one piece.

    With `completed`, the export writes the completion `isogami sheet` makes (the export
    completes at the periodic state nearest t = 0.3 whatever its --t, so a --t far from 0.3
    shows up as a different tile set)."""
    polys, pins, table = export_sheet(bin_path, design, region, t, folder, completed)
    problems = check_files_agree(polys, pins, table)
    mine = count_dof(polys, pins)
    t_export = float(table["t"])
    counted = dict(asdict(mine), dof_one_frame=mine.dof_one_frame)
    row = {"spec": design, "t_export": t_export, "numpy": counted, "problems": problems}
    if t_export <= 0.0:
        row["problems"].append(f"the export picked the closed state for --t {t}")
        return row
    report = isogami_sheet(bin_path, design, region, t_export, raw=not completed)
    if completed:
        comp = report.get("completion")
        if comp is None:
            row["problems"].append("isogami sheet made no completion")
            return row
        theirs, their_tiles = comp["mobility"], comp["sheet"]["tiles"]
        rep = comp["report"]
        row["completion"] = {"covered": rep["covered_fraction"], "removed": len(rep["removed"]),
                             "added": len(rep["added"]), "grown": rep["grown"]}
    else:
        theirs, their_tiles = report["raw_mobility"], report["raw"]["tiles"]
    row["t_sheet"] = float(report["t"])
    row["isogami"] = {k: theirs[k] for k in ("tiles", "joints", "pieces", "dof", "gap_decades")}
    if row["t_sheet"] != t_export:
        row["problems"].append(f"states differ: export t {t_export}, sheet t {row['t_sheet']}")
    if theirs["tiles"] != mine.tiles or theirs["joints"] != mine.joints:
        row["problems"].append(
            f"size differs: export {mine.tiles} tiles/{mine.joints} joints, sheet "
            f"{theirs['tiles']}/{theirs['joints']}"
        )
    elif tile_keys(table["tiles"]) != tile_keys(their_tiles):
        row["problems"].append("same number of tiles but not the same (cell, tile) set")
    if theirs["pieces"] != mine.pieces:
        row["problems"].append(f"pieces: numpy {mine.pieces}, sheet {theirs['pieces']}")
    row["agree"] = mine.dof_one_frame == theirs["dof"]
    return row


# ---------------------------------------------------------------------------------------------
# Script mode


def fmt_gap(g):
    return "inf" if math.isinf(g) else f"{g:.1f}"


def completion_table(done, errors):
    """What completion did over the compared sheets, and why the others have none (the
    export's refusal, grouped by its reason with the numbers taken out)."""
    comp = [r["completion"] for r in done if "completion" in r]
    if comp:
        covered = sorted(c["covered"] for c in comp)
        whole = sum(1 for c in comp if c["removed"] == 0 and c["added"] == 0)
        pruned = sum(1 for c in comp if c["removed"] > 0)
        grown = sum(1 for c in comp if c["grown"])
        print(f"# completion: {len(comp)} sheets; {whole} the whole region as it is, {pruned} "
              f"pruned, {grown} grown first; covered fraction median "
              f"{covered[len(covered) // 2]:.3f}, worst {covered[0]:.3f}")
    reasons = {}
    for r in errors:
        text = r["error"].split("no one-DOF sheet in this region: ")[-1]
        kind = ("isostatic cell (3n − 2p = 0): every finite sheet flops along its boundary"
                if "3n − 2p = 0" in text else re.sub(r"[0-9.]+", "N", text.split(";")[0]))
        reasons[kind] = reasons.get(kind, 0) + 1
    for kind, count in sorted(reasons.items(), key=lambda kv: -kv[1]):
        print(f"# no one-DOF sheet: {count} × {kind}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bin", required=True, help="the isogami binary")
    ap.add_argument("--specs", required=True, help="file of design specs, one per line")
    ap.add_argument("--region", default="6x6", help="RxC cells (the export's --patch)")
    ap.add_argument("--t", default="0.3", help="the state asked for")
    ap.add_argument("--completed", action="store_true",
                    help="export and compare the completed sheet instead of the raw rectangle")
    ap.add_argument("--limit", type=int, default=0, help="only the first N specs")
    ap.add_argument("--json", help="also write every row to this JSON file")
    opts = ap.parse_args(argv)

    specs = [s.strip() for s in Path(opts.specs).read_text().splitlines()]
    specs = [s for s in specs if s and not s.startswith("#")]
    if opts.limit:
        specs = specs[: opts.limit]
    try:
        mode = sheet_mode_flags(opts.bin, opts.completed)
    except RuntimeError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    what = "completion.mobility.dof" if opts.completed else "raw_mobility.dof"
    print(f"# {len(specs)} specs, region {opts.region}, t {opts.t}, against {what}; "
          f"rank tolerance {REL_TOL:g} x largest singular value; export flags "
          f"{' '.join(mode) or '(none)'}")
    print(f"{'spec':<58} {'tiles':>6} {'dof_numpy':>9} {'dof_isogami':>11} {'gap':>6}  note")
    print("# dof_numpy: 3 * tiles - rank - 3 (isogami's convention; minus 3 more per extra "
          "piece is noted when a sheet falls apart); gap: decades at the rank threshold")
    rows, start = [], time.time()
    with tempfile.TemporaryDirectory(prefix="finite-dof-") as tmp:
        for k, spec in enumerate(specs):
            folder = Path(tmp) / f"s{k}"
            folder.mkdir()
            try:
                row = compare(opts.bin, spec, opts.region, opts.t, folder, opts.completed)
            except (RuntimeError, subprocess.TimeoutExpired, ValueError, AssertionError) as e:
                row = {"spec": spec, "error": str(e).splitlines()[0] if str(e) else repr(e)}
            rows.append(row)
            if "error" in row:
                print(f"{spec:<58} {'':>6} {'':>9} {'':>11} {'':>6}  error: {row['error']}")
                continue
            mine = row["numpy"]
            theirs = row.get("isogami", {}).get("dof", "-")
            notes = list(row["problems"])
            if "isogami" in row and not row["agree"]:
                notes.insert(0, "DISAGREE")
            if mine["pieces"] > 1:
                notes.append(f"{mine['pieces']} pieces: 3n-rank-3*pieces = {mine['dof']}")
            if mine["gap_decades"] < MIN_GAP_DECADES:
                notes.append("doubtful gap")
            print(f"{spec:<58} {mine['tiles']:>6} {mine['dof_one_frame']:>9} {theirs!s:>11} "
                  f"{fmt_gap(mine['gap_decades']):>6}  {'; '.join(notes)}")
    done = [r for r in rows if "isogami" in r]
    agree = [r for r in done if r["agree"]]
    disagree = [r for r in done if not r["agree"]]
    errors = [r for r in rows if "error" in r]
    other = [r for r in rows if "error" not in r and "isogami" not in r]
    flagged = [r for r in done if r["problems"]]
    gaps = sorted(r["numpy"]["gap_decades"] for r in done)
    zeros = [r["numpy"]["largest_zero"] for r in done]
    nonzeros = [r["numpy"]["smallest_nonzero"] for r in done]
    print()
    print(f"# compared {len(done)} of {len(specs)}: {len(agree)} agree, {len(disagree)} disagree; "
          f"{len(errors)} errors, {len(other)} not compared, {len(flagged)} with file/state "
          f"problems; {time.time() - start:.1f} s")
    if done:
        print(f"# gap (decades) min {fmt_gap(gaps[0])}, median {fmt_gap(gaps[len(gaps) // 2])}; "
              f"largest zero {max(zeros):.2e}, smallest non-zero {min(nonzeros):.2e} "
              f"(relative to the largest singular value); largest pin residual "
              f"{max(r['numpy']['pin_residual'] for r in done):.1e} L")
        hist = {}
        for r in done:
            key = (r["numpy"]["dof_one_frame"], r["isogami"]["dof"])
            hist[key] = hist.get(key, 0) + 1
        print("# (dof_numpy, dof_isogami): count  " +
              ", ".join(f"{k}: {v}" for k, v in sorted(hist.items())))
    if opts.completed:
        completion_table(done, errors)
    for r in disagree:
        flag = "" if opts.completed else " --raw"
        print(f"# disagree: {r['spec']}  numpy {r['numpy']['dof_one_frame']} "
              f"(rank {r['numpy']['rank']}, pieces {r['numpy']['pieces']}, "
              f"gap {fmt_gap(r['numpy']['gap_decades'])}), isogami {r['isogami']['dof']} "
              f"(gap {r['isogami']['gap_decades']}); reproduce: isogami sheet --design "
              f"'{r['spec']}' --region {opts.region} --t {r['t_export']!r}{flag} --json")
    if opts.json:
        Path(opts.json).write_text(json.dumps(rows, indent=1, default=float))
    return 1 if disagree or errors else 0


if __name__ == "__main__":
    sys.exit(main())

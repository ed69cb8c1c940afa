#!/usr/bin/env python3
"""Headless driver for Liu, Choi & Mahadevan's kirigami_sim (pymunk spring simulator).

Builds their `simulation.Simulation` from the four files `isogami export --format kirigami-sim`
writes, steps `sim.space.step(dt)` exactly as their run_simulation.py does (25 frames/s, 10
sub-steps per frame, auto_expand springs on the hull tiles), and records per frame the area of
the convex hull of all tile vertices (from body pose and each tile's polygon) and the largest
tile rotation. No kirigami_sim code lives here: it is read from the git mirror at run time.

    run_ksim.py DIR [--seconds 60] [--out result.json] [--hull tiles|vertices]
                    [--vertex-multiplier 0.5] [--spring-stiffness 80] [--spring-damping 1000]
"""
import argparse, json, math, os, subprocess, sys, time

MIRROR = "/work/.mirror/lliu12+kirigami_sim/repo"
FPS, ITERATIONS = 25, 10  # as run_simulation.py


def their_source(mirror, dest):
    """Check out simulation.py / utils.py from the mirror (read-only) and put them on sys.path."""
    commit = subprocess.check_output(["git", "-C", mirror, "rev-parse", "HEAD"], text=True).strip()
    d = os.path.join(dest, commit)
    os.makedirs(d, exist_ok=True)
    for f in ("simulation.py", "utils.py"):
        p = os.path.join(d, f)
        if not os.path.exists(p):
            with open(p, "w") as fh:
                fh.write(subprocess.check_output(["git", "-C", mirror, "show", f"HEAD:{f}"], text=True))
    sys.path.insert(0, d)
    return commit


def hull_area(pts):
    """Area of the convex hull of 2-D points (Andrew's monotone chain + shoelace)."""
    pts = sorted(set(pts))
    if len(pts) < 3:
        return 0.0
    cross = lambda o, a, b: (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lo, up = [], []
    for p in pts:
        while len(lo) >= 2 and cross(lo[-2], lo[-1], p) <= 0:
            lo.pop()
        lo.append(p)
    for p in reversed(pts):
        while len(up) >= 2 and cross(up[-2], up[-1], p) <= 0:
            up.pop()
        up.append(p)
    h = lo[:-1] + up[:-1]
    return 0.5 * abs(sum(h[i][0] * h[i - 1][1] - h[i - 1][0] * h[i][1] for i in range(len(h))))


def world_vertices(sim):
    out = []
    for shape in sim.center_shapes:
        b = shape.body
        for v in shape.get_vertices():  # local polygon (pymunk keeps its convex hull)
            w = v.rotated(b.angle) + b.position
            out.append((w.x, w.y))
    return out


def pin_error(sim):
    """Largest violation of the tile-tile pin joints (distance change), in px."""
    worst = 0.0
    for pj in sim.tile_pinjoints:
        a = pj.a.position + pj.anchor_a.rotated(pj.a.angle)
        b = pj.b.position + pj.anchor_b.rotated(pj.b.angle)
        worst = max(worst, abs((a - b).length - pj.distance))
    return worst


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir", help="folder written by `isogami export --format kirigami-sim`")
    ap.add_argument("--seconds", type=float, default=60.0, help="simulated time limit")
    ap.add_argument("--window", type=float, default=2.0, help="plateau window, simulated s")
    ap.add_argument("--tol", type=float, default=1e-3, help="plateau: relative hull-area change over the window")
    ap.add_argument("--extra", type=float, default=4.0, help="simulated s to keep running after the plateau")
    ap.add_argument("--hull", choices=["tiles", "vertices"], default="tiles",
                    help="springs on hull_tiles.txt (default) or on the tiles of hull_vertices.txt")
    ap.add_argument("--vertex-multiplier", type=float, default=None)
    ap.add_argument("--spring-stiffness", type=int, default=None)
    ap.add_argument("--spring-damping", type=int, default=None)
    ap.add_argument("--mirror", default=MIRROR)
    ap.add_argument("--src-cache", default="/tmp/kirigami_sim_src")
    ap.add_argument("--out", help="write the time series and summary as JSON")
    a = ap.parse_args()

    os.environ.setdefault("SDL_VIDEODRIVER", "dummy")  # their modules import pygame
    os.environ.setdefault("MPLBACKEND", "Agg")
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    commit = their_source(a.mirror, a.src_cache)
    import pymunk
    import utils  # theirs
    from simulation import Simulation  # theirs

    f = lambda n: os.path.join(a.dir, n)
    argv = ["--vertices_file", f("vertices.txt"), "--constraints_file", f("constraints.txt"),
            "--auto_expand", "true", "--calculate_area_perim", "false"]
    argv += ["--hull_tiles_file", f("hull_tiles.txt")] if a.hull == "tiles" else ["--hull_vertices_file", f("hull_vertices.txt")]
    if a.vertex_multiplier is not None: argv += ["--vertex_multiplier", str(a.vertex_multiplier)]
    if a.spring_stiffness is not None: argv += ["--spring_stiffness", str(a.spring_stiffness)]
    if a.spring_damping is not None: argv += ["--spring_damping", str(a.spring_damping)]
    sys.argv = ["run_simulation.py"] + argv
    args = utils.parse_args()  # their defaults for everything not given
    utils.check_args(args)
    params = vars(args)

    # as run_simulation.py
    tile_vertices = utils.read_vertices_file(args.vertices_file, params)
    constraints = utils.read_constraints_file(args.constraints_file)
    hull_vertices = hull_tiles = None
    if args.hull_vertices_file is not None:
        hull_vertices = utils.read_hull_vertices_file(args.hull_vertices_file)
        hull_tiles = list(set(list(zip(*hull_vertices))[0]))
    else:
        hull_tiles = utils.read_hull_tiles_file(args.hull_tiles_file)
    sim = Simulation(tile_vertices, constraints, params, hull_vertices, hull_tiles)

    dt = 1.0 / FPS / ITERATIONS
    frame_dt = 1.0 / FPS
    a0 = hull_area(world_vertices(sim))
    edge = sum(math.dist(t[i], t[i - 1]) for t in tile_vertices for i in range(len(t))) / sum(len(t) for t in tile_vertices)
    win = int(round(a.window * FPS))
    inner = [b for i, b in enumerate(sim.center_bodies) if i not in set(hull_tiles)]  # off the patch boundary
    series = []  # (t, hull ratio, max |rotation| °, pin error / edge, median |rotation| °, max |rotation| ° off the boundary)
    plateau_t = None
    stop_at = int(round(a.seconds * FPS))
    wall = time.time()
    for k in range(1, stop_at + 1):
        for _ in range(ITERATIONS):
            sim.space.step(dt)
        r = hull_area(world_vertices(sim)) / a0
        rots = sorted(abs(math.degrees(b.angle)) for b in sim.center_bodies)
        rot_in = max((abs(math.degrees(b.angle)) for b in inner), default=0.0)
        series.append((k * frame_dt, r, rots[-1], pin_error(sim) / edge, rots[len(rots) // 2], rot_in))
        if plateau_t is None and k > win:
            w = [s[1] for s in series[-win - 1:]]
            if (max(w) - min(w)) < a.tol * w[-1]:
                plateau_t = series[-win - 1][0]  # start of the flat window
                stop_at = min(stop_at, k + int(round(a.extra * FPS)))
        if k >= stop_at:
            break
    contacts = set()
    for s in sim.center_shapes:
        s.body.each_arbiter(lambda arb: contacts.add(frozenset(id(x) for x in arb.shapes)) if arb.contact_point_set.points else None)
    pl = [s for s in series if plateau_t is not None and s[0] >= plateau_t] or series[-win:]
    summary = {
        "dir": os.path.abspath(a.dir), "kirigami_sim_commit": commit, "pymunk": pymunk.version,
        "params": {k: params[k] for k in ("vertex_multiplier", "spring_stiffness", "spring_damping", "x_offset", "y_offset")},
        "hull": a.hull, "tiles": len(tile_vertices), "pins": len(constraints), "spring_tiles": len(sim.expansion_springs),
        "edge_px": edge, "dt": dt, "simulated_s": series[-1][0], "wall_s": round(time.time() - wall, 1),
        "plateau_t": plateau_t,
        "plateau_hull_ratio": pl[-1][1], "max_hull_ratio": max(s[1] for s in series),
        "plateau_max_rotation_deg": pl[-1][2], "max_rotation_deg": max(s[2] for s in series),
        "plateau_median_rotation_deg": pl[-1][4], "plateau_max_inner_rotation_deg": pl[-1][5],
        "plateau_max_pin_error_per_edge": pl[-1][3], "max_pin_error_per_edge": max(s[3] for s in series),
        "contact_pairs_at_end": len(contacts),
    }
    print(json.dumps(summary, indent=1))
    if a.out:
        final = [[[w.x, w.y] for w in (v.rotated(s.body.angle) + s.body.position for v in s.get_vertices())]
                 for s in sim.center_shapes]  # per tile, pymunk's (convex) polygon
        with open(a.out, "w") as fh:
            json.dump({"summary": summary, "series": series, "final_vertices": final,
                   "final_angles_deg": [math.degrees(b.angle) for b in sim.center_bodies],
                   "hull_tiles": hull_tiles}, fh)


if __name__ == "__main__":
    main()

"""Surveys of finite sheets over many designs, through `isogami sheet --json` (issue 22).

    python3 scripts/finite/survey.py complete --bin target/release/isogami --specs specs.txt --region 6x6
    python3 scripts/finite/survey.py deploy   --bin ... --specs ... --region 6x6 [--every 8]
    python3 scripts/finite/survey.py pull     --bin ... --specs ... --region 4x4 [--raw]

`specs.txt` holds one design spec per line (e.g. the `spec` column of
`isogami db query --db full.db --json`). `complete` tabulates the raw and completed sheets'
DOF, how many were pruned or grown, the covered fraction (median, worst) and the refusals
with their reasons; `deploy` the finite deployment of the completed sheet against the
periodic one; `pull` the pulled sheet's deviation from the periodic motion. `--json FILE`
keeps every row. Only the standard library: the numbers are isogami's own; the independent
count is python/checks/finite_dof.py.
"""

import argparse
import collections
import json
import statistics
import subprocess
import sys
import time


def sheet(binary, spec, region, *flags):
    args = [binary, "sheet", "--design", spec, "--region", region, *flags, "--json"]
    start = time.time()
    done = subprocess.run(args, capture_output=True, text=True)
    took = time.time() - start
    if done.returncode != 0:
        return {"spec": spec, "error": done.stderr.strip(), "time": took}
    return {"spec": spec, "out": json.loads(done.stdout), "time": took}


def complete_row(r):
    d = r["out"]
    c = d["completion"]
    return {
        "raw_dof": d["raw_mobility"]["dof"],
        "dof": c["mobility"]["dof"],
        "follows": c["mobility"]["follows_periodic"],
        "covered": c["report"]["covered_fraction"],
        "removed": len(c["report"]["removed"]),
        "added": len(c["report"]["added"]),
        "grown": c["report"]["grown"],
        "gap": c["mobility"]["gap_decades"],
    }


def deploy_row(r):
    d = r["out"]
    a = d["agreement"]
    return {
        "end": d["end_reason"]["kind"],
        "steps": d["steps"],
        "periodic_steps": d["periodic"]["steps"],
        "end_hull": d["end"]["hull_area_ratio"],
        "periodic_hull": d["periodic"]["measures"]["hull_area_ratio"],
        "deviation": a["max_position_deviation"],
        "one_dof_throughout": d["one_dof_throughout"],
    }


def pull_row(r):
    d = r["out"]
    return {
        "dof": d["dof"],
        "end": d["end_reason"]["kind"],
        "extension": d["extension"],
        "max_deviation": d["max_deviation"],
        "leaving": len(d["leaving"]),
        "tiles": len(d["frames"][0]["poses"]),
        "leaves_dof": (d["leaves"] or {}).get("dof"),
    }


def summary(kind, rows):
    ok = [r for r in rows if "error" not in r]
    bad = [r for r in rows if "error" in r]
    times = sorted(r["time"] for r in rows)
    print(f"{len(rows)} designs, {len(bad)} refused; time per design median "
          f"{statistics.median(times):.2f} s, max {times[-1]:.2f} s")
    reasons = collections.Counter(r["error"].split(";")[0][:90] for r in bad)
    for reason, n in reasons.most_common(6):
        print(f"  refused x{n}: {reason}")
    if kind == "complete" and ok:
        cov = sorted(r["covered"] for r in ok)
        print(f"one DOF after completion: {sum(r['dof'] == 1 and r['follows'] for r in ok)} of {len(ok)}")
        print(f"raw region already one DOF: {sum(r['raw_dof'] == 1 for r in ok)}")
        print(f"pruned tiles: {sum(r['removed'] > 0 for r in ok)}, grew the ring: {sum(r['grown'] for r in ok)}")
        print(f"covered fraction median {statistics.median(cov):.3f}, worst {cov[0]:.3f}")
        gaps = [r["gap"] for r in ok if r["gap"] is not None]
        if gaps:
            print(f"smallest gap {min(gaps):.1f} decades")
    if kind == "deploy" and ok:
        same = sum(r["steps"] == r["periodic_steps"] and abs(r["end_hull"] - r["periodic_hull"]) < 1e-12 for r in ok)
        print(f"ends where the periodic sheet ends: {same} of {len(ok)}; "
              f"largest deviation before contact {max(r['deviation'] for r in ok):.1e} L; "
              f"one DOF at every check: {sum(r['one_dof_throughout'] for r in ok)}")
    if kind == "pull" and ok:
        leave = [r for r in ok if r["max_deviation"] > 1e-2]
        print(f"leave the periodic motion (> 0.01 L): {len(leave)} of {len(ok)} "
              f"({sum(r['dof'] > 1 for r in leave)} floppy, "
              f"{sum(r['dof'] == 1 for r in leave)} one-DOF at a branch point)")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("kind", choices=["complete", "deploy", "pull"])
    ap.add_argument("--bin", required=True)
    ap.add_argument("--specs", required=True)
    ap.add_argument("--region", default="6x6")
    ap.add_argument("--every", type=int, default=1, help="every k-th spec only")
    ap.add_argument("--raw", action="store_true", help="pull the raw region (pull only)")
    ap.add_argument("--json", help="write every row here")
    opts = ap.parse_args(argv)
    specs = [s.strip() for s in open(opts.specs) if s.strip() and not s.startswith("#")]
    specs = specs[:: opts.every]
    flags = {
        "complete": [],
        "deploy": ["--deploy", "--frames", "2"],
        "pull": ["--pull", "--frames", "6"] + (["--raw"] if opts.raw else []),
    }[opts.kind]
    make = {"complete": complete_row, "deploy": deploy_row, "pull": pull_row}[opts.kind]
    rows = []
    for spec in specs:
        r = sheet(opts.bin, spec, opts.region, *flags)
        rows.append({"spec": spec, "time": r["time"], "error": r["error"]} if "error" in r
                    else {"spec": spec, "time": r["time"], **make(r)})
    print(f"# {opts.kind} at {opts.region}, {opts.bin}")
    summary(opts.kind, rows)
    if opts.json:
        with open(opts.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())

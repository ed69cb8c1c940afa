"""Python overhead per deploy call: times `isogami.deploy(design)` on the designs of the
Rust benchmark (crates/isogami/benches/deploy.rs) and sets the medians beside criterion's
medians of the same library call (`deploy/api`, i.e. `isogami::api::deploy` with the default
request: the same work without Python).

    cargo bench -p isogami --bench deploy -- deploy/api      # the Rust side (release)
    maturin build --release; pip install target/wheels/...   # the Python side (release)
    python deploy_overhead.py [--runs N] [--criterion target/criterion]

Run both on a quiet machine: the difference is small next to the deployment itself.
"""

import argparse
import json
import statistics
import time
from pathlib import Path

import isogami


def median_seconds(call, runs):
    call()  # warm up
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def criterion_median(root: Path, spec: str):
    """criterion's median estimate (seconds) of deploy/api for a design, if it was run."""
    d = isogami.design(spec)
    name = f"{d.family}-{d.edge_count}"
    path = root / "deploy" / "api" / name / "new" / "estimates.json"
    if not path.is_file():
        return name, None
    return name, json.loads(path.read_text())["median"]["point_estimate"] * 1e-9


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=30)
    parser.add_argument("--criterion", type=Path, default=Path(__file__).resolve().parents[3] / "target" / "criterion")
    args = parser.parse_args()
    print(f"{'design':<10} {'python ms':>10} {'rust ms':>10} {'overhead us':>12} {'overhead %':>10}  (median of {args.runs})")
    for spec in isogami.SAMPLE_OPENING_DESIGNS:
        design = isogami.design(spec)
        py = median_seconds(lambda: isogami.deploy(design), args.runs)
        name, rust = criterion_median(args.criterion, spec)
        if rust is None:
            print(f"{name:<10} {py * 1e3:>10.3f} {'-':>10} {'-':>12} {'-':>10}")
        else:
            over = py - rust
            print(f"{name:<10} {py * 1e3:>10.3f} {rust * 1e3:>10.3f} {over * 1e6:>12.1f} {100 * over / rust:>9.2f}%")
    # The fixed cost of the binding alone: a call that fails its checks before any work.
    fixed = median_seconds(lambda: _refused(), 2000)
    print(f"binding round trip of a refused call (argument parsing, settings, error): {fixed * 1e6:.1f} us")


def _refused():
    try:
        isogami.deploy("rotating-squares", frames=1)
    except isogami.SettingsError:
        pass


if __name__ == "__main__":
    main()

"""Shared set-up of the independent checks of `isogami export` files.

The checks run the real CLI (``ISOGAMI_BIN``, default ``target/debug/isogami``) and read
what it writes with libraries that are not ours: trimesh, manifold3d and lib3mf for the
meshes, shapely for the expected geometry, ezdxf for the DXF. Each design's files are made
once per session.
"""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("ISOGAMI_BIN", ROOT / "target" / "debug" / "isogami"))

# rotating-squares and designs of four other families; IH6, IH22 and IH28 have concave
# tiles (the same designs as the Rust export tests, crates/isogami/tests/export/fixtures.rs).
DESIGNS = [
    "rotating-squares",
    "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:a--aa-",
    "IH6:0.4512,0.7209,0.5231,0.9206,0.7110:1x1:-a-aaaaaaa--",
    "IH22:0.1312,0.2611,0.4191:1x1:aa-a-",
    "IH28:0.1136,0.2021:1x1:a--a-b-bbb",
]
CONCAVE = DESIGNS[2:]
# The export writes a design's one-DOF completion by default; these have none at 2x3 cells
# (their finite sheets flop whatever is pruned), so their files are the rectangle as it is
# (`--raw`), and the others' files are completed sheets. Both kinds are checked.
NO_COMPLETION = {DESIGNS[1], DESIGNS[3], DESIGNS[4]}

# Small patches keep the debug CLI fast.
PATCH = "2x3"
WIDTH_MM = 60.0
# Print settings asked for (not the defaults, so the files must carry what was asked).
PRINT = {"thickness_mm": 2.5, "gap_mm": 0.5, "hinge_mm": 1.0, "lamella_mm": 0.6, "nozzle_mm": 0.4}


def run_export(design, fmt, out, *extra):
    """Runs `isogami export` and returns the finished process (`--raw` for the designs of
    NO_COMPLETION)."""
    raw = ["--raw"] if design in NO_COMPLETION else []
    args = [str(BIN), "export", "--design", design, "--format", fmt, "--out", str(out),
            "--patch", PATCH, "--width-mm", str(WIDTH_MM), *raw, *map(str, extra)]
    return subprocess.run(args, capture_output=True, text=True, timeout=300)


def print_flags():
    return [f"--{k.replace('_', '-')}={v}" for k, v in PRINT.items()]


class DesignFiles:
    """Lazily made export files of one design."""

    def __init__(self, design, folder):
        self.design = design
        self.folder = folder
        self.paths = {}

    def path(self, fmt):
        if fmt not in self.paths:
            ext = {"tiles-json": "json"}.get(fmt, fmt)
            out = self.folder / f"sheet.{ext}"
            extra = print_flags() if fmt in ("stl", "3mf") else []
            done = run_export(self.design, fmt, out, *extra)
            assert done.returncode == 0, f"{self.design} {fmt}: {done.stderr}"
            self.paths[fmt] = out
        return self.paths[fmt]


@pytest.fixture(scope="session")
def files(tmp_path_factory):
    if not BIN.exists():
        pytest.fail(f"no isogami binary at {BIN}: build it (cargo build -p isogami-cli)")
    made = {}

    def get(design):
        if design not in made:
            folder = tmp_path_factory.mktemp(f"d{len(made)}")
            made[design] = DesignFiles(design, folder)
        return made[design]

    return get

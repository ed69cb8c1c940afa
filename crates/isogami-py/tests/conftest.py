"""Shared fixtures of the isogami Python tests.

The tests run against the installed ``isogami`` wheel and compare it with the command line
built from the same sources: ``ISOGAMI_BIN`` (default: target/debug/isogami of this
repository). ``ISOGAMI_DB`` may name a quick database made by ``isogami explore --quick``;
otherwise one is made once per session.
"""

import json
import math
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


def cli_path() -> Path:
    return Path(os.environ.get("ISOGAMI_BIN", REPO / "target" / "debug" / "isogami"))


@pytest.fixture(scope="session")
def cli():
    """Runs the isogami command line and returns its parsed JSON output."""
    binary = cli_path()
    if not binary.is_file():
        pytest.fail(f"no isogami binary at {binary}: run `cargo build -p isogami-cli` or set ISOGAMI_BIN")

    def run(*args: str):
        done = subprocess.run(
            [str(binary), *args], capture_output=True, text=True, timeout=600
        )
        if done.returncode != 0:
            raise AssertionError(f"isogami {' '.join(args)} failed: {done.stderr.strip()}")
        return json.loads(done.stdout)

    return run


@pytest.fixture(scope="session")
def cli_raw():
    """Runs the isogami command line and returns the completed process."""
    binary = cli_path()

    def run(*args: str):
        return subprocess.run([str(binary), *args], capture_output=True, timeout=600)

    return run


@pytest.fixture(scope="session")
def quick_db(tmp_path_factory) -> Path:
    """A quick design database (``isogami explore --quick``)."""
    given = os.environ.get("ISOGAMI_DB")
    if given:
        return Path(given)
    path = tmp_path_factory.mktemp("db") / "quick.db"
    done = subprocess.run(
        [str(cli_path()), "explore", "--quick", "--db", str(path)],
        capture_output=True,
        text=True,
        timeout=1200,
    )
    assert done.returncode == 0, done.stderr
    return path


def assert_same(got, want, path="$", tol=1e-12):
    """Recursively checks that `got` equals the CLI's JSON `want`: same keys and lengths,
    equal strings, numbers within `tol` (relative to their size, absolute below 1)."""
    if isinstance(want, dict):
        assert isinstance(got, dict), f"{path}: {type(got).__name__} is not a dict"
        assert set(got) == set(want), f"{path}: keys {sorted(got)} != {sorted(want)}"
        for k in want:
            assert_same(got[k], want[k], f"{path}.{k}", tol)
    elif isinstance(want, list):
        got = list(got)
        assert len(got) == len(want), f"{path}: length {len(got)} != {len(want)}"
        for i, (g, w) in enumerate(zip(got, want)):
            assert_same(g, w, f"{path}[{i}]", tol)
    elif isinstance(want, bool) or want is None or isinstance(want, str):
        assert got == want, f"{path}: {got!r} != {want!r}"
    elif isinstance(want, (int, float)):
        g = float(got)
        assert math.isfinite(g), f"{path}: {g}"
        assert abs(g - want) <= tol * max(1.0, abs(want)), f"{path}: {g!r} != {want!r}"
    else:
        raise AssertionError(f"{path}: unexpected JSON value {want!r}")

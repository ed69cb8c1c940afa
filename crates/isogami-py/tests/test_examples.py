"""The examples run: the script on the quick database writes its figure, and the notebook's
code cells run in order against the same database."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import isogami

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
PNG = b"\x89PNG\r\n\x1a\n"


def test_script_finds_deploys_and_plots_the_best_isotropic_auxetic(quick_db, tmp_path):
    pytest.importorskip("matplotlib")
    figure = tmp_path / "figure.png"
    done = subprocess.run(
        [sys.executable, str(EXAMPLES / "isotropic_auxetics.py"), str(quick_db), str(figure)],
        capture_output=True,
        text=True,
        timeout=600,
        env={**os.environ, "MPLBACKEND": "Agg"},
    )
    assert done.returncode == 0, done.stderr
    assert figure.read_bytes().startswith(PNG) and figure.stat().st_size > 10_000
    with isogami.open_database(quick_db) as db:
        best = db.designs(behaviour="isotropic_auxetic", sort="-max_area_ratio", limit=1)[0]
    assert f"best: {best.spec}" in done.stdout
    assert "behaviour isotropic_auxetic" in done.stdout


def test_notebook_cells_run(quick_db, tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    pytest.importorskip("pandas")
    import matplotlib

    matplotlib.use("Agg")
    notebook = json.loads((EXAMPLES / "isotropic_auxetics.ipynb").read_text())
    assert notebook["nbformat"] == 4
    shutil.copy(quick_db, tmp_path / "quick.db")
    monkeypatch.chdir(tmp_path)
    scope = {}
    for cell in notebook["cells"]:
        if cell["cell_type"] == "code":
            exec(compile("".join(cell["source"]), "notebook", "exec"), scope)
    assert (tmp_path / "isotropic_auxetic.png").read_bytes().startswith(PNG)
    assert scope["run"].behaviour == "isotropic_auxetic"
    scope["db"].close()

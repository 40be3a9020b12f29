"""The teaching notebooks run top to bottom in a fresh kernel, their exercises pass and their plots are saved.

The notebooks are committed as jupytext percent scripts (``notebooks/*.py``); each is converted in memory and
executed with nbclient in a temporary directory, with matplotlib's non-interactive backend.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

jupytext = pytest.importorskip("jupytext")
nbclient = pytest.importorskip("nbclient")

NOTEBOOKS = sorted((Path(__file__).resolve().parent.parent / "notebooks").glob("[0-9][0-9]_*.py"))


def test_there_is_a_notebook_per_topic():
    assert len(NOTEBOOKS) >= 5


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs_and_saves_its_figures(path, tmp_path, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("SYMJAC_NOTEBOOK_OUTPUT", str(tmp_path / "figures"))
    notebook = jupytext.read(path)
    client = nbclient.NotebookClient(notebook, timeout=240, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    source = path.read_text(encoding="utf-8")
    assert "## Exercises" in source and "check(" in source, "every notebook ends with checked exercises"
    for name in re.findall(r'OUTPUT / "([^"]+\.png)"', source):
        assert (tmp_path / "figures" / name).stat().st_size > 1000, name

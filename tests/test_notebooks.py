"""The teaching notebooks run top to bottom in a fresh kernel, their exercises pass and their plots are saved.

The notebooks are committed as jupytext percent scripts (``notebooks/*.py``); each is converted in memory and
executed with nbclient in a temporary directory, with matplotlib's non-interactive backend. Exercise cells ship
with placeholders (``answer_1 = ...  # your answer here``): each such cell is run as shipped, where it must fail,
then again with the worked answer from ``notebooks/solutions.py`` in place, where its checks must pass.
"""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

jupytext = pytest.importorskip("jupytext")
nbclient = pytest.importorskip("nbclient")

FOLDER = Path(__file__).resolve().parent.parent / "notebooks"
NOTEBOOKS = sorted(FOLDER.glob("[0-9][0-9]_*.py"))
PLACEHOLDER = re.compile(r"^(answer_\d+) = \.\.\.  # your answer here$", re.MULTILINE)


def _solutions() -> dict[str, dict[str, str]]:
    spec = importlib.util.spec_from_file_location("notebook_solutions", FOLDER / "solutions.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.SOLUTIONS


def test_there_is_a_notebook_per_topic():
    assert len(NOTEBOOKS) >= 5


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
@pytest.mark.external
def test_notebook_runs_and_saves_its_figures(path, tmp_path, monkeypatch):
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("SYMJAC_NOTEBOOK_OUTPUT", str(tmp_path / "figures"))
    notebook = jupytext.read(path)
    solutions = _solutions()[path.stem]
    client = nbclient.NotebookClient(notebook, timeout=240, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    placeholders = []
    with client.setup_kernel():
        for index, cell in enumerate(notebook.cells):
            names = PLACEHOLDER.findall(cell.source) if cell.cell_type == "code" else []
            if names:
                with pytest.raises(nbclient.exceptions.CellExecutionError, match="AssertionError"):
                    client.execute_cell(cell, index)  # as shipped: the student has not answered yet
                cell.source = PLACEHOLDER.sub(lambda match: solutions[match.group(1)], cell.source)
                placeholders += names
            client.execute_cell(cell, index)
    source = path.read_text(encoding="utf-8")
    assert "## Exercises" in source and "check(" in source, "every notebook ends with checked exercises"
    assert placeholders and sorted(placeholders) == sorted(solutions), "one worked answer per placeholder"
    exercises = source.partition("## Exercises")[2]
    assert not re.search(r"^answer_\d+ = (?!\.\.\.  # your answer here$)", exercises, re.MULTILINE), (
        "answers are left for the student: the worked ones live in notebooks/solutions.py")
    for name in re.findall(r'OUTPUT / "([^"]+\.png)"', source):
        assert (tmp_path / "figures" / name).stat().st_size > 1000, name

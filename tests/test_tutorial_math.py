"""The tutorials show explanations as typeset text, and every notebook exercise is marked by a checker.

A singularity report's captions mix words and ``$...$`` math. Printed, the site shows them as raw LaTeX in a
monospace box; the notebooks display them as Markdown, which the site reads as MyST (``nb_render_markdown_format``)
with ``dollarmath``, so the math is typeset. The captions are rendered here the way the site renders them.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

from symjac import load_robot, singularities
from symjac.printing import singularity_summary

ROOT = Path(__file__).resolve().parent.parent
NOTEBOOKS = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.py"))


def _site_markdown():
    """The parser the site reads a notebook's Markdown output with: MyST's, with the extensions ``conf.py`` enables."""
    markdown_it = pytest.importorskip("markdown_it")
    dollarmath = pytest.importorskip("mdit_py_plugins.dollarmath")
    source = (ROOT / "docs" / "conf.py").read_text(encoding="utf-8")
    assert re.search(r'^nb_render_markdown_format = "myst"$', source, re.MULTILINE), "notebook Markdown is MyST"
    assert re.search(r'^myst_enable_extensions = \[.*"dollarmath"', source, re.MULTILINE)
    return markdown_it.MarkdownIt("commonmark").use(dollarmath.dollarmath_plugin)


@pytest.mark.parametrize("name", ["planar2r", "articulated3r"])
def test_singularity_captions_render_as_text_with_typeset_math(name):
    parser = _site_markdown()
    captions = [caption for caption, _ in singularity_summary(singularities(load_robot(name)))]
    assert any("$v_{x}$" in caption for caption in captions)  # the report does write math in its captions
    for caption in captions:
        tokens = [t for block in parser.parse(caption) for t in (block.children or [block])]
        text = "".join(t.content for t in tokens if t.type == "text")
        assert "$" not in text and "\\" not in text, caption  # no raw LaTeX left in the words
        assert all(t.type != "code_inline" for t in tokens)
        if "$" in caption:
            assert any(t.type == "math_inline" for t in tokens), caption


def test_notebooks_display_report_captions_as_markdown_not_print():
    for path in NOTEBOOKS:
        source = path.read_text(encoding="utf-8")
        assert not re.search(r"print\((caption|summary|line)\)", source), path.name
    assert "display(Markdown(caption))" in (ROOT / "notebooks" / "04_singularities.py").read_text(encoding="utf-8")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_every_exercise_is_marked_by_a_checker(path):
    """No bare ``assert answer_N == ...``: each answer goes through ``check`` or ``check_set``, which give hints."""
    exercises = path.read_text(encoding="utf-8").partition("## Exercises")[2]
    cells = [cell for cell in exercises.split("# %%") if re.search(r"^answer_\d+ = ", cell, re.MULTILINE)]
    assert cells
    for cell in cells:
        for name in re.findall(r"^(answer_\d+) = ", cell, re.MULTILINE):
            assert re.search(rf"^check(_set)?\({name}, ", cell, re.MULTILINE), f"{path.name}: {name}"
        assert not re.search(r"^assert .*answer_", cell, re.MULTILINE), path.name


def test_the_built_singularities_tutorial_has_no_raw_latex_in_literal_blocks():
    """On a built site (``SYMJAC_DOCS_HTML``: its folder), the tutorial's output boxes hold no ``$...$`` math."""
    folder = os.environ.get("SYMJAC_DOCS_HTML")
    if not folder:
        pytest.skip("set SYMJAC_DOCS_HTML to a built site to check its pages")
    page = (Path(folder) / "tutorials" / "notebooks" / "04_singularities.html").read_text(encoding="utf-8")
    literal = "".join(re.findall(r"<pre[^>]*>(.*?)</pre>", page, re.DOTALL))
    assert "$v_{x}$" not in literal and r"\{2\}" not in literal
    assert "v_{x}" in page  # typeset by MathJax from the math spans

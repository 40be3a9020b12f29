"""The jinja2 templates are found wherever symjac is installed: regular wheel, editable install, this checkout.

The ``slow`` tests build real installs into fresh virtual environments (no system site-packages) and download
symjac's dependencies from the package index; set ``CI_SKIP_PACKAGING=1`` to skip them.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import types
from pathlib import Path

import jinja2
import pytest

import symjac.resources
from symjac.resources import render_template, templates_dir

REPO = Path(__file__).resolve().parent.parent
TEMPLATE = "documents/latex_document.tex.j2"
TIMEOUT = 300  # seconds for one subprocess (venv creation, pip install, one symjac run)

DOCUMENT_DATA = {
    "version": "0.0.test",
    "robot": "demo",
    "title": "Demo title",
    "blocks": [{"caption": "First block", "latex": r"x = \alpha"}, {"caption": "", "latex": "y = 2"}],
}

skip_packaging = pytest.mark.skipif(
    os.environ.get("CI_SKIP_PACKAGING") == "1",
    reason="CI_SKIP_PACKAGING=1: skipping the fresh-venv install tests (they download dependencies)",
)

SHOW_TEMPLATES = """\
import json, sysconfig
import symjac
from symjac.resources import render_template, templates_dir
print(json.dumps({
    "templates_dir": str(templates_dir()),
    "package": symjac.__file__,
    "purelib": sysconfig.get_path("purelib"),
    "document": render_template("documents/latex_document.tex.j2", version="v", robot="r", title="T", blocks=[]),
}))
"""


# --- this environment -------------------------------------------------------------------------------------------


def test_templates_dir_holds_the_latex_document_template():
    directory = templates_dir()
    assert directory.is_dir()
    assert (directory / TEMPLATE).is_file()


def test_render_template_fills_in_the_document():
    text = render_template(TEMPLATE, **DOCUMENT_DATA)
    assert r"\documentclass{article}" in text
    assert text.rstrip().endswith(r"\end{document}")
    assert "symjac 0.0.test" in text
    assert '"demo"' in text
    assert "Demo title" in text
    assert "First block" in text
    assert r"x = \alpha" in text
    assert "y = 2" in text
    assert "{{" not in text
    assert "{%" not in text
    assert "{#" not in text  # template comments are stripped


@pytest.mark.parametrize("missing", ["version", "robot", "title", "blocks"])
def test_render_template_is_strict_about_missing_variables(missing):
    data = {key: value for key, value in DOCUMENT_DATA.items() if key != missing}
    with pytest.raises(jinja2.UndefinedError):
        render_template(TEMPLATE, **data)


def test_render_template_is_strict_about_missing_attributes():
    with pytest.raises(jinja2.UndefinedError):
        render_template(TEMPLATE, **{**DOCUMENT_DATA, "blocks": [{"latex": "x"}]})  # no caption


def test_unknown_template_raises():
    with pytest.raises(jinja2.TemplateNotFound):
        render_template("no_such_template.j2")


def test_templates_dir_falls_back_to_the_checkout(monkeypatch, tmp_path):
    """Without an installed copy (editable install), the checkout's ``templates/`` folder is used."""
    monkeypatch.setattr(symjac.resources, "resources", types.SimpleNamespace(files=lambda package: tmp_path))
    assert templates_dir() == REPO / "templates"


def test_templates_dir_reports_an_incomplete_installation(monkeypatch, tmp_path):
    monkeypatch.setattr(symjac.resources, "resources", types.SimpleNamespace(files=lambda package: tmp_path))
    monkeypatch.setattr(symjac.resources, "__file__", str(tmp_path / "site" / "symjac" / "resources.py"))
    with pytest.raises(FileNotFoundError, match="templates not found"):
        templates_dir()


# --- fresh virtual environments ---------------------------------------------------------------------------------


def _clean_env() -> dict[str, str]:
    """The environment for subprocesses, without anything pointing at the Python running the tests."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV", "PYTHONSTARTUP")}
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    env["PYTHONNOUSERSITE"] = "1"
    return env


def _run(args: list[str | Path], cwd: Path) -> str:
    """Run a command, failing the test with its output if it fails; return its stdout."""
    result = subprocess.run([str(a) for a in args], cwd=cwd, env=_clean_env(), capture_output=True, text=True,
                            timeout=TIMEOUT, check=False)
    assert result.returncode == 0, (
        f"{' '.join(map(str, args))} exited with {result.returncode}\n"
        f"--- stdout ---\n{result.stdout}\n--- stderr ---\n{result.stderr}"
    )
    return result.stdout


def _fresh_venv(tmp_path: Path) -> tuple[Path, Path]:
    """A clean virtual environment (no system site-packages); return (its python, its bin directory)."""
    venv = tmp_path / "venv"
    _run([sys.executable, "-m", "venv", venv], cwd=tmp_path)
    bindir = venv / ("Scripts" if os.name == "nt" else "bin")
    python = bindir / ("python.exe" if os.name == "nt" else "python")
    assert python.exists()
    config = (venv / "pyvenv.cfg").read_text(encoding="utf-8")
    assert "include-system-site-packages = false" in config
    return python, bindir


def _show_templates(python: Path, cwd: Path) -> dict[str, str]:
    return json.loads(_run([python, "-c", SHOW_TEMPLATES], cwd=cwd))


@pytest.fixture
def outside(tmp_path: Path) -> Path:
    """A working directory outside the repository, so ``import symjac`` cannot pick up the checkout by accident."""
    directory = tmp_path / "elsewhere"
    directory.mkdir()
    assert REPO not in directory.resolve().parents
    return directory


@pytest.mark.slow
@skip_packaging
@pytest.mark.external
def test_regular_install_ships_the_templates(tmp_path, outside):
    python, bindir = _fresh_venv(tmp_path)
    _run([python, "-m", "pip", "install", "--quiet", REPO], cwd=outside)

    info = _show_templates(python, outside)
    purelib = Path(info["purelib"]).resolve()
    package = Path(info["package"]).resolve()
    directory = Path(info["templates_dir"]).resolve()
    assert purelib in package.parents, f"symjac imported from {package}, not from the venv's {purelib}"
    assert directory == purelib / "symjac" / "templates"
    assert (directory / TEMPLATE).is_file()
    assert (directory / TEMPLATE).read_text(encoding="utf-8") == (REPO / "templates" / TEMPLATE).read_text(
        encoding="utf-8")
    assert REPO not in directory.parents
    assert r"\documentclass{article}" in info["document"]

    symjac = bindir / ("symjac.exe" if os.name == "nt" else "symjac")
    out = _run([symjac, "jacobian", "planar2r", "--standalone"], cwd=outside)
    assert r"\documentclass{article}" in out
    assert r"{}^{0}J = \begin{bmatrix}" in out
    assert "s_{12}" in out
    assert out.rstrip().endswith(r"\end{document}")

    # Code generation renders its module templates from the installed copy; the module checks itself.
    module = outside / "planar_generated.py"
    _run([symjac, "codegen", "planar2r", "--target", "python", "-o", module], cwd=outside)
    _run([python, "-c", "import planar_generated; planar_generated.selftest()"], cwd=outside)
    # URDF robots ship inside the package too.
    assert "ur5" in _run([symjac, "fk", "ur5.urdf", "--format", "json"], cwd=outside)

    # The wheel carries only the package (and its templates and robot files), not the checkout's tests.
    assert not (purelib / "tests").exists()
    assert not (purelib / "templates").exists()


def _editable_environment() -> tuple[Path, Path] | None:
    """This test run's own (python, bin directory) when it imports symjac from an editable install of this checkout."""
    here = subprocess.run([sys.executable, "-c", "import symjac; print(symjac.__file__)"], cwd=Path("/"),
                          env=_clean_env(), capture_output=True, text=True, timeout=TIMEOUT, check=False)
    if here.returncode != 0 or Path(here.stdout.strip()).resolve() != REPO / "symjac" / "__init__.py":
        return None
    return Path(sys.executable), Path(sys.executable).parent


@pytest.mark.slow
@skip_packaging
@pytest.mark.external
def test_editable_install_finds_the_templates(tmp_path, outside):
    """Checked in this run's own environment when it is an editable install (as in ``.ci/run``), else in a new one."""
    found = _editable_environment()
    if found is None or not (found[1] / ("symjac.exe" if os.name == "nt" else "symjac")).exists():
        python, bindir = _fresh_venv(tmp_path)
        _run([python, "-m", "pip", "install", "--quiet", "-e", REPO], cwd=outside)
    else:
        python, bindir = found

    info = _show_templates(python, outside)
    package = Path(info["package"]).resolve()
    directory = Path(info["templates_dir"]).resolve()
    assert package == REPO / "symjac" / "__init__.py", f"editable install imports symjac from {package}"
    assert (directory / TEMPLATE).is_file()
    if directory != REPO / "templates":  # an installed copy is acceptable, but must be the same template
        assert (directory / TEMPLATE).read_text(encoding="utf-8") == (REPO / "templates" / TEMPLATE).read_text(
            encoding="utf-8")
    assert r"\documentclass{article}" in info["document"]
    assert '"r"' in info["document"]

    symjac = bindir / ("symjac.exe" if os.name == "nt" else "symjac")
    out = _run([symjac, "fk", "planar2r", "--standalone"], cwd=outside)
    assert r"\documentclass{article}" in out
    assert out.rstrip().endswith(r"\end{document}")


def test_the_jupyter_extra_brings_a_front_end_that_ci_does_not_install():
    """Issue 14 point 8: ``pip install -e '.[jupyter]'`` gives JupyterLab with jupytext; ``.[test]`` does not."""
    import re
    import tomllib

    extras = tomllib.loads((REPO / "pyproject.toml").read_text(encoding="utf-8"))["project"]["optional-dependencies"]

    def names(extra: str) -> set[str]:
        found = set()
        for requirement in extras[extra]:
            name = re.split(r"[<>=\[ ;]", requirement, maxsplit=1)[0].lower()
            nested = re.fullmatch(r"symjac\[(\w+)\]", requirement)
            found |= names(nested.group(1)) if nested else {name}
        return found

    assert {"jupyterlab", "jupytext", "ipykernel"} <= names("jupyter")
    assert "jupyterlab" not in names("test") and "notebook" not in names("test")

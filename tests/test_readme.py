"""The README and the documentation pages run: every Python example and every concrete ``symjac`` command in them.

Python blocks run in order in one namespace per page (later blocks use the ``robot`` of the first), in a scratch
folder. Commands run in-process through :func:`symjac.cli.main.main` in a folder that holds the files the pages name:
``my_arm.toml`` (the robot-file guide's own example), ``arm.urdf`` (a UR5 with a ``tool0`` link) and ``arm.xml`` (the
MJCF guide's own example). A command with
a placeholder (``ROBOT``, ``FILE``, ``K``) or alternatives (``a|b``) is a usage line, not an example. The C and C++
programs of the code generation pages are compiled and run by ``tests/test_docs.py``.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from symjac import catalog
from symjac.cli.main import main

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
PAGES = [README, *sorted((ROOT / "docs").glob("**/*.md"))]
PAGES = [page for page in PAGES if "_build" not in page.parts]
FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.MULTILINE | re.DOTALL)
INLINE_COMMAND = re.compile(r"`(symjac [^`]+)`")
PLACEHOLDER = re.compile(r"\b[A-Z]{1,}\b|\||\.\.\.")
OTHER_SHELL = ("pip ", "jupyter ", "python -m pytest", "bash .ci/run", "python -m sphinx", "gcc ", "g++ ", "./main")
"""Shell lines that are not symjac commands: installing, running the tests, building the site, compiling examples."""


def _name(page: Path) -> str:
    return str(page.relative_to(ROOT))


def _blocks(language: str, page: Path = README) -> list[str]:
    return [body for lang, body in FENCE.findall(page.read_text(encoding="utf-8")) if lang == language]


def _commands() -> list[str]:
    commands = []
    for page in PAGES:
        for block in _blocks("bash", page):
            for line in block.splitlines():
                for part in line.split("&&"):
                    part = part.split("  #")[0].strip()
                    if not part:
                        continue
                    if part.startswith("symjac "):
                        commands.append(part)
                    else:
                        assert part.startswith(OTHER_SHELL), f"{_name(page)}: shell line not understood: {part!r}"
        prose = FENCE.sub("", page.read_text(encoding="utf-8")).replace("\n", " ")
        commands += [c for c in INLINE_COMMAND.findall(prose) if not PLACEHOLDER.search(c.removeprefix("symjac "))]
    return list(dict.fromkeys(commands))


def _pages_with_python() -> list[Path]:
    return [page for page in PAGES if _blocks("python", page)]


@pytest.fixture
def readme_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    (toml,) = [b for b in _blocks("toml", ROOT / "docs" / "guide" / "robot_files.md")
               if "[[joints]]" in b and 'name = "puma560"' in b]
    (tmp_path / "my_arm.toml").write_text(toml.replace('name = "puma560"', 'name = "my_arm"'), encoding="utf-8")
    (tmp_path / "arm.urdf").write_bytes((ROOT / "symjac" / "robots" / "urdf" / "ur5.urdf").read_bytes())
    (mjcf,) = [b for b in _blocks("xml", ROOT / "docs" / "guide" / "mjcf.md") if "<mujoco" in b]
    (tmp_path / "arm.xml").write_text(mjcf, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_the_pages_have_examples_to_run():
    assert len(_blocks("python")) >= 1
    assert sum(len(_blocks("python", page)) for page in PAGES) >= 12
    assert len(_commands()) >= 15


@pytest.mark.parametrize("command", _commands())
@pytest.mark.slow
def test_documented_command_runs(command: str, readme_folder: Path, capsys: pytest.CaptureFixture[str]):
    status = main(shlex.split(command)[1:])
    captured = capsys.readouterr()
    assert status == 0, f"{command}: {captured.err}"
    assert captured.out or "-o" in shlex.split(command), f"{command} printed nothing"


@pytest.mark.parametrize("page", _pages_with_python(), ids=_name)
def test_documented_python_examples_run(page: Path, readme_folder: Path, capsys: pytest.CaptureFixture[str]):
    namespace: dict[str, object] = {"__name__": "docs_example"}
    for number, block in enumerate(_blocks("python", page), start=1):
        try:
            exec(compile(block, f"{_name(page)} python block {number}", "exec"), namespace)
        except Exception as error:  # name the block, keep the cause
            raise AssertionError(f"{_name(page)} python block {number} fails: {error!r}\n{block}") from error


def _catalog_rows(text: str) -> list[tuple[str, str]]:
    """The (name, description) rows of the catalog table: the one headed ``| name | robot |``."""
    return re.findall(r"^\| `(\w+)` \| (.+) \|$", text[text.index("| name | robot |"):], re.MULTILINE)


def test_the_catalog_tables_list_every_built_in_robot_once():
    """The README's catalog and the site's catalog page are the same table, one row per robot of ``catalog()``."""
    readme = _catalog_rows(README.read_text(encoding="utf-8"))
    assert readme == _catalog_rows((ROOT / "docs" / "catalog.md").read_text(encoding="utf-8"))
    assert sorted(name for name, _ in readme) == sorted(catalog())

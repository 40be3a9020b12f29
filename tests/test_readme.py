"""The README runs: every Python example and every concrete ``symjac`` command in it is executed here.

Python blocks run in order in one namespace (later blocks use the ``robot`` of the first), in a scratch folder.
Commands run in-process through :func:`symjac.cli.main.main` in a folder that holds the files the README names:
``my_arm.toml`` (the README's own robot-file example) and ``arm.urdf`` (a UR5 with a ``tool0`` link). A command
with a placeholder (``ROBOT``, ``FILE``, ``K``) or alternatives (``a|b``) is a usage line, not an example.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from symjac.cli.main import main

ROOT = Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.MULTILINE | re.DOTALL)
INLINE_COMMAND = re.compile(r"`(symjac [^`]+)`")
PLACEHOLDER = re.compile(r"\b[A-Z]{1,}\b|\||\.\.\.")
OTHER_SHELL = ("pip ", "jupyter ", "python -m pytest", "bash .ci/run")
"""Shell lines of the README that are not symjac commands: installing and running the test suite."""


def _blocks(language: str) -> list[str]:
    return [body for lang, body in FENCE.findall(README.read_text(encoding="utf-8")) if lang == language]


def _commands() -> list[str]:
    commands = []
    for block in _blocks("bash"):
        for line in block.splitlines():
            for part in line.split("&&"):
                part = part.split("  #")[0].strip()
                if not part:
                    continue
                if part.startswith("symjac "):
                    commands.append(part)
                else:
                    assert part.startswith(OTHER_SHELL), f"README shell line not understood by the test: {part!r}"
    prose = FENCE.sub("", README.read_text(encoding="utf-8")).replace("\n", " ")
    commands += [c for c in INLINE_COMMAND.findall(prose) if not PLACEHOLDER.search(c.removeprefix("symjac "))]
    return list(dict.fromkeys(commands))


@pytest.fixture
def readme_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    (toml,) = [b for b in _blocks("toml") if "[[joints]]" in b and 'name = "puma560"' in b]
    (tmp_path / "my_arm.toml").write_text(toml.replace('name = "puma560"', 'name = "my_arm"'), encoding="utf-8")
    (tmp_path / "arm.urdf").write_bytes((ROOT / "symjac" / "robots" / "urdf" / "ur5.urdf").read_bytes())
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_the_readme_has_examples_to_run():
    assert len(_blocks("python")) >= 4
    assert len(_commands()) >= 15


@pytest.mark.parametrize("command", _commands())
@pytest.mark.slow
def test_readme_command_runs(command: str, readme_folder: Path, capsys: pytest.CaptureFixture[str]):
    status = main(shlex.split(command)[1:])
    captured = capsys.readouterr()
    assert status == 0, f"{command}: {captured.err}"
    assert captured.out or "-o" in shlex.split(command), f"{command} printed nothing"


def test_readme_python_examples_run(readme_folder: Path, capsys: pytest.CaptureFixture[str]):
    namespace: dict[str, object] = {"__name__": "readme"}
    for number, block in enumerate(_blocks("python"), start=1):
        try:
            exec(compile(block, f"README.md python block {number}", "exec"), namespace)
        except Exception as error:  # name the block, keep the cause
            raise AssertionError(f"README python block {number} fails: {error!r}\n{block}") from error

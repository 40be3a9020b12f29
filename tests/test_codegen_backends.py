"""The backend seam: one folder per target in the registry, rendering to a mapping, each target's own identifier
rule, and an all-or-none write of several files."""

from __future__ import annotations

import builtins
import keyword
import os
import re
from pathlib import Path

import pytest
from marks import PYTHON_TARGETS, marked

from symjac import load_robot, robot_from_mapping
from symjac.codegen import (
    BACKENDS,
    TARGETS,
    CodegenError,
    ModuleRequest,
    describe,
    generate,
    render_files,
    write_module,
)
from symjac.codegen.backends.c import C_KEYWORDS

BACKENDS_DIR = Path(__file__).resolve().parent.parent / "symjac" / "codegen" / "backends"
TEMPLATES_DIR = Path(__file__).resolve().parent.parent / "templates"


def test_the_registry_lists_each_backend_folder():
    folders = {p.name for p in BACKENDS_DIR.iterdir() if p.is_dir() and (p / "__init__.py").is_file()
               and not p.name.startswith("_")}
    assert set(TARGETS) == folders
    for name, spec in BACKENDS.items():
        assert (BACKENDS_DIR / name / "printer.py").is_file()
        assert all((TEMPLATES_DIR / template).is_file() for template in spec.templates)
        assert spec.templates[0].startswith(f"{name}/")


@pytest.mark.parametrize("target", PYTHON_TARGETS)
def test_rendering_returns_a_mapping_whose_primary_file_is_the_module(target):
    files = render_files(describe(ModuleRequest(load_robot("planar2r"), target)))
    assert list(files) == ["planar2r.py"]
    assert files["planar2r.py"] == generate(load_robot("planar2r"), target)


def _robot_with_parameter(name: str):
    return robot_from_mapping({"name": "arm", "convention": "standard", "parameters": {name: 1.0},
                               "joints": [{"type": "revolute", "a": name}, {"type": "revolute", "a": 1}]})


@pytest.mark.parametrize("target", PYTHON_TARGETS)
@pytest.mark.parametrize(("word", "message"), [("lambda", "is a Python keyword"), ("match", "is a Python keyword"),
                                               ("len", "would shadow the Python builtin")])
def test_python_reserved_words_are_refused_by_every_target(target, word, message):
    # robot files refuse these names already; the target's own rule is the second line of defence
    with pytest.raises(CodegenError, match=f"parameter name '{word}' {message}"):
        BACKENDS[target].identifiers.check(word, "parameter name")
    assert BACKENDS[target].identifiers.check("L1", "parameter name") == "L1"


PYTHON_WORDS = set(keyword.kwlist) | set(keyword.softkwlist) | set(dir(builtins))


@pytest.mark.parametrize("word", sorted(C_KEYWORDS - PYTHON_WORDS))
def test_c_keywords_are_refused_by_the_c_target_only(word):
    with pytest.raises(CodegenError, match=f"parameter name '{word}' is a C keyword"):
        generate(_robot_with_parameter(word), "c")
    assert "jacobian" in generate(_robot_with_parameter(word), "python")


def test_a_multi_file_write_is_all_or_none(tmp_path, monkeypatch):
    (tmp_path / "old.py").write_text("old\n")
    failing = {"old.py": "new\n", "sub/second.h": "x\n"}  # the folder "sub" does not exist: the second file fails
    with pytest.raises(FileNotFoundError):
        write_module(tmp_path / "old.py", failing)
    assert (tmp_path / "old.py").read_text() == "old\n"
    assert sorted(os.listdir(tmp_path)) == ["old.py"]  # no temporary file left either

    replace = os.replace
    calls = []

    def second_fails(source, target):
        calls.append(target)
        if len(calls) == 2:
            raise PermissionError(13, "denied", str(target))
        replace(source, target)

    monkeypatch.setattr(os, "replace", second_fails)
    with pytest.raises(PermissionError):
        write_module(tmp_path / "old.py", {"old.py": "new\n", "extra.h": "x\n"})
    assert (tmp_path / "old.py").read_text() == "old\n"  # the first replacement was undone
    assert sorted(os.listdir(tmp_path)) == ["old.py"]
    monkeypatch.undo()
    write_module(tmp_path / "old.py", {"old.py": "new\n", "extra.h": "x\n"})
    assert (tmp_path / "old.py").read_text() == "new\n" and (tmp_path / "extra.h").read_text() == "x\n"


def test_generated_file_names_stay_in_the_output_folder(tmp_path):
    with pytest.raises(CodegenError, match="must be relative"):
        write_module(tmp_path / "a.py", {"a.py": "", str(Path(os.pardir, "b.py")): ""})  # a name climbing out


@pytest.mark.parametrize("target", TARGETS)
def test_name_sets_the_module_name_and_is_checked_by_the_target(target, tmp_path):
    files = render_files(describe(ModuleRequest(load_robot("planar2r"), target, name="arm_two")))
    assert all(name.startswith("arm_two.") for name in files)
    # prefixes, namespace and ROBOT take the name; the robot is still loaded as planar2r by the regenerating call,
    # and the header names the file it came from
    assert all("planar2r" not in text.replace('load_robot("planar2r")', "").replace("file (TOML) planar2r.toml", "")
               for text in files.values())
    assert 'name="arm_two"' in next(iter(files.values()))  # the primary file says how to regenerate
    with pytest.raises(CodegenError, match="module name 'two-arms' is not an ASCII identifier"):
        describe(ModuleRequest(load_robot("planar2r"), target, name="two-arms"))


@pytest.mark.parametrize(("target", "word", "language"), [("c99", "int", "C"), ("cpp", "namespace", "C\\+\\+"),
                                                          ("python", "lambda", "Python")])
def test_a_module_name_reserved_in_the_language_is_refused_in_one_line(target, word, language):
    with pytest.raises(CodegenError, match=f"module name '{word}' is a {language} keyword"):
        generate(load_robot("planar2r"), target, name=word)


def _bodies(source: str) -> dict[str, str]:
    """The ``sj_body_*`` functions of a C source, by name, from their comment to their closing brace."""
    bodies = re.findall(r"\n(/\* [^\n]*(?:\n \*[^\n]*)*\*/\nstatic \w+ (sj_body_\w+)\(.*?\n}\n)", source, re.S)
    return {name: text for text, name in bodies}


_SLIDES = {"name": "slides", "convention": "standard",
           "joints": [{"type": "prismatic", "alpha": "-pi/2"}, {"type": "prismatic", "alpha": "pi/2"}]}


@pytest.mark.parametrize("name", marked(["planar2r", "puma560", "scara", "palletizer", "slides"]))
def test_the_c_extension_holds_the_c99_targets_function_bodies(name):
    """One template prints the function bodies of both C targets: the extension holds the c99 file's, byte for byte
    (all but the self-test's kinematics, which the c module computes in NumPy); a robot without revolute joints has
    no sines and cosines to pass."""
    robot = robot_from_mapping(_SLIDES) if name == "slides" else load_robot(name)
    c99 = _bodies(render_files(describe(ModuleRequest(robot, "c99", acceleration=True)))[f"{robot.name}.c"])
    module = generate(robot, "c", acceleration=True)
    extension = _bodies(module[module.index('_C_SOURCE = r"""'):])
    assert extension and set(extension) == set(c99) - {"sj_body_kinematics"}
    assert all(extension[function] == c99[function] for function in extension)
    assert all(("const real S[" in text) == (name != "slides") for text in extension.values())

"""Runtime sections: a generated module carries the runtime's core and only the sections it uses.

Each runtime file (``templates/runtime/``) is cut into named sections; a module asks for its derived routines and
self-test checks (:attr:`ModuleDescription.runtime_sections`), the runtime adds what those need. Checked here: a
module without the acceleration level carries no acceleration check and no gradient, the Cholesky solve (which
nothing calls yet) is in no module but selected when asked, every section a description can ask for exists in
every runtime, each section alone brings every name it uses, and the selected text still imports, compiles without
a warning (an unused C function would warn) and passes its self-test.
"""

from __future__ import annotations

import ast
import importlib.util
import shutil
import subprocess
from pathlib import Path

import pytest

from symjac import load_robot
from symjac.codegen import BACKENDS, ModuleRequest, describe, render_files
from symjac.codegen.kinds import CHECK_WORDS, KINDS
from symjac.codegen.runtime import CORE_CHECKS, MARK, RUNTIMES, runtime_source, section_names
from symjac.errors import CodegenError

REPO = Path(__file__).resolve().parent.parent
RUNTIME = REPO / "templates" / "runtime"
TARGETS = tuple(target for target, backend in BACKENDS.items() if backend.runtime)
ASKABLE = frozenset(kind.routine for kind in KINDS.values() if kind.routine) | frozenset(CHECK_WORDS)
"""Every section a description can ask for: a derived kind's routine or a self-test check."""

ACCELERATION_WORDS = ("_acceleration_error", "sj_check_acceleration", "manipulability_gradient", "hessian")


def _files(robot: str, target: str, acceleration: bool) -> dict[str, str]:
    return dict(render_files(describe(ModuleRequest(load_robot(robot), target, acceleration=acceleration))))


def _text(robot: str, target: str, acceleration: bool) -> str:
    return "\n".join(_files(robot, target, acceleration).values())


@pytest.mark.parametrize("target", TARGETS)
def test_a_module_without_acceleration_has_no_acceleration_check_and_no_gradient(target):
    plain = _text("planar2r", target, acceleration=False)
    assert not [word for word in ACCELERATION_WORDS if word in plain]
    full = _text("planar2r", target, acceleration=True)
    assert "manipulability_gradient" in full
    if target != "cpp":  # the C++ header has no self-test
        assert "_acceleration_error" in full or "sj_check_acceleration" in full


@pytest.mark.parametrize("target", TARGETS)
@pytest.mark.parametrize("robot", ["planar2r", "stanford"])
def test_the_cholesky_solve_is_in_no_generated_module(target, robot):
    for acceleration in (False, True):
        assert "cholesky" not in _text(robot, target, acceleration).lower()


@pytest.mark.parametrize("name", RUNTIMES)
def test_every_section_a_description_asks_for_exists_and_the_cholesky_solve_is_selected_when_asked(name):
    assert section_names(name) >= ASKABLE - CORE_CHECKS, name
    assert "cholesky_solve" in section_names(name)
    core = runtime_source(name, frozenset())
    asked = runtime_source(name, frozenset({"cholesky_solve"}))
    assert "cholesky" not in core.lower() and "cholesky_solve" in asked and len(asked) > len(core)
    lines = iter(asked.splitlines())
    assert all(line in lines for line in core.splitlines())  # the core, in order, with the section added
    assert runtime_source(name, frozenset(CORE_CHECKS)) == core  # the core holds the pose and Jacobian checks
    every = runtime_source(name)  # every section (and every section's needs exist)
    assert all(runtime_source(name, frozenset({section})) != "" for section in section_names(name))
    assert "cholesky" in every.lower()
    with pytest.raises(CodegenError, match="has no section"):
        runtime_source(name, frozenset({"fft"}))


def test_a_section_brings_what_it_needs():
    gradient = runtime_source("c99.h", frozenset({"manipulability_gradient"}))
    for definition in ("void sj_solve(", "int sj_gram(", "real sj_lu_determinant(", "void sj_manipulability_gradient("):
        assert f"static inline {definition}" in gradient
    assert "sj_manipulability(" not in gradient and "sj_determinant(" not in gradient
    determinant = runtime_source("c99.h", frozenset({"determinant"}))
    assert "sj_lu_determinant(" in determinant and "sj_solve(" not in determinant and "sj_gram(" not in determinant
    python = runtime_source("python.py", frozenset({"manipulability_gradient"}))
    assert "def _solve(" in python and "def _entry(" in python and "def _manipulability(" not in python


@pytest.mark.skipif(shutil.which("ruff") is None, reason="ruff is not installed")
def test_each_python_section_alone_names_nothing_undefined(tmp_path):
    """The file's head (imports) with the core and one section: ruff finds no undefined name (F821)."""
    files = []
    for name in (n for n in RUNTIMES if n.endswith(".py")):
        head = (RUNTIME / name).read_text(encoding="utf-8").partition(MARK)[0].rsplit("\n", 1)[0]
        for section in sorted(section_names(name)):
            path = tmp_path / f"{name[:-3]}_{section}.py"
            path.write_text(head + "\n\n\n" + runtime_source(name, frozenset({section})), encoding="utf-8")
            files.append(str(path))
    result = subprocess.run(["ruff", "check", "--no-cache", "--isolated", "--select", "F821", *files],
                            capture_output=True, text=True, check=False, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr


def _runtime_functions(text: str, runtime: str) -> set[str]:
    """The top-level functions of a generated Python module that come from its runtime."""
    names = {node.name for node in ast.parse(runtime_source(runtime)).body if isinstance(node, ast.FunctionDef)}
    return {node.name for node in ast.parse(text).body if isinstance(node, ast.FunctionDef)} & names


@pytest.mark.parametrize("target", [t for t in TARGETS if BACKENDS[t].language.startswith("Python")])
@pytest.mark.parametrize("acceleration", [False, True])
def test_every_runtime_function_a_python_module_carries_is_used(target, acceleration):
    description = describe(ModuleRequest(load_robot("planar2r"), target, acceleration=acceleration))
    text = "\n".join(render_files(description).values())
    tree = ast.parse(text)
    used = {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}
    used |= {f"_{check.routine}_error" for check in description.checks}  # the driver finds these by name
    carried = _runtime_functions(text, BACKENDS[target].runtime)
    assert carried and not carried - used, sorted(carried - used)


def _import(path: Path, text: str):
    path.write_text(text, encoding="utf-8")
    spec = importlib.util.spec_from_file_location(path.stem, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("target", ["python", "numpy", "lambdify"])
@pytest.mark.parametrize("acceleration", [False, True])
def test_the_selected_runtime_imports_and_the_self_test_passes(tmp_path, target, acceleration):
    if target != "python":
        pytest.importorskip("numpy")
    module = _import(tmp_path / f"planar2r_{target}_{acceleration}.py", _text("planar2r", target, acceleration))
    assert module.selftest(samples=3) <= 1e-6


@pytest.mark.slow
@pytest.mark.parametrize("target", ["jax", "casadi"])
def test_the_selected_jax_and_casadi_runtimes_import_and_pass_the_self_test(tmp_path, target):
    pytest.importorskip(target)
    for acceleration in (False, True):
        module = _import(tmp_path / f"planar2r_{target}_{acceleration}.py", _text("planar2r", target, acceleration))
        assert module.selftest(samples=2) >= 0.0  # raises beyond the target's own tolerance


C_MAIN = '#include "planar2r.h"\nint main(void)\n{\n    return planar2r_selftest();\n}\n'


@pytest.mark.external  # a C compiler
@pytest.mark.parametrize("acceleration", [False, True])
def test_the_c99_runtime_compiles_without_warnings_and_nothing_unused_remains(tmp_path, acceleration):
    if shutil.which("gcc") is None:
        pytest.skip("gcc is not installed")
    files = _files("planar2r", "c99", acceleration)
    for name, text in files.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    (tmp_path / "main.c").write_text(C_MAIN, encoding="utf-8")
    flags = ["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"]
    subprocess.run([*flags, "planar2r.c", "main.c", "-o", "main", "-lm"], cwd=tmp_path, check=True,
                   capture_output=True, text=True, timeout=120)
    assert subprocess.run([str(tmp_path / "main")], check=False, timeout=60).returncode == 0  # no failed check
    # without inline, an unused static function warns (-Wunused-function): every runtime function is called
    plain = [*flags, "-Dinline=", "-c", "planar2r.c", "-o", "plain.o"]
    result = subprocess.run(plain, cwd=tmp_path, capture_output=True, text=True, check=False, timeout=120)
    assert result.returncode == 0, result.stderr
    # and the check can fail: the whole runtime has unused functions
    whole = files["planar2r.c"].replace(runtime_source("c99.h", describe(ModuleRequest(
        load_robot("planar2r"), "c99", acceleration=acceleration)).runtime_sections).rstrip("\n"),
        runtime_source("c99.h").rstrip("\n"))
    (tmp_path / "planar2r.c").write_text(whole, encoding="utf-8")
    result = subprocess.run(plain, cwd=tmp_path, capture_output=True, text=True, check=False, timeout=120)
    assert result.returncode != 0 and "unused" in result.stderr


CPP_MAIN = """#include <cstdio>
#include "planar2r.hpp"
int main()
{
    const Eigen::Vector2d q(0.3, -0.7);
    const double w = symjac::planar2r::manipulability(q);
    std::printf("%.17g\\n", w);
#ifdef GRADIENT
    const Eigen::Vector2d g = symjac::planar2r::manipulability_gradient(q);
    std::printf("%.17g %.17g\\n", g(0), g(1));
#endif
    return w > 0 ? 0 : 1;
}
"""


@pytest.mark.external  # a C++ compiler and Eigen
@pytest.mark.parametrize("acceleration", [False, True])
def test_the_cpp_runtime_compiles_without_warnings(tmp_path, acceleration):
    if shutil.which("g++") is None or not Path("/usr/include/eigen3/Eigen/Dense").is_file():
        pytest.skip("g++ or Eigen's headers (Debian libeigen3-dev) are missing")
    for name, text in _files("planar2r", "cpp", acceleration).items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    (tmp_path / "main.cpp").write_text(CPP_MAIN, encoding="utf-8")
    define = ["-DGRADIENT"] if acceleration else []
    subprocess.run(["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-I/usr/include/eigen3", *define, "main.cpp",
                    "-o", "main"], cwd=tmp_path, check=True, capture_output=True, text=True, timeout=300)
    assert subprocess.run([str(tmp_path / "main")], check=False, capture_output=True, timeout=60).returncode == 0

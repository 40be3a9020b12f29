"""The throwaway quantity ``tool_position``: one module, in every front end and every codegen target.

Each value is checked against an independent computation: the tool frame's origin relative to frame {0} from
``tests/reference.py``'s plain-NumPy frames.
"""

from __future__ import annotations

import contextlib
import ctypes
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from compiled import load_module
from reference import evaluate, frame_index, frames

from symjac import load_robot
from symjac.codegen import render_files
from symjac.codegen.module import ModuleRequest, describe
from symjac.quantities import QUANTITIES

ROBOTS = ("planar2r", "palletizer")  # light, and a coupled one (the rates law)
PYTHON_TARGETS = ("python", "numpy", "lambdify", "jax", "casadi")
EIGEN = Path("/usr/include/eigen3")


def reference_position(robot, q: np.ndarray) -> np.ndarray:
    poses = frames(robot, q)
    return (np.linalg.inv(poses[frame_index(robot, 0)]) @ poses[frame_index(robot, "tool")])[:3, 3]


def configurations(robot, count: int = 5) -> list[np.ndarray]:
    rng = np.random.default_rng(11)
    return [rng.uniform(-np.pi, np.pi, robot.n_coordinates) for _ in range(count)]


@pytest.mark.parametrize("name", ROBOTS)
def test_python_api_against_numpy_frames(name):
    robot = load_robot(name)
    p = QUANTITIES["tool_position"].derive(robot)
    assert p.shape == (3, 1)
    for q in configurations(robot):
        np.testing.assert_allclose(evaluate(p, robot, q).ravel(), reference_position(robot, q), atol=1e-12)


@pytest.mark.parametrize("name", ROBOTS)
def test_cli_latex_pretty_and_json(cli, name):
    robot = load_robot(name)
    assert cli.latex_line("position", name).startswith(r"{}^{0}p_{t} = \begin{bmatrix}")
    pretty = cli.ok("position", name, "--format", "pretty")
    assert pretty.startswith("Position of the tool point in frame {0}\np_0_t =")
    data = cli.json("position", name)
    assert data["robot"] == name and data["shape"] == [3] and data["latex"].startswith("{}^{0}p_{t} =")
    entries = [sp.sympify(entry) for entry in data["entries"]]
    for q in configurations(robot, 3):
        values = {**{str(s): float(v) for s, v in robot.defaults.items()},
                  **{str(s): float(v) for s, v in zip(robot.q, q, strict=True)}}
        got = [float(e.subs({s: values[str(s)] for s in e.free_symbols})) for e in entries]
        np.testing.assert_allclose(got, reference_position(robot, q), atol=1e-12)


@pytest.mark.parametrize("target", PYTHON_TARGETS)
@pytest.mark.parametrize("name", ROBOTS)
def test_python_family_targets(tmp_path, name, target):
    robot = load_robot(name)
    module = load_module(tmp_path, robot, target)
    assert "tool_position" in module.__all__
    with _double_precision(target):
        for q in configurations(robot):
            extra = (module.PARAMETER_DEFAULTS,) if target == "casadi" else ()  # CasADi takes (q, p)
            got = np.ravel(np.asarray(module.tool_position(q, *extra), dtype=float))
            np.testing.assert_allclose(got, reference_position(robot, q), rtol=1e-12, atol=1e-12)
        assert module.selftest() <= 1e-6


def _double_precision(target: str) -> contextlib.AbstractContextManager:
    """JAX computes in float32 unless x64 is on: on here, for this test only."""
    if target != "jax":
        return contextlib.nullcontext()
    import jax

    return jax.enable_x64(True)


@pytest.mark.external
@pytest.mark.parametrize("name", ROBOTS)
def test_c_extension_target(tmp_path, name):
    robot = load_robot(name)
    module = load_module(tmp_path, robot, "c")
    assert module.BACKEND == "c", module.BUILD_ERROR
    qs = np.array(configurations(robot))
    got = module.tool_position(qs)
    np.testing.assert_allclose(got, [reference_position(robot, q) for q in qs], rtol=1e-12, atol=1e-12)
    assert module.selftest() <= 1e-6


@pytest.mark.external
@pytest.mark.skipif(shutil.which("gcc") is None, reason="gcc is not installed")
@pytest.mark.parametrize("name", ROBOTS)
def test_c99_target(tmp_path, name):
    robot = load_robot(name)
    files = render_files(describe(ModuleRequest(robot, "c99")))
    for file, text in files.items():
        (tmp_path / file).write_text(text)
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2", "-fPIC", "-shared",
                    f"{name}.c", "-o", "libarm.so", "-lm"], cwd=tmp_path, check=True, capture_output=True)
    library = ctypes.CDLL(str(tmp_path / "libarm.so"))
    pointer = ctypes.POINTER(ctypes.c_double)
    for q in configurations(robot):
        q = np.ascontiguousarray(q)
        out = np.zeros(3)
        getattr(library, f"{name}_tool_position")(q.ctypes.data_as(pointer), None, out.ctypes.data_as(pointer))
        np.testing.assert_allclose(out, reference_position(robot, q), rtol=1e-12, atol=1e-12)
    assert getattr(library, f"{name}_selftest")() == 0


MAIN = """#include <cstdio>
#include "{robot}.hpp"

int main()
{{
    using namespace symjac::{robot};
    const double qs[][n_coordinates] = {{{rows}}};
    for (const auto &row : qs) {{
        const auto p = tool_position(Eigen::Matrix<double, n_coordinates, 1>(row));
        std::printf("%.17g %.17g %.17g\\n", p(0), p(1), p(2));
    }}
    return 0;
}}
"""


@pytest.mark.external
@pytest.mark.skipif(shutil.which("g++") is None or not (EIGEN / "Eigen" / "Dense").is_file(), reason="no g++ or Eigen")
@pytest.mark.parametrize("name", ROBOTS)
def test_cpp_target(tmp_path, name):
    robot = load_robot(name)
    for file, text in render_files(describe(ModuleRequest(robot, "cpp"))).items():
        (tmp_path / file).write_text(text)
    qs = configurations(robot)
    rows = ", ".join("{" + ", ".join(repr(float(v)) for v in q) + "}" for q in qs)
    (tmp_path / "main.cpp").write_text(MAIN.format(robot=name, rows=rows))
    subprocess.run(["g++", "-std=c++17", "-O2", "-Wall", "-Wextra", "-Werror", f"-I{EIGEN}", "main.cpp", "-o", "main"],
                   cwd=tmp_path, check=True, capture_output=True)
    lines = subprocess.run([str(tmp_path / "main")], check=True, capture_output=True, text=True).stdout.split("\n")
    for q, line in zip(qs, lines, strict=False):
        np.testing.assert_allclose([float(v) for v in line.split()], reference_position(robot, q), rtol=1e-12,
                                   atol=1e-12)
    assert len([line for line in lines if line]) == len(qs)  # the cpp target has no self-test of its own

"""Code generation for generic geometry: nested chains (intermediates) lowered straight into temporaries.

Three small generic arms, a standard-DH arm with generic twists (a parameter, a prismatic joint with an offset), a
product-of-exponentials arm with calibrated float screws and a coupled modified-DH arm, are derived nested
(:mod:`symjac.symbolic.nested`). Their generated modules must agree with an independent numeric chain
(:mod:`reference`) and with symjac's own symbolic results, pass their self-tests with the acceleration level, stay
ruff-clean and deterministic, and never show an intermediate's name; one compiled case (c99, ``-Wall -Wextra
-Werror``) agrees with the python target.
"""

from __future__ import annotations

import ctypes
import hashlib
import importlib.util
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from compiled import load_module
from reference import end_of_chain, finite_difference_jacobian, frames

from symjac import Chain, jacobian, robot_from_mapping
from symjac.cli.main import main
from symjac.codegen import ModuleRequest, describe, generate, render_files
from symjac.symbolic.nested import has_intermediates, substitute

REPO = Path(__file__).resolve().parent.parent


def _unit(v: list[float]) -> list[float]:
    norm = math.sqrt(sum(x * x for x in v))
    return [round(x / norm, 6) for x in v]


def _screw(axis: list[float], point: list[float]) -> list[float]:
    """A revolute screw (omega, v = -omega x point), rounded as a calibration file would hold it."""
    w = _unit(axis)
    v = [-(w[1] * point[2] - w[2] * point[1]), -(w[2] * point[0] - w[0] * point[2]),
         -(w[0] * point[1] - w[1] * point[0])]
    return [*w, *(round(x, 6) for x in v)]


def dh_arm():
    """Standard DH, generic twists, a length parameter and a prismatic joint with a theta offset."""
    return robot_from_mapping({"name": "generic4", "convention": "standard", "parameters": {"L": 0.35}, "joints": [
        {"type": "revolute", "a": 0.31, "d": 0.12, "alpha": 1.2},
        {"type": "revolute", "a": "L", "d": -0.2, "alpha": -0.7},
        {"type": "prismatic", "a": 0.2, "theta": 0.4, "alpha": 0.9},
        {"type": "revolute", "a": 0.1, "d": 0.05, "alpha": 2.1}]})


def poe_arm():
    """Product of exponentials with calibrated float screws and a home pose."""
    return robot_from_mapping({"name": "poe3", "convention": "poe",
                               "home": {"matrix": [[1, 0, 0, 0.7], [0, 1, 0, 0.1], [0, 0, 1, 0.3], [0, 0, 0, 1]]},
                               "joints": [{"type": "revolute", "screw": _screw([0.02, -0.01, 1.0], [0, 0, 0])},
                                          {"type": "revolute", "screw": _screw([-0.438, 0.758, -0.483],
                                                                               [0.1, 0.02, 0.3])},
                                          {"type": "revolute", "screw": _screw([0.3, 0.9, 0.1],
                                                                               [0.5, -0.03, 0.31])}]})


def coupled_arm():
    """Modified DH, a calibrated twist and a coupled joint (theta3 = -theta2): its coordinates are not its joints."""
    return robot_from_mapping({"name": "coupled3", "convention": "modified", "parameters": {"L1": 0.4}, "joints": [
        {"type": "revolute", "d": 0.3},
        {"type": "revolute", "alpha": -1.5702, "a": 0.05},
        {"type": "revolute", "a": "L1", "coupled": "-theta2"},
        {"type": "revolute", "alpha": 0.0004, "a": 0.3, "d": 0.02}]})


ARMS = {"dh": dh_arm, "poe": poe_arm, "coupled": coupled_arm}


def _configurations(robot, count: int = 5) -> list[np.ndarray]:
    rng = np.random.default_rng(3)
    return [rng.uniform(-np.pi, np.pi, robot.n_coordinates) for _ in range(count)]


@pytest.mark.parametrize("arm", sorted(ARMS))
def test_the_arms_are_derived_nested(arm):
    chain = Chain(ARMS[arm]())
    assert chain.nested
    assert has_intermediates(chain.transform(0, "tool"))


@pytest.mark.parametrize("target", ["python", "numpy"])
@pytest.mark.parametrize("arm", sorted(ARMS))
def test_generated_modules_agree_with_a_numeric_chain_and_finite_differences(tmp_path, arm, target):
    robot = ARMS[arm]()
    module = load_module(tmp_path, robot, target, acceleration=True)
    assert module.selftest() < 1e-6  # Jacobian, torques, Hessian, bias acceleration against differences
    n = robot.n_coordinates
    for q in _configurations(robot):
        T = np.asarray(module.forward_kinematics(q), dtype=float).reshape(4, 4)
        np.testing.assert_allclose(T, frames(robot, q)[-1], atol=1e-12)
        J = np.asarray(module.jacobian(q), dtype=float).reshape(6, n)
        np.testing.assert_allclose(J, finite_difference_jacobian(robot, q, point=end_of_chain(robot)), atol=1e-7)


@pytest.mark.parametrize("arm", ["dh", "poe"])  # a coupled arm's raw nested J_q still holds a joint variable
def test_the_python_target_equals_the_symbolic_nested_jacobian(tmp_path, arm):
    robot = ARMS[arm]()
    chain = Chain(robot)
    module = load_module(tmp_path, robot, "python")
    J_symbolic = jacobian(chain, simplify=False)
    for q in _configurations(robot, 3):
        values = {**robot.defaults, **dict(zip(robot.q, q, strict=True))}
        expected = np.array([float(v) for v in substitute(list(J_symbolic), values)]).reshape(6, -1)
        np.testing.assert_allclose(np.asarray(module.jacobian(q), dtype=float), expected, atol=1e-12)


@pytest.mark.parametrize("arm", sorted(ARMS))
def test_generation_is_deterministic_and_shows_no_intermediate(arm):
    robot = ARMS[arm]()
    first = generate(robot, "python", acceleration=True)
    assert generate(Chain(ARMS[arm]()), "python", acceleration=True) == first  # a fresh chain: new intermediates
    assert "_w" not in first and "Dummy" not in first and "_h" not in first
    assert "x0 = " in first  # temporaries numbered as for any robot


GENERATE = """
import hashlib, sys
sys.path.insert(0, sys.argv[1])
from test_codegen_nested import ARMS
from symjac.codegen import generate
print(hashlib.sha256(generate(ARMS[sys.argv[2]](), "numpy", acceleration=True).encode()).hexdigest())
"""


@pytest.mark.slow  # a second interpreter imports SymPy and derives again
def test_generation_is_byte_identical_in_a_fresh_process_with_another_hash_seed():
    expected = hashlib.sha256(generate(poe_arm(), "numpy", acceleration=True).encode()).hexdigest()
    env = {**os.environ, "PYTHONHASHSEED": "7", "PYTHONPATH": os.pathsep.join([str(REPO), *sys.path])}
    result = subprocess.run([sys.executable, "-c", GENERATE, str(Path(__file__).parent), "poe"], env=env,
                            capture_output=True, text=True, timeout=120, check=True)
    assert result.stdout.strip() == expected


def test_generated_modules_are_ruff_clean(tmp_path):
    if shutil.which("ruff") is None:
        pytest.skip("ruff is not installed")
    for make in ARMS.values():
        for target in ("python", "numpy"):
            (tmp_path / f"{make().name}_{target}.py").write_text(generate(make(), target, acceleration=True))
    result = subprocess.run(["ruff", "check", "--no-cache", "--config", str(REPO / "pyproject.toml"),
                             *sorted(str(p) for p in tmp_path.glob("*.py"))], capture_output=True, text=True,
                            timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr


def test_the_command_line_generates_a_robot_file_with_generic_twists(tmp_path, capsys):
    path = tmp_path / "generic3.toml"
    joints = [(0.31, 0.12, 1.2), (0.4, -0.2, -0.7), (0.2, 0.05, 0.9)]
    path.write_text('name = "generic3"\nconvention = "standard"\n' + "".join(
        f'[[joints]]\ntype = "revolute"\na = {a}\nd = {d}\nalpha = {alpha}\n' for a, d, alpha in joints))
    out = tmp_path / "generic3_numpy.py"
    assert main(["codegen", str(path), "--target", "numpy", "-o", str(out)]) == 0
    spec = importlib.util.spec_from_file_location("generic3_numpy_cli", out)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.selftest() < 1e-6


@pytest.mark.external  # a C compiler
def test_the_c99_target_compiles_cleanly_and_agrees_with_the_python_target(tmp_path):
    if shutil.which("gcc") is None:  # pragma: no cover - .ci/run installs it
        pytest.skip("gcc is missing")
    robot = dh_arm()
    files = render_files(describe(ModuleRequest(robot, "c99", acceleration=True)))
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    source = next(name for name in files if name.endswith(".c"))
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O1", "-fPIC", "-shared", source, "-o",
                    "libarm.so", "-lm"], cwd=tmp_path, check=True, capture_output=True, text=True)
    library = ctypes.CDLL(str(tmp_path / "libarm.so"))
    prefix = source.removesuffix(".c")
    assert getattr(library, f"{prefix}_selftest")() == 0
    reference = load_module(tmp_path, robot, "python", acceleration=True)
    n = robot.n_coordinates
    pointer = ctypes.POINTER(ctypes.c_double)
    for q in _configurations(robot):
        q = np.ascontiguousarray(q)
        J = np.zeros(6 * n)
        getattr(library, f"{prefix}_jacobian")(q.ctypes.data_as(pointer), None, J.ctypes.data_as(pointer))
        np.testing.assert_allclose(J, np.ravel(reference.jacobian(q)), rtol=1e-12, atol=1e-12)
        H = np.zeros(6 * n * n)
        getattr(library, f"{prefix}_hessian")(q.ctypes.data_as(pointer), None, H.ctypes.data_as(pointer))
        np.testing.assert_allclose(H, np.ravel(reference.hessian(q)), rtol=1e-12, atol=1e-12)

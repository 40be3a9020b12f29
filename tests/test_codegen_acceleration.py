"""Generated acceleration-level functions: the Hessian, the bias acceleration Jdot qdot, the manipulability gradient.

They are generated with ``generate(..., acceleration=True)`` (CLI ``--acceleration``) and checked here against
``symjac.kinematics.acceleration`` evaluated numerically, against central differences of the module's own Jacobian and
manipulability, and for determinism, ruff and golden files (``tests/golden/*_acceleration*``; regenerate them with
``SYMJAC_UPDATE_GOLDEN=1``). Modules without the option must not change (the other golden files check that).
"""

from __future__ import annotations

import dataclasses
import functools
import importlib.util
import os
import shlex
import shutil
import subprocess
import types
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from marks import PYTHON_TARGETS, marked

from symjac import Chain, Parameter, clear_caches, joint_rate_symbols, load_robot
from symjac.codegen import BACKENDS, CodegenError, JacobianRequest, generate, write_module
from symjac.codegen.acceleration import lowered_bias_acceleration
from symjac.codegen.lower import lowered_jacobian
from symjac.kinematics.acceleration import bias_acceleration, hessian
from symjac.kinematics.numeric import numeric_at

REPO = Path(__file__).resolve().parent.parent
GOLDEN = Path(__file__).resolve().parent / "golden"
TIMEOUT = 120


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    """A folder outside the repository for generated modules, and a private cache for compiled C kernels."""
    directory = tmp_path_factory.mktemp("acceleration")
    previous = os.environ.get("SYMJAC_CACHE_DIR")
    os.environ["SYMJAC_CACHE_DIR"] = str(tmp_path_factory.mktemp("c-cache"))
    yield directory
    if previous is None:
        os.environ.pop("SYMJAC_CACHE_DIR", None)
    else:
        os.environ["SYMJAC_CACHE_DIR"] = previous


def _requests(name: str) -> list[JacobianRequest]:
    """A fixed frame at the wrist, and a moving frame at an offset point with a subset of the rows."""
    if name == "panda":
        return [JacobianRequest(0, "tool")]
    point = (sp.Rational(1, 10), sp.Rational(-1, 5), sp.Rational(3, 10))
    return [JacobianRequest(0, "wrist"), JacobianRequest(3, point, (0, 1, 2, 5))]


_MODULES: dict[tuple[str, str], types.ModuleType] = {}


def _module(workspace: Path, name: str, target: str) -> types.ModuleType:
    if (name, target) not in _MODULES:
        path = workspace / f"{name}_{target}_acceleration.py"
        write_module(path, generate(load_robot(name), target, jacobians=_requests(name), acceleration=True))
        spec = importlib.util.spec_from_file_location(f"acceleration_{name}_{target}", path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        _MODULES[name, target] = module
    return _MODULES[name, target]


def _suffixes(name: str) -> list[str]:
    return [""] if name == "panda" else ["", "_3_p1_r0125"]


@functools.cache
def _references(name: str) -> list[dict[str, object]]:
    """Per seeded configuration and request: symjac.kinematics.acceleration's Hessian and Jdot qdot, evaluated
    numerically."""
    robot = load_robot(name)
    rates = joint_rate_symbols(robot)
    rng = np.random.default_rng(5)
    cases = []
    for _ in range(2):
        q = rng.uniform(-np.pi, np.pi, robot.n_coordinates)
        qdot = rng.uniform(-1.0, 1.0, robot.n_coordinates)
        per_request = []
        for request in _requests(name):
            rows = list(request.rows or range(6))
            H = hessian(robot, request.frame, request.point, simplify=False)
            flat = numeric_at(robot, sp.Matrix(H.reshape(6, robot.n_coordinates ** 2).tolist()), q)
            bias = bias_acceleration(robot, request.frame, request.point, simplify=False)
            speeds = {rate: sp.Float(float(value)) for rate, value in zip(rates, qdot, strict=True)}
            per_request.append((flat.reshape(6, robot.n_coordinates, robot.n_coordinates)[rows],
                                numeric_at(robot, bias.xreplace(speeds), q).ravel()[rows]))
        cases.append({"q": q, "qdot": qdot, "expected": per_request})
    return cases


def _call(module: types.ModuleType, target: str, function: str, *arguments: np.ndarray) -> np.ndarray:
    batched = BACKENDS[target].batched
    return np.array(getattr(module, function)(*(a if batched else list(a) for a in arguments)), dtype=float)


def _central(function, q: np.ndarray, direction: np.ndarray, step: float = 1e-6) -> np.ndarray:
    return (function(q + step * direction) - function(q - step * direction)) / (2 * step)


CASES = [(name, target) for name in ("puma560", "stanford") for target in PYTHON_TARGETS] + [("panda", "numpy")]


@pytest.mark.parametrize(("name", "target"), marked(CASES))
def test_acceleration_functions_agree_with_symjac_and_differences(workspace, name, target):
    module = _module(workspace, name, target)
    for case in _references(name):
        q, qdot = case["q"], case["qdot"]
        for suffix, (H_expected, bias_expected) in zip(_suffixes(name), case["expected"], strict=True):
            def J(x, suffix=suffix):
                return _call(module, target, f"jacobian{suffix}", x)

            def w(x, suffix=suffix):
                return float(getattr(module, f"manipulability{suffix}")(list(x)))

            H = _call(module, target, f"hessian{suffix}", q)
            assert H.shape == H_expected.shape
            np.testing.assert_allclose(H, H_expected, atol=1e-12)
            bias = _call(module, target, f"bias_acceleration{suffix}", q, qdot)
            np.testing.assert_allclose(bias, bias_expected, atol=1e-12)
            identity = np.eye(len(q))
            for m in range(len(q)):
                np.testing.assert_allclose(H[..., m], _central(J, q, identity[m]), atol=1e-7)
            np.testing.assert_allclose(bias, _central(J, q, qdot) @ qdot, atol=1e-7)
            gradient = _call(module, target, f"manipulability_gradient{suffix}", q)
            differences = np.array([_central(w, q, identity[m]) for m in range(len(q))])
            np.testing.assert_allclose(gradient, differences, atol=1e-7)
    assert module.selftest() < 1e-6


def test_batched_targets_keep_the_batch_axes_in_front(workspace):
    module = _module(workspace, "stanford", "numpy")
    rng = np.random.default_rng(2)
    q, qdot = rng.uniform(-1, 1, (4, 3, 6)), rng.uniform(-1, 1, (4, 3, 6))
    assert module.hessian(q).shape == (4, 3, 6, 6, 6)
    assert module.hessian_3_p1_r0125(q).shape == (4, 3, 4, 6, 6)
    assert module.bias_acceleration(q, qdot).shape == (4, 3, 6)
    assert module.manipulability_gradient_3_p1_r0125(q).shape == (4, 3, 6)
    np.testing.assert_array_equal(module.bias_acceleration(q, qdot)[2, 1],
                                  module.bias_acceleration(q[2, 1], qdot[2, 1]))


@pytest.mark.parametrize("target", ["python", "numpy"])
def test_gradient_at_singular_configurations(workspace, target):
    # theta5 = 0: w has a kink; rounding leaves it tiny but not zero, and the gradient stays finite and bounded
    module = _module(workspace, "puma560", target)
    q = [0.3, -0.4, 0.0, 0.2, 0.0, 0.1]
    assert float(module.manipulability(q)) < 1e-12
    assert np.all(np.abs(np.array(module.manipulability_gradient(q))) < 1.0)
    # where the Gram determinant is exactly zero the result is zero, and NaN still propagates
    namespace: dict = {}
    source = generate(load_robot("planar2r"), target, rows=(0, 1), acceleration=True)
    exec(compile(source, f"planar2r_{target}.py", "exec"), namespace)
    assert np.array(namespace["manipulability_gradient"]([0.0, 0.0])).tolist() == [0.0, 0.0]
    with np.errstate(invalid="ignore"):  # numpy.linalg.det warns about the NaN it returns
        assert np.isnan(np.array(namespace["manipulability_gradient"]([float("nan"), 0.0]))).all()


def test_puma_bias_costs_at_most_twice_the_jacobian():
    chain = Chain(load_robot("puma560"))
    point, rows = (sp.S.Zero,) * 3, tuple(range(6))
    J = lowered_jacobian(chain, 0, point, rows, "fastest")
    bias = lowered_bias_acceleration(chain, 0, point, rows, "fastest")
    assert bias.op_count <= 2 * J.op_count, (bias.op_count, J.op_count)
    assert bias.trig_count <= J.trig_count


@pytest.mark.slow
def test_generation_is_byte_identical_and_the_option_changes_nothing_else():
    robot = load_robot("stanford")
    requests = _requests("stanford")
    first = generate(robot, "c", jacobians=requests, acceleration=True)
    assert generate(Chain(robot), "c", jacobians=requests, acceleration=True) == first
    clear_caches()
    assert generate(robot, "c", jacobians=requests, acceleration=True) == first
    plain = generate(robot, "python", jacobians=requests)
    assert "hessian" not in plain and "bias_acceleration" not in plain and "acceleration=True" not in plain
    assert "acceleration=True" in generate(robot, "python", jacobians=requests, acceleration=True)


@pytest.mark.parametrize("target", PYTHON_TARGETS)
def test_golden_files(target):
    text = generate(load_robot("planar2r"), target, acceleration=True)
    path = GOLDEN / f"planar2r_{target}_acceleration{BACKENDS[target].suffix}.golden"
    if os.environ.get("SYMJAC_UPDATE_GOLDEN") == "1":
        write_module(path, text)
    assert path.is_file(), f"missing {path.name}: run with SYMJAC_UPDATE_GOLDEN=1 to create it"
    assert text == path.read_text(encoding="utf-8"), f"{path.name} differs; regenerate with SYMJAC_UPDATE_GOLDEN=1"


@pytest.mark.slow
def test_generated_modules_are_ruff_clean(workspace):
    if shutil.which("ruff") is None:
        pytest.skip("ruff is not installed")
    for name, target in CASES:
        _module(workspace, name, target)
    files = sorted(str(path) for path in workspace.glob("*_acceleration.py"))
    assert len(files) == len(CASES)
    result = subprocess.run(["ruff", "check", "--no-cache", "--config", str(REPO / "pyproject.toml"), *files],
                            capture_output=True, text=True, timeout=TIMEOUT, check=False)
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.parametrize(("parameter", "message"), [
    ("qdot", "parameter name 'qdot' clashes with an argument of the generated functions"),
    ("hessian", "parameter name 'hessian' clashes with a function of the generated module"),
])
def test_new_names_are_reserved(parameter, message):
    robot = load_robot("planar2r")
    renamed = dataclasses.replace(robot, parameters=(Parameter(parameter, sp.Rational(1, 2)), *robot.parameters[1:]))
    with pytest.raises(CodegenError, match=message):
        generate(renamed, "python", acceleration=True)


def test_command_line_option(tmp_path):
    from symjac.cli.main import main

    path = tmp_path / "planar.py"
    argv = ["codegen", "planar2r", "--target", "numpy", "--acceleration", "-o", str(path)]
    assert main(argv) == 0
    expected = generate(load_robot("planar2r"), "numpy", jacobians=[JacobianRequest(0, "wrist")],
                        command=shlex.join(["symjac", *argv]), acceleration=True)
    assert path.read_text(encoding="utf-8") == expected
    assert "def manipulability_gradient(" in expected


def test_frames_carried_by_every_joint_and_long_names():
    # the tool frame turns with every joint (the moving-frame terms of all of them), "world" with none; the long
    # function names must still fit the line width in every target (the C kernels' signatures are wrapped)
    robot = load_robot("planar3r")
    requests = [JacobianRequest("world", "tool"), JacobianRequest("tool", "tool", (0, 1, 5))]
    namespace: dict = {}
    exec(compile(generate(robot, "python", jacobians=requests, acceleration=True), "planar3r.py", "exec"), namespace)
    assert namespace["selftest"](samples=5) < 1e-6
    q, qdot = [0.3, -0.7, 1.1], [0.5, -0.2, 0.9]
    expected = numeric_at(robot, bias_acceleration(robot, "tool", "tool", simplify=False).xreplace(
        dict(zip(joint_rate_symbols(robot), map(sp.Float, qdot), strict=True))), q).ravel()[[0, 1, 5]]
    np.testing.assert_allclose(namespace["bias_acceleration_tool_tool_r015"](q, qdot), expected, atol=1e-12)
    assert "k_bias_acceleration_tool_tool_r015(" in generate(robot, "c", jacobians=requests, acceleration=True)


@pytest.mark.parametrize("target", ["python", "numpy"])
def test_the_self_test_passes_by_default_with_a_sample_near_a_singularity(tmp_path, target):
    # the palletizer's first default sample has theta3 ~ -6.5e-4 (w ~ 1.5e-3): a central difference of w itself
    # there is off by 1e-6 from rounding alone (the square root divides det's rounding by w); w^2 is not
    path = tmp_path / f"pallet_{target}.py"
    write_module(path, generate(load_robot("palletizer"), target, acceleration=True))
    spec = importlib.util.spec_from_file_location(f"pallet_{target}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert module.selftest() < 1e-6

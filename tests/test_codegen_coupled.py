"""Generated modules for coupled robots: every target takes q in the independent coordinates.

The robots are those of ``test_coordinates.py`` (a palletizer with theta4 = -(theta2 + theta3), the same arm without
its flange joint, a SCARA whose ball screw follows the wrist, d3 = k theta4 + d30 with symbolic k and d30). Each
module is checked against symjac's symbolic results in the coordinates (J_q, forward kinematics, C^T J^T F, the
Hessian, the bias acceleration) evaluated numerically, against central differences of its own forward kinematics, by
its own self-test, by ruff and, for the c target, by the C compiler with every warning an error.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib.util
import shutil
import subprocess
import sysconfig
import types
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from marks import PYTHON_TARGETS, marked
from test_coordinates import ROBOTS

from symjac import forward_kinematics, jacobian, joint_rate_symbols, load_robot
from symjac.codegen import JacobianRequest, generate, write_module
from symjac.kinematics.acceleration import bias_acceleration, hessian
from symjac.kinematics.statics import joint_torques
from symjac.model.coordinates import Coupling

REPO = Path(__file__).resolve().parent.parent
POINT = (sp.Rational(1, 10), sp.Rational(-1, 5), sp.Rational(3, 10))
WRENCH = np.array([0.3, -1.2, 2.0, 0.1, 0.4, -0.6])
H = 1e-6


@functools.cache
def _robot(name: str):
    return ROBOTS[name]()


def _requests(name: str) -> list[JacobianRequest]:
    """The base frame at the wrist (all rows), and a moving frame at an offset point with a square set of rows."""
    square = (0, 1, 2, 5)[:_robot(name).n_coordinates]
    return [JacobianRequest(0, "wrist"), JacobianRequest(2, POINT, square)]


@pytest.fixture(scope="module")
def workspace(tmp_path_factory, monkeypatch_module):
    monkeypatch_module.setenv("SYMJAC_CACHE_DIR", str(tmp_path_factory.mktemp("c-cache")))
    return tmp_path_factory.mktemp("coupled")


@pytest.fixture(scope="module")
def monkeypatch_module():
    with pytest.MonkeyPatch.context() as patch:
        yield patch


_MODULES: dict[tuple[str, str], types.ModuleType] = {}


def _module(workspace: Path, name: str, target: str) -> types.ModuleType:
    if (name, target) not in _MODULES:
        path = workspace / f"{name}_{target}.py"
        write_module(path, generate(_robot(name), target, jacobians=_requests(name), acceleration=True))
        spec = importlib.util.spec_from_file_location(f"coupled_{name}_{target}", path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        _MODULES[name, target] = module
    return _MODULES[name, target]


@functools.cache
def _reference(name: str, index: int) -> dict[str, object]:
    """symjac's symbolic results in the coordinates for request ``index``, as NumPy functions of (q, qdot)."""
    robot = _robot(name)
    request = _requests(name)[index]
    rows = list(request.rows or range(6))
    arguments = [*robot.q, *joint_rate_symbols(robot), *robot.parameter_symbols]

    def compiled(expr: sp.Expr | sp.NDimArray | sp.MatrixBase):
        return sp.lambdify(arguments, sp.Array(expr).tolist(), "numpy")

    Hq = hessian(robot, request.frame, request.point, simplify=False)
    return {
        "jacobian": compiled(sp.Matrix(jacobian(robot, request.frame, request.point, simplify=False))[rows, :]),
        "torques": compiled(joint_torques(robot, [w if r in rows else 0 for r, w in enumerate(WRENCH)],
                                          request.frame, request.point)),
        "hessian": compiled(sp.Array([[[Hq[i, j, m] for m in range(robot.n_coordinates)]
                                       for j in range(robot.n_coordinates)] for i in rows])),
        "bias": compiled(sp.Matrix(bias_acceleration(robot, request.frame, request.point, simplify=False))[rows, :]),
        "fk": compiled(forward_kinematics(robot, 0, "tool")),
    }


def _configurations(robot, count: int = 3) -> list[tuple[np.ndarray, np.ndarray]]:
    rng = np.random.default_rng(28)
    return [(rng.uniform(-2.5, 2.5, robot.n_coordinates), rng.uniform(-1.0, 1.0, robot.n_coordinates))
            for _ in range(count)]


def _call(module: types.ModuleType, function: str, *arguments: np.ndarray) -> np.ndarray:
    return np.asarray(getattr(module, function)(*(list(a) for a in arguments)), dtype=float)


CASES = [(name, target) for name in sorted(ROBOTS) for target in PYTHON_TARGETS]


@pytest.mark.parametrize(("name", "target"), marked(CASES))
def test_module_matches_the_symbolic_results_in_the_coordinates(workspace, name, target):
    robot = _robot(name)
    module = _module(workspace, name, target)
    defaults = [float(robot.defaults[p]) for p in robot.parameter_symbols]
    assert tuple(c.name for c in robot.q) == module.COORDINATES
    assert module.selftest() < 1e-6
    for index, suffix in enumerate(["", f"_2_p1_r{''.join(map(str, _requests(name)[1].rows))}"]):
        reference = _reference(name, index)
        rows = _requests(name)[index].rows or tuple(range(6))
        for q, qdot in _configurations(robot):
            at = (*q, *qdot, *defaults)
            J = _call(module, f"jacobian{suffix}", q)
            assert J.shape == (len(rows), robot.n_coordinates)
            np.testing.assert_allclose(J, np.array(reference["jacobian"](*at), dtype=float), atol=1e-10)
            np.testing.assert_allclose(_call(module, f"joint_torques{suffix}", q, WRENCH[list(rows)]),
                                       np.array(reference["torques"](*at), dtype=float).ravel(), atol=1e-10)
            np.testing.assert_allclose(_call(module, f"hessian{suffix}", q),
                                       np.array(reference["hessian"](*at), dtype=float), atol=1e-10)
            np.testing.assert_allclose(_call(module, f"bias_acceleration{suffix}", q, qdot),
                                       np.array(reference["bias"](*at), dtype=float).ravel(), atol=1e-10)
            np.testing.assert_allclose(_call(module, "forward_kinematics", q),
                                       np.array(reference["fk"](*at), dtype=float), atol=1e-12)
            if len(rows) == robot.n_coordinates:
                determinant = float(np.asarray(getattr(module, f"jacobian_determinant{suffix}")(list(q))))
                np.testing.assert_allclose(determinant, np.linalg.det(J), atol=1e-10)
                np.testing.assert_allclose(float(np.asarray(getattr(module, f"manipulability{suffix}")(list(q)))),
                                           abs(np.linalg.det(J)), atol=1e-10)


@pytest.mark.parametrize(("name", "target"), marked(CASES))
def test_jacobian_is_a_central_difference_of_the_generated_forward_kinematics(workspace, name, target):
    """Frame {0} at the wrist: dx/dq and omega from R(q + h) R(q - h)^T, all in the coordinates."""
    robot = _robot(name)
    module = _module(workspace, name, target)
    n = robot.n_coordinates
    for q, _ in _configurations(robot):
        expected = np.zeros((6, n))
        R = _call(module, "forward_kinematics", q)[:3, :3]
        for j in range(n):
            step = np.zeros(n)
            step[j] = H
            plus, minus = _call(module, "forward_kinematics", q + step), _call(module, "forward_kinematics", q - step)
            expected[:3, j] = (plus[:3, 3] - minus[:3, 3]) / (2 * H)
            w = (plus[:3, :3] - minus[:3, :3]) / (2 * H) @ R.T
            expected[3:, j] = (w[2, 1], w[0, 2], w[1, 0])
        np.testing.assert_allclose(_call(module, "jacobian", q), expected, atol=1e-7)


@pytest.mark.parametrize("target", PYTHON_TARGETS)
def test_a_symbolic_coupling_coefficient_is_a_parameter(workspace, target):
    """The belt SCARA's k and d30 are keyword parameters: overriding them moves the screw as d3 = k theta4 + d30."""
    robot = _robot("belt_scara")
    module = _module(workspace, "belt_scara", target)
    q = np.array([0.3, -0.7, 1.1])
    k = sp.Symbol("k", real=True)
    values = {**robot.defaults, k: sp.Rational(1, 4), **dict(zip(robot.q, q, strict=True))}
    expected = np.array(sp.Matrix(jacobian(robot, simplify=False)).xreplace(values).evalf(), dtype=float)
    got = np.asarray(module.jacobian(list(q), k=0.25), dtype=float)
    np.testing.assert_allclose(got, expected, atol=1e-12)
    assert abs(got[2, 2]) == pytest.approx(0.25)  # the wrist coordinate moves the screw, along z, by k per radian


@pytest.mark.parametrize("target", PYTHON_TARGETS)
def test_header_and_docstring_say_how_the_joints_couple(target):
    robot = _robot("palletizer")
    text = generate(robot, target)
    header = text.split('"""', 1)[0]
    assert "# Robot: palletizer (5 joints), from " in header
    assert "# Convention: modified DH (Craig)." in header
    assert "# Coupled joints, driven by 4 coordinates q = (theta1, theta2, theta3, theta5):" in header
    assert "#   theta4 = -theta2 - theta3" in header
    docstring = " ".join(text.split('"""', 2)[1].split())
    assert "coupled, driven by 4 independent coordinates q = (theta1, theta2, theta3, theta5)" in docstring
    assert "J_q = J(theta(q)) C" in docstring and "C^T J^T F" in docstring
    assert "One generalised force per coordinate, C^T J^T F." in text and "belongs to coordinate i." in text
    assert "(-theta2 - theta3)" in text  # the flange angle goes to sin/cos written in the coordinates
    assert "theta4" not in text.split('"""', 2)[2]  # and is never a variable of the code


def test_joint_variables_and_rates_that_are_not_coordinates_are_computed_first():
    belt = generate(_robot("belt_scara"), "python", acceleration=True)
    assert "    d3 = d30 + k*theta4\n" in belt and "qdot : sequence of 3 floats" in belt
    palletizer = generate(_robot("palletizer"), "python", acceleration=True)
    assert "    thetadot4 = -thetadot2 - thetadot3\n" in palletizer
    assert "Coordinate rates: thetadot1, thetadot2, thetadot3, thetadot5." in palletizer


@pytest.mark.slow
def test_generated_modules_are_ruff_clean(workspace):
    if shutil.which("ruff") is None:
        pytest.skip("ruff is not installed")
    files = [str(workspace / f"{name}_{target}.py") for name, target in CASES if _module(workspace, name, target)]
    result = subprocess.run(["ruff", "check", "--no-cache", "--config", str(REPO / "pyproject.toml"), *files],
                            capture_output=True, text=True, timeout=120, check=False)
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_c_kernels_compile_with_every_warning_an_error(workspace, tmp_path, name):
    compiler = shutil.which("cc") or shutil.which("gcc")
    include = Path(sysconfig.get_paths()["include"])
    if compiler is None or not (include / "Python.h").is_file():
        pytest.skip("no C compiler or no Python headers")
    module = _module(workspace, name, "c")
    assert module.BACKEND == "c", module.BUILD_ERROR
    source = tmp_path / "kernels.c"
    source.write_text(module._C_SOURCE, encoding="utf-8")
    for extra in ([], [f"-I{np.get_include()}", "-DSYMJAC_NUMPY", "-DSYMJAC_LIBMVEC"]):
        result = subprocess.run([compiler, "-Wall", "-Wextra", "-Werror", "-fsyntax-only", f"-I{include}", *extra,
                                 str(source)], capture_output=True, text=True, timeout=120, check=False)
        assert result.returncode == 0, result.stderr



@pytest.mark.parametrize("target", marked(PYTHON_TARGETS))
def test_renamed_coordinates_give_the_same_numbers_as_the_joint_variables(target):
    """theta_i = q_i (the identity coupling, other names) goes through the coupled route and changes only names."""
    robot = load_robot("scara")
    q = tuple(sp.Symbol(f"q{i + 1}", real=True) for i in range(robot.n_joints))
    renamed = dataclasses.replace(robot, coupling=Coupling(q, q))
    modules = []
    for model in (robot, renamed):
        namespace = types.ModuleType(f"renamed_{target}")
        exec(compile(generate(model, target, acceleration=True), f"{model.name}.py", "exec"), namespace.__dict__)
        modules.append(namespace)
    plain, coupled = modules
    assert coupled.COORDINATES == coupled.JOINTS == ("q1", "q2", "q3", "q4") and coupled.selftest() < 1e-6
    x, rates = [0.3, -0.4, 0.05, 0.7], [0.2, -0.1, 0.3, 0.5]
    for function, arguments in (("forward_kinematics", (x,)), ("jacobian", (x,)), ("joint_torques", (x, WRENCH)),
                                ("hessian", (x,)), ("bias_acceleration", (x, rates))):
        np.testing.assert_allclose(np.asarray(getattr(coupled, function)(*arguments), dtype=float),
                                   np.asarray(getattr(plain, function)(*arguments), dtype=float), atol=1e-13)


@pytest.mark.parametrize("target", ["python", "numpy", "c99", "cpp"])
def test_a_long_point_keeps_every_line_within_the_width(target):
    # the summary of a coupled robot's Jacobian names its point; a long one moves to the module's listing
    point = (sp.Rational(1, 10), -sp.Rational(1, 5), sp.Rational(3, 10))
    text = generate(load_robot("palletizer"), target, jacobians=[JacobianRequest("world", point)])
    assert max(len(line) for line in text.splitlines()) <= 120
    assert "the point the module docstring names" in text and "(1/10, -1/5, 3/10)" in text

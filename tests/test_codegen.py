"""Generated modules: correct against independent references, deterministic, ruff-clean, self-testing, validated.

Every catalog robot is generated for every target and imported; its forward kinematics, Jacobians (two per module,
in two frames and at two points), joint torques and manipulability are compared with the NumPy reference of
``tests/reference.py`` (FK and central differences) and with symjac's own unsimplified Jacobian evaluated by
lambdify. Golden files live in ``tests/golden``; regenerate them with ``SYMJAC_UPDATE_GOLDEN=1 pytest
tests/test_codegen.py``. The C target needs a C compiler and the Python headers; without them its tests check the
NumPy fallback instead.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import importlib.util
import os
import shlex
import shutil
import subprocess
import sys
import sysconfig
import types
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from marks import PYTHON_TARGETS, marked
from reference import evaluate, finite_difference_jacobian, frames, random_configuration
from strategies import robots

from symjac import Chain, FrameError, Parameter, catalog, clear_caches, jacobian, load_robot, robot_from_mapping
from symjac.codegen import (
    BACKENDS,
    CodegenError,
    JacobianRequest,
    generate,
    write_module,
)
from symjac.codegen.source_layout import wrap_statement

REPO = Path(__file__).resolve().parent.parent
GOLDEN = Path(__file__).resolve().parent / "golden"
ROBOTS = sorted(catalog())
BATCHED = tuple(name for name, spec in BACKENDS.items() if spec.batched)
HAVE_C = bool(shutil.which("cc") or shutil.which("gcc")) and (
    Path(sysconfig.get_paths()["include"]) / "Python.h").is_file()
TIMEOUT = 120


# --- helpers ---------------------------------------------------------------------------------------------------


@pytest.fixture(scope="session")
def workspace(tmp_path_factory):
    """A folder outside the repository for generated modules, and a private cache for compiled C kernels."""
    directory = tmp_path_factory.mktemp("generated")
    assert REPO not in directory.resolve().parents
    cache = tmp_path_factory.mktemp("c-cache")
    previous = os.environ.get("SYMJAC_CACHE_DIR")
    os.environ["SYMJAC_CACHE_DIR"] = str(cache)
    yield directory
    if previous is None:
        os.environ.pop("SYMJAC_CACHE_DIR", None)
    else:
        os.environ["SYMJAC_CACHE_DIR"] = previous


_MODULES: dict[tuple[str, str], types.ModuleType] = {}


def _import(path: Path, name: str) -> types.ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _requests(robot):
    """Two Jacobians per module: {0} at the wrist, and a middle frame at the tool (or an offset point)."""
    point = "tool" if robot.tool is not None else (sp.Rational(1, 10), sp.Rational(-1, 5), sp.Rational(3, 10))
    return [JacobianRequest(0, "wrist"), JacobianRequest(robot.n_joints // 2, point)]


def _module(workspace, name: str, target: str) -> types.ModuleType:
    if (name, target) not in _MODULES:
        robot = load_robot(name)
        path = workspace / f"{name}_{target}{BACKENDS[target].suffix}"
        write_module(path, generate(robot, target, jacobians=_requests(robot)))
        _MODULES[name, target] = _import(path, f"generated_{name}_{target}")
    return _MODULES[name, target]


def _point(robot, request):
    if request.point == "wrist":
        return None
    if request.point == "tool":
        return np.array([float(v) for v in robot.tool.matrix[:3, 3].subs(robot.defaults)])
    return np.array([float(v) for v in request.point])


def _call(module, target, function, q, *extra):
    """One configuration through ``function``; nested tuples (targets that are not batched) become arrays."""
    return np.array(getattr(module, function)(q if BACKENDS[target].batched else list(q), *extra), dtype=float)


# --- correctness --------------------------------------------------------------------------------------------------


@functools.cache
def _references(name: str) -> list[dict[str, object]]:
    """Per seeded configuration: the tool pose, and each requested Jacobian symbolically and by differences."""
    robot = load_robot(name)
    rng = np.random.default_rng(11)
    cases = []
    for _ in range(4):
        q = random_configuration(robot, rng)
        poses = frames(robot, q)
        jacobians = [(evaluate(jacobian(robot, r.frame, r.point, simplify=False), robot, q),
                      finite_difference_jacobian(robot, q, r.frame, _point(robot, r))) for r in _requests(robot)]
        cases.append({"q": q, "pose": np.linalg.inv(poses[1]) @ poses[-1], "jacobians": jacobians,
                      "wrench": rng.uniform(-1, 1, 6)})
    return cases


@pytest.mark.parametrize("target", marked(PYTHON_TARGETS))
@pytest.mark.parametrize("name", marked(ROBOTS))
def test_module_agrees_with_references(workspace, name, target):
    robot = load_robot(name)
    module = _module(workspace, name, target)
    middle, label = robot.n_joints // 2, "tool" if robot.tool is not None else "p1"
    names = [tuple(f"{kind}{suffix}" for kind in ("jacobian", "joint_torques", "manipulability",
                                                   "jacobian_determinant"))
             for suffix in ("", f"_{middle}_{label}")]
    for case in _references(name):
        q, wrench = case["q"], case["wrench"]
        np.testing.assert_allclose(_call(module, target, "forward_kinematics", q), case["pose"], atol=1e-12)
        for (symbolic, differences), (J_name, tau_name, w_name, det_name) in zip(case["jacobians"], names,
                                                                                 strict=True):
            J = _call(module, target, J_name, q)
            np.testing.assert_allclose(J, symbolic, atol=1e-12)
            np.testing.assert_allclose(J, differences, atol=1e-6)
            np.testing.assert_allclose(_call(module, target, tau_name, q, list(wrench)), J.T @ wrench, atol=1e-12)
            gram = J @ J.T if robot.n_coordinates >= 6 else J.T @ J
            expected = np.sqrt(max(np.linalg.det(gram), 0.0))
            assert abs(float(getattr(module, w_name)(list(q))) - expected) <= 1e-9 * (1 + expected)
            if robot.n_coordinates == 6:
                assert float(getattr(module, det_name)(list(q))) == pytest.approx(np.linalg.det(J), abs=1e-12)
            else:
                assert not hasattr(module, det_name)
    configurations = np.array([case["q"] for case in _references(name)])
    if target in BATCHED:
        batched = module.jacobian(configurations.reshape(2, 2, robot.n_coordinates))
        assert batched.shape == (2, 2, 6, robot.n_coordinates)
        singles = np.array([module.jacobian(q) for q in configurations]).reshape(batched.shape)
        np.testing.assert_allclose(batched, singles, atol=1e-15, rtol=1e-14)


@pytest.mark.parametrize("target", PYTHON_TARGETS)
def test_parameters_are_overridable_per_call(workspace, target):
    robot = load_robot("puma560")
    module = _module(workspace, "puma560", target)
    assert dict(module.PARAMETERS) == {p.name: float(p.default) for p in robot.parameters}
    q = random_configuration(robot, np.random.default_rng(3))
    a2, d4 = sp.Symbol("a2", real=True), sp.Symbol("d4", real=True)
    expected = evaluate(jacobian(robot, simplify=False), robot, q, extra={a2: 0.5, d4: 0.25})
    np.testing.assert_allclose(_call_kw(module, target, q, a2=0.5, d4=0.25), expected, atol=1e-12)


def _call_kw(module, target, q, **parameters):
    return np.array(module.jacobian(q if BACKENDS[target].batched else list(q), **parameters), dtype=float)


@pytest.mark.parametrize("target", PYTHON_TARGETS)
def test_wrong_shapes_raise_and_nan_propagates(workspace, target):
    module = _module(workspace, "planar2r", target)
    if not BACKENDS[target].batched:
        with pytest.raises(ValueError, match="q must be a sequence of 2 numbers, got 3 values"):
            module.jacobian([0.1, 0.2, 0.3])
        with pytest.raises(ValueError, match="q must be a sequence of 2 numbers, got float"):
            module.jacobian(0.5)
        with pytest.raises(ValueError, match="wrench must be a sequence of 6 numbers"):
            module.joint_torques([0.1, 0.2], [1.0, 2.0])
        J = np.array(module.jacobian([float("nan"), 0.2]))
    else:
        with pytest.raises(ValueError, match=r"q must have shape \(\.\.\., 2\), got shape \(3,\)"):
            module.jacobian(np.zeros(3))
        with pytest.raises(ValueError, match="out"):
            module.jacobian(np.zeros((4, 2)), out=np.empty((4, 2, 6)))
        with pytest.raises(ValueError, match="wrench must have shape"):
            module.joint_torques(np.zeros(2), np.zeros(5))
        J = module.jacobian(np.array([np.nan, 0.2]))
        out = np.empty((3, 6, 2))
        assert module.jacobian(np.zeros((3, 2)), out=out) is out
        # broadcasting of q against the wrench
        torques = module.joint_torques(np.zeros(2), np.ones((5, 6)))
        assert torques.shape == (5, 2)
    assert np.isnan(J[:2]).all()  # v depends on theta1
    np.testing.assert_array_equal(J[5], [1.0, 1.0])  # omega_z does not


def test_python_module_uses_floats_only_and_returns_nested_tuples(workspace):
    module = _module(workspace, "ur5", "python")
    J = module.jacobian([0.1] * 6)
    assert isinstance(J, tuple) and all(isinstance(row, tuple) and len(row) == 6 for row in J)
    assert all(type(value) is float for row in J for value in row)


@pytest.mark.parametrize("target", ["python", "numpy"])
def test_scalar_functions_can_be_plugged_in(workspace, target):
    robot = load_robot("planar2r")
    L1, L2, t2 = (sp.Symbol(s, real=True) for s in ("L1", "L2", "theta2"))
    source = generate(robot, target, rows=(0, 1), scalars={"det_factored": L1 * L2 * sp.sin(t2)})
    path = workspace / f"planar2r_scalar_{target}.py"
    write_module(path, source)
    module = _import(path, f"planar2r_scalar_{target}")
    q = [0.3, 1.1]
    assert float(module.det_factored(q)) == pytest.approx(float(module.jacobian_determinant(q)), abs=1e-14)
    assert "def det_factored(" in source and "det_factored" in module.__all__


@settings(max_examples=6, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(robot=robots(max_joints=4))
def test_random_chains_pass_their_selftest_and_targets_agree(robot):
    modules = {}
    for target in ("python", "numpy"):
        namespace: dict[str, object] = {}
        source = generate(robot, target, points=("tool" if robot.tool else "wrist",))
        exec(compile(source, f"random_{target}.py", "exec"), namespace)
        assert namespace["selftest"](samples=5) < 1e-6  # type: ignore[operator]
        modules[target] = namespace
    q = np.random.default_rng(2).uniform(-1, 1, (3, robot.n_coordinates))
    batched = modules["numpy"]["jacobian"](q)  # type: ignore[operator]
    for k in range(3):
        np.testing.assert_allclose(modules["python"]["jacobian"](list(q[k])), batched[k], atol=1e-12)  # type: ignore[operator]


# --- determinism, golden files, lint ---------------------------------------------------------------------------------


GOLDEN_CASES = [("planar2r", target) for target in PYTHON_TARGETS] + [("puma560", "python"), ("puma560", "numpy")]


@pytest.mark.parametrize(("name", "target"), marked(GOLDEN_CASES))
def test_golden_files(name, target):
    text = generate(load_robot(name), target)
    path = GOLDEN / f"{name}_{target}{BACKENDS[target].suffix}.golden"
    if os.environ.get("SYMJAC_UPDATE_GOLDEN") == "1":
        GOLDEN.mkdir(exist_ok=True)
        write_module(path, text)
    assert path.is_file(), f"missing {path.name}: run with SYMJAC_UPDATE_GOLDEN=1 to create it"
    assert text == path.read_text(encoding="utf-8"), (
        f"{name} ({target}) differs from {path.name}; if the change is intended, regenerate with "
        "SYMJAC_UPDATE_GOLDEN=1")


GENERATE_SCRIPT = """
import hashlib, sys
from symjac import load_robot
from symjac.codegen import generate, JacobianRequest
text = generate(load_robot(sys.argv[1]), sys.argv[2], jacobians=[JacobianRequest(0, "wrist"), JacobianRequest(3)])
print(hashlib.sha256(text.encode()).hexdigest())
"""


@pytest.mark.slow
def test_generation_is_byte_identical_across_runs_and_hash_seeds():
    robot = load_robot("ur5")
    requests = [JacobianRequest(0, "wrist"), JacobianRequest(3)]
    first = generate(robot, "c", jacobians=requests)
    assert generate(Chain(robot), "c", jacobians=requests) == first  # a fresh chain derives everything again
    clear_caches()
    assert generate(robot, "c", jacobians=requests) == first
    digests = set()
    for seed in ("1", "2"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        result = subprocess.run([sys.executable, "-c", GENERATE_SCRIPT, "ur5", "c"], capture_output=True, text=True,
                                env=env, timeout=TIMEOUT, check=True)
        digests.add(result.stdout.strip())
    assert digests == {hashlib.sha256(first.encode()).hexdigest()}


def test_generated_modules_are_ruff_clean(workspace):
    if shutil.which("ruff") is None:
        pytest.skip("ruff is not installed")
    for name in ("puma560", "panda", "stanford"):
        for target in PYTHON_TARGETS:
            _module(workspace, name, target)
    files = sorted(str(path) for path in workspace.glob("*.py"))
    assert len(files) >= 12
    result = subprocess.run(["ruff", "check", "--no-cache", "--config", str(REPO / "pyproject.toml"), *files],
                            capture_output=True, text=True, timeout=TIMEOUT, check=False)
    assert result.returncode == 0, result.stdout + result.stderr


# --- self-test in isolation ----------------------------------------------------------------------------------------


ISOLATED = """
import sys
sys.path.insert(0, ".")
for blocked in {blocked!r}:
    sys.modules[blocked] = None  # importing it now raises ImportError
import {module} as module
loaded = sorted(name for name in ("numpy", "sympy") if sys.modules.get(name) is not None)
print(module.selftest(), getattr(module, "BACKEND", "-"), loaded)
"""


@pytest.mark.parametrize("target", marked(PYTHON_TARGETS))
def test_selftest_runs_outside_the_repository_with_only_its_dependency(workspace, tmp_path, target):
    robot = load_robot("puma560")
    write_module(tmp_path / "puma_module.py", generate(robot, target, points=("wrist",)))
    dependencies = BACKENDS[target].dependencies
    blocked = [name for name in ("sympy", "symjac") if name not in dependencies]
    command = [sys.executable, "-I"]
    if not dependencies:
        command.append("-S")  # no site-packages at all: only the standard library is importable
    command += ["-c", ISOLATED.format(blocked=blocked, module="puma_module")]
    env = {"PATH": os.environ.get("PATH", ""), "SYMJAC_CACHE_DIR": str(tmp_path / "cache")}
    result = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, env=env, timeout=TIMEOUT,
                            check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    error, backend, imported = result.stdout.split(" ", 2)
    assert float(error) < 1e-6
    assert imported.strip() == str(sorted(set(dependencies) & {"numpy", "sympy"}))
    if target == "c":
        assert backend == ("c" if HAVE_C else "numpy")


def test_c_target_falls_back_to_numpy_without_a_compiler(workspace, tmp_path, monkeypatch):
    monkeypatch.setenv("CC", str(tmp_path / "no-such-compiler"))
    monkeypatch.setenv("SYMJAC_CACHE_DIR", str(tmp_path / "cache"))
    path = tmp_path / "fallback_module.py"
    write_module(path, generate(load_robot("planar3r"), "c"))
    module = _import(path, "fallback_module")
    assert module.BACKEND == "numpy"
    assert "no-such-compiler" in module.BUILD_ERROR
    assert module.selftest() < 1e-6
    monkeypatch.setenv("SYMJAC_DISABLE_C", "1")
    assert _import(path, "fallback_module_disabled").BUILD_ERROR == "disabled by SYMJAC_DISABLE_C"


@pytest.mark.external
@pytest.mark.skipif(not HAVE_C, reason="no C compiler or Python headers")
def test_c_kernels_match_the_numpy_fallback(workspace):
    module = _module(workspace, "panda", "c")
    assert module.BACKEND == "c", module.BUILD_ERROR
    q = np.random.default_rng(5).uniform(-3, 3, (20000, 7))  # large enough for threads and vectorised sines
    parameters = tuple(module.PARAMETERS.values())
    threads = module.THREADS
    try:
        for function, kernel in ((module.jacobian, module._jacobian_kernel),
                                 (module.forward_kinematics, module._forward_kinematics_kernel)):
            module.THREADS = 2  # the batch split over two threads
            fast = function(q)
            reference = module._evaluate(kernel, ((q, 7, "q"),), fast.shape[1:], None, parameters)
            np.testing.assert_allclose(fast, reference, atol=1e-13)
            out = np.empty_like(fast)
            assert function(q, out) is out
            np.testing.assert_array_equal(out, fast)
            module.THREADS = 1  # the whole batch in one call of the kernel
            np.testing.assert_array_equal(function(q), fast)
        module.THREADS = 2  # an array-like that is not an ndarray takes the converting path, threads included
        np.testing.assert_array_equal(module.jacobian(q.tolist()), module.jacobian(q))
    finally:
        module.THREADS = threads
    # non-contiguous and integer inputs take the converting path
    np.testing.assert_allclose(module.jacobian(q[::2].astype(np.float32).astype(int)),
                               module._evaluate(module._jacobian_kernel, ((q[::2].astype(int), 7, "q"),),
                                                (6, 7), None, parameters), atol=1e-13)


# --- validation, files, command line ---------------------------------------------------------------------------------


def _robot_with_parameter(name: str):
    """planar2r with its first parameter renamed (bypassing the robot-file validation, as a caller could)."""
    robot = load_robot("planar2r")
    return dataclasses.replace(robot, parameters=(Parameter(name, sp.Rational(1, 2)), *robot.parameters[1:]))


@pytest.mark.parametrize(
    ("parameter", "message"),
    [
        ("len", "parameter name 'len' would shadow the Python builtin"),
        ("np", "parameter name 'np' clashes with an import of the generated module"),
        ("out", "parameter name 'out' clashes with an argument of the generated functions"),
        ("PARAMETERS", "clashes with a constant of the generated module"),
        ("match", "parameter name 'match' is a Python keyword"),
        ("a-b", "not an ASCII identifier"),
        ("_hidden", "private"),
    ],
)
def test_unusable_parameter_names_are_refused(parameter, message):
    with pytest.raises(CodegenError, match=message):
        generate(_robot_with_parameter(parameter), "python")


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"target": "fortran"}, CodegenError, "unknown target 'fortran'"),
        ({"strategy": "best"}, CodegenError, "unknown strategy 'best'"),
        ({"frames": (9,)}, FrameError, "frame 9 does not exist"),
        ({"points": ("elbow",)}, FrameError, "unknown point 'elbow'"),
        ({"rows": (0, 7)}, CodegenError, r"rows must be row numbers 0..5 .*got \[v_x, 7\]"),
        ({"rows": (1, 1)}, CodegenError, "must not repeat"),
        ({"points": ((0, 0, sp.Symbol("z")),)}, CodegenError, "uses z, which is not a parameter of planar2r"),
        ({"scalars": {"f": sp.exp(sp.Symbol("theta1", real=True))}}, CodegenError, "exp.* is not supported"),
        ({"scalars": {"f": sp.Symbol("k")}}, CodegenError, "depend on k, which is not an argument"),
        ({"scalars": {"jacobian": sp.S.One}}, CodegenError, "'jacobian' clashes with a function in the generated"),
        ({"scalars": {"kinematics": sp.S.One}}, CodegenError, "'kinematics' clashes with a function of the generated"),
        ({"frames": (0, 0)}, CodegenError, "requested twice"),
    ],
)
def test_bad_requests_are_refused_before_anything_is_written(kwargs, error, message):
    with pytest.raises(error, match=message):
        generate(load_robot("planar2r"), **kwargs)


def test_robot_names_that_would_shadow_builtins_are_refused():
    robot = robot_from_mapping({"name": "print", "convention": "standard", "joints": [{"type": "revolute"}]})
    with pytest.raises(CodegenError, match="robot name 'print' would shadow the Python builtin"):
        generate(robot)


def test_write_module_is_atomic(tmp_path, monkeypatch):
    path = tmp_path / "module.py"
    write_module(path, "x = 1\n")
    assert path.read_text() == "x = 1\n"

    def fail(*args):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(OSError, match="disk full"):
        write_module(path, "x = 2\n")
    assert path.read_text() == "x = 1\n"  # the old file is untouched
    assert sorted(p.name for p in tmp_path.iterdir()) == ["module.py"]  # no temporary left behind


def test_command_line_generates_the_same_module(tmp_path, capsys):
    from symjac.cli.main import main

    path = tmp_path / "puma.py"
    argv = ["codegen", "puma560", "--target", "numpy", "--frame", "0", "--frame", "3", "--point", "wrist",
            "--point", "0,0,d4/2", "--rows", "v_x,v_y,v_z", "-o", str(path)]
    assert main(argv) == 0
    d4 = sp.Symbol("d4", real=True)
    requests = [JacobianRequest(f, p, (0, 1, 2)) for f in (0, 3) for p in ("wrist", (0, 0, d4 / 2))]
    text = path.read_text(encoding="utf-8")
    assert text == generate(load_robot("puma560"), "numpy", jacobians=requests,
                            command=shlex.join(["symjac", *argv]))
    assert "def jacobian_3_p1_r012(" in text
    assert main(["codegen", "puma560", "--point", "1,2"]) == 2
    assert "--point must be" in capsys.readouterr().err
    assert main(["codegen", "puma560", "--rows", "v_q"]) == 2
    assert "unknown row 'v_q'" in capsys.readouterr().err


def test_codegen_works_on_a_chain_loaded_from_urdf(tmp_path):
    from symjac import load_robot
    from symjac.analysis.spaces import numeric_jacobian

    robot = load_robot("ur5.urdf")
    namespace: dict = {}
    exec(compile(generate(robot, "python"), "ur5_urdf.py", "exec"), namespace)
    rng = np.random.default_rng(4)
    for _ in range(3):
        q = rng.uniform(-np.pi, np.pi, robot.n_coordinates)
        assert np.allclose(np.array(namespace["jacobian"](list(q))), numeric_jacobian(robot, q), atol=1e-12)
    namespace["selftest"]()


def test_cli_codegen_writes_a_module(tmp_path, capsys):
    from symjac.cli.main import main

    target = tmp_path / "planar.py"
    assert main(["codegen", "planar2r", "--target", "numpy", "-o", str(target)]) == 0
    assert "def jacobian(" in target.read_text()
    assert main(["codegen", "planar2r", "--target", "numpy", "--frame", "9", "-o", str(tmp_path / "bad.py")]) == 2
    assert not (tmp_path / "bad.py").exists()


def test_layout_counts_the_closing_tail_on_the_last_line():
    """Regression (found by hypothesis): a statement whose last piece fitted but whose closing ')),' did not."""
    code = " + ".join(["x1234567"] * 12)
    for width in range(40, 80):
        lines = wrap_statement("        ", code, ")),", width=width)
        assert all(len(line) <= width for line in lines), width
        assert "".join(lines).replace(" ", "") == "(" + code.replace(" ", "") + ")" + ")),"  # wrapped, nothing lost

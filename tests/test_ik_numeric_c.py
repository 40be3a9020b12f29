"""The numeric inverse kinematics in generated C99: compiled with the strictest flags, its solutions checked by an
independent forward kinematics (the symbolic pose lambdified), deterministic for a seed, within the limits."""

from __future__ import annotations

import ctypes
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from symjac import load_robot
from symjac.analysis.inverse_kinematics import seed_bounds, solve_numeric
from symjac.codegen import CodegenError, ModuleRequest, describe, render_files
from symjac.codegen.numeric_model import numeric_model
from symjac.kinematics.chain import forward_kinematics

pytestmark = pytest.mark.external  # a C compiler

if shutil.which("gcc") is None:  # pragma: no cover - .ci/run installs it
    pytest.skip("gcc is not installed", allow_module_level=True)

FLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2", "-fPIC", "-shared"]
POSES = 40
P = ctypes.POINTER(ctypes.c_double)


def _solver(tmp_path, robot):
    files = render_files(describe(ModuleRequest(robot, "c99", numeric_ik=True)))
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    source = next(name for name in files if name.endswith(".c"))
    subprocess.run(["gcc", *FLAGS, source, "-o", "libik.so", "-lm"], cwd=tmp_path, check=True, capture_output=True)
    function = getattr(ctypes.CDLL(str(tmp_path / "libik.so")), f"{robot.name}_inverse_kinematics_numeric")
    function.argtypes = [P, P, P, ctypes.c_ulonglong, P, ctypes.POINTER(ctypes.c_int), P, P]

    def solve(pose, seed, start=None, errors=False):
        q, iterations = np.zeros(robot.n_joints), ctypes.c_int(-1)
        position, orientation = ctypes.c_double(-1.0), ctypes.c_double(-1.0)
        pose = np.ascontiguousarray(pose, dtype=float)
        begin = None if start is None else np.ascontiguousarray(start, dtype=float)
        found = function(pose.ctypes.data_as(P), None, None if begin is None else begin.ctypes.data_as(P), seed,
                         q.ctypes.data_as(P), ctypes.byref(iterations), ctypes.byref(position) if errors else None,
                         ctypes.byref(orientation) if errors else None)
        return (found, q, iterations.value) + ((position.value, orientation.value) if errors else ())

    return solve


def _independent_fk(robot):
    pose = forward_kinematics(robot, target="tool").subs(robot.defaults)
    return sp.lambdify([list(robot.joint_variables)], pose, "numpy")


@pytest.mark.parametrize("name", ["panda", "puma560", "ur5", "stanford"])
def test_generated_solver_reaches_every_pose_within_the_limits(tmp_path, name):
    robot = load_robot(name)
    solve, fk = _solver(tmp_path, robot), _independent_fk(robot)
    lower, upper = seed_bounds(robot)
    generator = np.random.default_rng(46)
    solved = 0
    for k in range(POSES):
        pose = np.asarray(fk(generator.uniform(lower, upper)), dtype=float)
        found, q, iterations = solve(pose, k)
        assert found in (0, 1) and iterations > 0
        if found:
            solved += 1
            assert np.abs(np.asarray(fk(q), dtype=float) - pose).max() < 1e-9
            assert np.all(q >= lower - 1e-12) and np.all(q <= upper + 1e-12)
    assert solved == POSES  # a fixed set: the solver restarts within the call until it converges


def test_generated_solver_is_deterministic_and_starts_from_a_given_configuration(tmp_path):
    robot = load_robot("iiwa7")
    solve, fk = _solver(tmp_path, robot), _independent_fk(robot)
    q0 = np.array([0.3, -0.4, 0.2, -1.0, 0.1, 0.6, 0.5])
    pose = np.asarray(fk(q0), dtype=float)
    first, second, other = solve(pose, 7), solve(pose, 7), solve(pose, 8)
    assert first[0] == second[0] == 1 and np.array_equal(first[1], second[1]) and first[2] == second[2]
    assert other[0] == 1 and not np.array_equal(first[1], other[1])  # another seed, another point of the self-motion
    found, q, iterations = solve(pose, 0, start=q0)
    assert found == 1 and iterations == 0 and np.array_equal(q, q0)


def _errors(fk, q, pose):
    """Position and orientation errors of q against the pose, from the independent forward kinematics."""
    reached = np.asarray(fk(q), dtype=float)
    r = reached[:3, :3] @ pose[:3, :3].T
    sine = np.linalg.norm([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]]) / 2.0
    return float(np.linalg.norm(reached[:3, 3] - pose[:3, 3])), float(np.arctan2(sine, (np.trace(r) - 1.0) / 2.0))


def assert_closest(fk, q, pose, lower, upper):
    """q is a local minimum of the squared errors within the limits: the gradient (central differences of the
    independent forward kinematics) vanishes along free joints and points outwards at a limit."""
    cost = [sum(x * x for x in _errors(fk, q + h, pose)) - sum(x * x for x in _errors(fk, q - h, pose))
            for h in np.eye(len(q)) * 1e-6]
    gradient = np.array(cost) / 2e-6
    low, high = q <= lower + 1e-9, q >= upper - 1e-9
    assert np.all(np.abs(gradient[~low & ~high]) < 1e-5) and np.all(gradient[low] > -1e-5)
    assert np.all(gradient[high] < 1e-5)


def test_an_unreachable_pose_gives_the_closest_configuration_and_its_errors(tmp_path):
    robot = load_robot("puma560")
    solve, fk = _solver(tmp_path, robot), _independent_fk(robot)
    lower, upper = seed_bounds(robot)
    pose = np.eye(4)
    pose[:3, 3] = [5.0, 0.0, 0.0]  # far beyond the PUMA's reach of about 0.9 m
    for seed in range(4):
        found, q, iterations, position, orientation = solve(pose, seed, errors=True)
        assert found == 0 and iterations > 0 and np.all(q >= lower - 1e-12) and np.all(q <= upper + 1e-12)
        assert (position, orientation) == pytest.approx(_errors(fk, q, pose), abs=1e-12)
        assert_closest(fk, q, pose, lower, upper)
        closest = solve_numeric(robot, pose, numeric_model(robot), restarts=16, until_found=16).closest
        assert closest is not None  # Python's closest: as close, to 1 % (each finds its own local minimum)
        assert position ** 2 + orientation ** 2 < 1.01 * (closest.position_error ** 2 + closest.orientation_error ** 2)
        assert solve(pose, seed)[:3] == (found, pytest.approx(q, abs=0), iterations)  # NULL errors: the same answer
    reachable = np.asarray(fk(np.array([0.3, -0.5, 0.4, -1.0, 0.6, 0.2])), dtype=float)
    found, q, _, position, orientation = solve(reachable, 1, errors=True)
    assert found == 1 and max(position, orientation) <= 1e-10


def test_only_c_targets_and_a_base_frame_jacobian_have_it():
    robot = load_robot("planar2r")
    assert describe(ModuleRequest(robot, "jax", numeric_ik=True)).numeric_ik  # a fixed graph there (ikcodegen)
    with pytest.raises(CodegenError, match="frame"):
        describe(ModuleRequest(robot, "c99", frames=(1,), numeric_ik=True))
    plain = "".join(render_files(describe(ModuleRequest(robot, "c99"))).values())
    assert "inverse_kinematics_numeric" not in plain and "sj_ik_" not in plain
    header = render_files(describe(ModuleRequest(robot, "c99", numeric_ik=True)))["planar2r.h"]
    assert 'symjac.generate(symjac.load_robot("planar2r"), "c99", jacobians=[symjac.JacobianRequest(0)], ' \
           "numeric_ik=True)" in header  # the header's command regenerates it with the solver


SHIM = """
#include "{robot}.hpp"

extern "C" int solve(const double *pose, unsigned long long seed, double *q, int *iterations, double *errors)
{{
    using Matrix = Eigen::Matrix<double, 4, 4, Eigen::RowMajor>;
    Eigen::Matrix<double, {n}, 1> x;
    const int found = symjac::{robot}::inverse_kinematics_numeric<double>(
        Eigen::Matrix4d(Eigen::Map<const Matrix>(pose)), seed, x, iterations, errors, errors + 1);
    Eigen::Map<Eigen::Matrix<double, {n}, 1>> out(q);
    out = x;
    Eigen::Matrix<float, {n}, 1> single;  // single precision compiles and converges to its own tolerance
    return found + 2 * symjac::{robot}::inverse_kinematics_numeric<float>(
        Eigen::Matrix4d(Eigen::Map<const Matrix>(pose)).cast<float>().eval(), seed, single);
}}
"""


@pytest.mark.skipif(shutil.which("g++") is None or not (Path("/usr/include/eigen3/Eigen/Dense")).is_file(),
                    reason="g++ or Eigen's headers (Debian libeigen3-dev) are missing")
@pytest.mark.parametrize("name", ["iiwa7", "ur5"])
def test_generated_cpp_solver_reaches_every_pose(tmp_path, name):
    robot = load_robot(name)
    for file, text in render_files(describe(ModuleRequest(robot, "cpp", numeric_ik=True))).items():
        (tmp_path / file).write_text(text)
    (tmp_path / "shim.cpp").write_text(SHIM.format(robot=name, n=robot.n_joints))
    subprocess.run(["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-O1", "-I/usr/include/eigen3", "-fPIC",
                    "-shared", "shim.cpp", "-o", "libshim.so"], cwd=tmp_path, check=True, capture_output=True)
    solve = ctypes.CDLL(str(tmp_path / "libshim.so")).solve
    solve.argtypes = [P, ctypes.c_ulonglong, P, ctypes.POINTER(ctypes.c_int), P]
    fk, (lower, upper) = _independent_fk(robot), seed_bounds(robot)
    generator = np.random.default_rng(47)
    for k in range(POSES // 2):
        pose = np.ascontiguousarray(fk(generator.uniform(lower, upper)), dtype=float)
        q, iterations, errors = np.zeros(robot.n_joints), ctypes.c_int(-1), np.full(2, -1.0)
        found = solve(pose.ctypes.data_as(P), k, q.ctypes.data_as(P), ctypes.byref(iterations),
                      errors.ctypes.data_as(P))
        assert found == 3 and iterations.value > 0 and np.all(errors <= 1e-10) and np.all(errors >= 0)
        assert np.abs(np.asarray(fk(q), dtype=float) - pose).max() < 1e-9
        assert np.all(q >= lower - 1e-12) and np.all(q <= upper + 1e-12)
    far = np.eye(4)
    far[:3, 3] = [3.0, 0.0, 0.5]  # beyond reach: the closest configuration, as the c99 solver's (same seeds and steps)
    q, iterations, errors = np.zeros(robot.n_joints), ctypes.c_int(-1), np.zeros(2)
    found = solve(far.ctypes.data_as(P), 3, q.ctypes.data_as(P), ctypes.byref(iterations), errors.ctypes.data_as(P))
    assert found == 0 and np.all(q >= lower - 1e-12) and np.all(q <= upper + 1e-12)
    assert tuple(errors) == pytest.approx(_errors(fk, q, far), abs=1e-12)
    assert_closest(fk, q, far, lower, upper)
    c99 = _solver(tmp_path, robot)(far, 3, errors=True)
    assert c99[0] == 0 and c99[2] == iterations.value and np.abs(c99[1] - q).max() < 1e-6  # a flat minimum: rounding
    assert tuple(errors) == pytest.approx(c99[3:], abs=1e-9)


@pytest.mark.parametrize("name", ["panda", "stanford"])
def test_generated_python_solver_agrees_with_the_c99_one(tmp_path, name):
    import types

    robot = load_robot(name)
    source = next(iter(render_files(describe(ModuleRequest(robot, "python", numeric_ik=True))).values()))
    module = types.ModuleType(f"{name}_ik")
    exec(compile(source, f"{name}_ik.py", "exec"), module.__dict__)  # our own generated module
    solve_c, fk = _solver(tmp_path, robot), _independent_fk(robot)
    lower, upper = seed_bounds(robot)
    generator = np.random.default_rng(48)
    same = 0
    for k in range(10):
        pose = np.asarray(fk(generator.uniform(lower, upper)), dtype=float)
        q, found, iterations, position, orientation = module.inverse_kinematics_numeric(pose.tolist(), seed=k)
        assert found and iterations > 0 and max(position, orientation) <= 1e-10
        assert np.abs(np.asarray(fk(q), dtype=float) - pose).max() < 1e-9
        assert np.all(np.asarray(q) >= lower - 1e-12) and np.all(np.asarray(q) <= upper + 1e-12)
        assert module.inverse_kinematics_numeric(pose.tolist(), seed=k) == (q, found, iterations, position,
                                                                            orientation)  # deterministic
        found_c, q_c, iterations_c = solve_c(pose, k)
        same += found_c == 1 and iterations_c == iterations and np.abs(q_c - np.asarray(q)).max() < 1e-8
    assert same >= 8  # the same seeds and steps: the same path, unless rounding sends one start elsewhere
    far = np.eye(4)
    far[:3, 3] = [3.0, 0.0, 0.5]  # beyond reach: the same closest configuration and errors as the c99 solver's
    q, found, iterations, position, orientation = module.inverse_kinematics_numeric(far.tolist(), seed=2)
    found_c, q_c, iterations_c, position_c, orientation_c = solve_c(far, 2, errors=True)
    assert not found and found_c == 0 and iterations == iterations_c and np.abs(q_c - np.asarray(q)).max() < 1e-9
    assert (position, orientation) == pytest.approx((position_c, orientation_c), abs=1e-9)
    assert (position, orientation) == pytest.approx(_errors(fk, np.asarray(q), far), abs=1e-12)

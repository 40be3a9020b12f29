"""Generated closed-form inverse kinematics of a 7-joint arm with one joint given (the redundancy parameter).

The iiwa7 with joint 3 given (``free_joint=3``) is a spherical wrist: every target's ``inverse_kinematics(pose,
q_free)`` must find the same solutions as :func:`~symjac.analysis.inverse_kinematics.closed_form.solve_plan` with
``free_value=q_free`` (up to 2 pi) at random poses, each reproducing the pose to 1e-10 and holding the given value in
joint 3, the configuration that made the pose among them. C99 and C++ are compiled with -Wall -Wextra -Werror.
"""

from __future__ import annotations

import ctypes
import importlib.util
import subprocess

import numpy as np
import pytest
from ik_generated import C_FLAGS, CPP_FLAGS, ik_files

from symjac.analysis.inverse_kinematics import closed_form_plan, seed_bounds, solve_plan
from symjac.codegen.module import ModuleRequest, describe
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import CodegenError, NoClosedFormError
from symjac.model.io import load_robot

FREE = 3  # joint 3 (joint numbers are 1-based)
COLUMN = FREE - 1  # its column in q
TARGETS = ("python", "numpy", "c", "lambdify", "jax", "casadi", "c99", "cpp")

CPP_SHIM = """#include "iiwa7.hpp"
extern "C" int solve(const double* pose, double q_free, double* out)
{
    using namespace symjac::iiwa7;
    const Eigen::Matrix4d T = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(pose);
    std::array<Eigen::Matrix<double, 7, 1>, ik_max_solutions> solutions;
    std::array<int, ik_max_solutions> branches;
    const int count = inverse_kinematics(T, q_free, solutions, branches);
    for (int k = 0; k < count; ++k) {
        for (int i = 0; i < 7; ++i) {
            out[k * 7 + i] = solutions[k](i);
        }
    }
    return count;
}
"""


def _module(folder, robot, target):
    (name, text), = ik_files(robot, target, free_joint=FREE).items()
    path = folder / f"{target}_{name}"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location(f"ik_free_{target}_{id(path)}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _solver(folder, robot, target):
    """``solve(poses, free_values) -> list of (count, 7) arrays`` for ``target``."""
    where = folder / target
    where.mkdir()
    if target == "c99":
        for name, text in ik_files(robot, "c99", free_joint=FREE).items():
            (where / name).write_text(text)
        subprocess.run(["gcc", *C_FLAGS, "-fPIC", "-shared", "iiwa7.c", "-o", "libiiwa7.so", "-lm"], cwd=where,
                       check=True, capture_output=True)
        function = ctypes.CDLL(str(where / "libiiwa7.so")).iiwa7_inverse_kinematics
        function.restype = ctypes.c_int

        def c99(poses, free):
            found = []
            for pose, value in zip(poses, free, strict=True):
                flat, out = np.ascontiguousarray(pose, dtype=float).ravel(), np.full(8 * 7, np.nan)
                count = function(flat.ctypes.data_as(ctypes.c_void_p), ctypes.c_double(value), None,
                                 ctypes.c_double(1e-9), out.ctypes.data_as(ctypes.c_void_p), None)
                found.append(out.reshape(8, 7)[:count].copy())
            return found

        return c99
    if target == "cpp":
        (name, text), = ik_files(robot, "cpp", free_joint=FREE).items()
        (where / name).write_text(text)
        (where / "shim.cpp").write_text(CPP_SHIM)
        subprocess.run(["g++", *CPP_FLAGS, "-fPIC", "-shared", "shim.cpp", "-o", "libshim.so"], cwd=where,
                       check=True, capture_output=True)
        lib = ctypes.CDLL(str(where / "libshim.so"))

        def cpp(poses, free):
            found = []
            for pose, value in zip(poses, free, strict=True):
                flat, out = np.ascontiguousarray(pose, dtype=float).ravel(), np.full(8 * 7, np.nan)
                count = lib.solve(flat.ctypes.data_as(ctypes.c_void_p), ctypes.c_double(value),
                                  out.ctypes.data_as(ctypes.c_void_p))
                found.append(out.reshape(8, 7)[:count].copy())
            return found

        return cpp
    module = _module(where, robot, target)
    if target == "python":
        return lambda poses, free: [np.array(module.inverse_kinematics(p.tolist(), v)[0]).reshape(-1, 7)
                                    for p, v in zip(poses, free, strict=True)]
    if target == "jax":
        import jax

        jax.config.update("jax_enable_x64", True)
        solve = jax.jit(jax.vmap(module.inverse_kinematics))

        def masked(poses, free):
            solutions, valid = (np.asarray(a) for a in solve(poses, free))
            return [rows[ok] for rows, ok in zip(solutions, valid, strict=True)]

        return masked
    if target == "casadi":
        defaults = np.array(module.PARAMETER_DEFAULTS, dtype=float)

        def function(poses, free):
            found = []
            for pose, value in zip(poses, free, strict=True):
                solutions, valid = (np.asarray(a) for a in module.inverse_kinematics(pose, value, defaults))
                found.append(solutions[valid.ravel() > 0.5])
            return found

        return function

    def batched(poses, free):
        solutions, count, _ = module.inverse_kinematics(poses, free)
        return [rows[:k] for rows, k in zip(solutions, count, strict=True)]

    return batched


@pytest.fixture(scope="module")
def iiwa(tmp_path_factory):
    """The iiwa7, its plan with joint 3 given, every target's solver and 25 poses of configurations in its limits."""
    robot = load_robot("iiwa7")
    plan = closed_form_plan(robot, free_joint=FREE)
    folder = tmp_path_factory.mktemp("ik_free")
    solvers = {target: _solver(folder, robot, target) for target in TARGETS}
    lower, upper = seed_bounds(robot)
    q = np.random.default_rng(461).uniform(lower, upper, (25, 7))
    return robot, plan, solvers, q, numeric_model(robot, backend="numpy").fk(q)


def _distance(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Largest difference per pair of rows, angles modulo 2 pi (every joint of the iiwa7 is revolute)."""
    difference = a[:, None, :] - b[None, :, :]
    return np.abs((difference + np.pi) % (2 * np.pi) - np.pi).max(axis=2)


def test_every_target_finds_the_executors_solutions_with_the_joint_given(iiwa):
    robot, plan, solvers, q, poses = iiwa
    fk = numeric_model(robot, backend="numpy").fk
    free = q[:, COLUMN]
    expected = [np.array([s.q for s in solve_plan(plan, pose, free_value=v).solutions])
                for pose, v in zip(poses, free, strict=True)]
    assert sum(len(e) for e in expected) >= 4 * len(poses)  # most poses have several solutions
    for target, solve in solvers.items():
        for k, (found, reference) in enumerate(zip(solve(poses, free), expected, strict=True)):
            assert len(found) == len(reference), (target, k)
            np.testing.assert_allclose(found, reference, atol=1e-8, err_msg=f"{target}, pose {k}")
            assert np.abs(fk(found) - poses[k]).max() < 1e-10, (target, k)
            assert np.all(np.abs(found[:, COLUMN] - free[k]) < 1e-15), (target, k)
            assert _distance(found, q[k:k + 1]).min() < 1e-6, (target, k)


def test_a_value_of_the_given_joint_that_no_solution_has_gives_none(iiwa):
    """With joint 3 at its value, a pose from another value of it is out of reach of joints 1-2 and 4-7, or solved
    by a configuration holding the given value: every row holds it and reproduces the pose."""
    robot, plan, solvers, q, poses = iiwa
    fk = numeric_model(robot, backend="numpy").fk
    other = q[:, COLUMN] + 0.8
    for target in ("numpy", "c99"):
        for k, found in enumerate(solvers[target](poses, other)):
            reference = solve_plan(plan, poses[k], free_value=other[k]).solutions
            assert len(found) == len(reference), (target, k)
            if len(found):
                assert np.abs(fk(found) - poses[k]).max() < 1e-9, (target, k)
                assert np.all(_distance(found[:, COLUMN:COLUMN + 1], other[k:k + 1, None]) < 1e-12), (target, k)


def test_the_option_is_refused_in_one_line_where_it_does_not_apply(cli):
    robot = load_robot("iiwa7")
    command = describe(ModuleRequest(robot, "python", inverse_kinematics=True, free_joint=FREE)).command
    assert command.endswith(", inverse_kinematics=True, free_joint=3)")  # the header's call regenerates it
    with pytest.raises(CodegenError, match="ask for inverse_kinematics too"):
        describe(ModuleRequest(robot, "numpy", free_joint=FREE))
    with pytest.raises(CodegenError, match="1 to 7 for iiwa7, got 8"):
        ik_files(robot, "numpy", free_joint=8)
    with pytest.raises(NoClosedFormError):  # joint 5 given leaves no closed form, and no numeric stand-in
        ik_files(robot, "c99", free_joint=5)
    error = cli.one_line_error("codegen", "iiwa7", "--target", "numpy", "--inverse-kinematics", "--free-joint", "9")
    assert "--free-joint" in error and "1 to 7" in error


def test_the_command_line_option_writes_a_module_that_takes_the_joint(cli):
    source = cli.ok("codegen", "iiwa7", "--target", "numpy", "--inverse-kinematics", "--free-joint", "3")
    assert "--free-joint 3" in source.split('"""')[0]  # the regenerating command in the header
    namespace: dict = {}
    exec(compile(source, "iiwa7.py", "exec"), namespace)
    q = np.array([0.3, -0.5, 0.4, 0.9, 0.7, -0.6, 0.2])
    solutions, count, _ = namespace["inverse_kinematics"](namespace["forward_kinematics"](q), q[COLUMN])
    assert int(count) >= 1 and np.abs(solutions[:count] - q).max(axis=1).min() < 1e-9

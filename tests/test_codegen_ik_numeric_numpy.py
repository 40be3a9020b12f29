"""The numeric inverse kinematics of the NumPy-family targets (numpy, lambdify, c) on the Panda, which has no closed
form: solutions checked by an independent forward kinematics (the symbolic pose lambdified), within the limits,
deterministic for a seed and on the same path as the python target's solver (the same seeds and steps)."""

from __future__ import annotations

import types

import numpy as np
import pytest
import sympy as sp

from symjac import load_robot
from symjac.analysis.inverse_kinematics import seed_bounds
from symjac.codegen import ModuleRequest, describe, render_files
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import NoClosedFormError
from symjac.kinematics.chain import forward_kinematics

TARGETS = ("numpy", "lambdify", "c")


def _module(robot, target: str, **options) -> types.ModuleType:
    source = next(iter(render_files(describe(ModuleRequest(robot, target, **options))).values()))
    module = types.ModuleType(f"{robot.name}_{target}_ik")
    exec(compile(source, f"{robot.name}_{target}_ik.py", "exec"), module.__dict__)  # our own generated module
    return module


@pytest.fixture(scope="module")
def panda():
    robot = load_robot("panda")
    pose = forward_kinematics(robot, target="tool").subs(robot.defaults)
    fk = sp.lambdify([list(robot.joint_variables)], pose, "numpy")
    modules = {target: _module(robot, target, numeric_ik=True) for target in (*TARGETS, "python")}
    return robot, fk, modules


@pytest.mark.parametrize("target", TARGETS)
def test_the_solver_reaches_every_pose_within_the_limits_as_the_python_one(panda, target):
    robot, fk, modules = panda
    module, python = modules[target], modules["python"]
    lower, upper = seed_bounds(robot)
    generator = np.random.default_rng(4602)
    same = 0
    for k in range(10):
        pose = np.asarray(fk(generator.uniform(lower, upper)), dtype=float)
        q, found, iterations, position, orientation = module.inverse_kinematics_numeric(pose, seed=k)
        assert found and iterations > 0 and q.shape == (7,) and max(position, orientation) <= 1e-10, (target, k)
        assert np.abs(np.asarray(fk(q), dtype=float) - pose).max() < 1e-9, (target, k)
        assert np.all(q >= lower - 1e-12) and np.all(q <= upper + 1e-12), (target, k)
        again = module.inverse_kinematics_numeric(pose, seed=k)
        assert np.array_equal(again[0], q) and again[1:] == (found, iterations, position, orientation), (target, k)
        q_python, found_python, iterations_python, *_ = python.inverse_kinematics_numeric(pose.tolist(), seed=k)
        same += found_python and iterations_python == iterations and np.abs(np.asarray(q_python) - q).max() < 1e-8
    assert same >= 8, target  # the same seeds and steps: the same path, unless rounding sends one start elsewhere


def test_a_start_near_the_answer_converges_from_it_and_an_unreachable_pose_is_not_found(panda):
    robot, fk, modules = panda
    module = modules["numpy"]
    q0 = np.array([0.1, -0.3, 0.2, -2.0, 0.1, 1.5, 0.3])
    pose = np.asarray(fk(q0), dtype=float)
    q, found, iterations, _, _ = module.inverse_kinematics_numeric(pose, seed=5, start=q0 + 0.01)
    assert found and iterations < 20 and np.abs(np.asarray(fk(q), dtype=float) - pose).max() < 1e-9
    assert np.abs(q - q0).max() < 0.01  # a redundant arm: near the start, not at q0 (it moves along the self-motion)
    far = pose.copy()
    far[:3, 3] = [3.0, 0.0, 0.5]  # 3 m from the base, beyond the Panda's reach of about 1 m
    q, found, _, position, orientation = module.inverse_kinematics_numeric(far, seed=1)
    lower, upper = seed_bounds(robot)
    assert not found and np.all(q >= lower - 1e-12) and np.all(q <= upper + 1e-12)
    reached = np.asarray(fk(q), dtype=float)  # the errors are those of q, by an independent forward kinematics
    assert position == pytest.approx(np.linalg.norm(reached[:3, 3] - far[:3, 3]), abs=1e-12) and position > 1.5
    assert orientation == pytest.approx(np.arccos(np.clip((np.trace(reached[:3, :3] @ far[:3, :3].T) - 1) / 2, -1, 1)),
                                        abs=1e-6)
    for target in ("lambdify", "c", "python"):  # every target: the same closest configuration and errors
        other = modules[target].inverse_kinematics_numeric(far if target != "python" else far.tolist(), seed=1)
        assert not other[1] and np.abs(np.asarray(other[0]) - q).max() < 1e-6, target
        assert other[3:] == pytest.approx((position, orientation), abs=1e-9), target
    with pytest.raises(ValueError, match=r"shape \(4, 4\)"):
        module.inverse_kinematics_numeric(np.eye(3))


def test_asking_for_inverse_kinematics_gives_the_numeric_solver_in_every_target(panda):
    robot, _, _ = panda
    module = _module(robot, "numpy", inverse_kinematics=True)
    assert "inverse_kinematics_numeric" in module.__all__ and not hasattr(module, "inverse_kinematics")
    with pytest.raises(NoClosedFormError):  # the model's ik is the closed form's: no numeric stand-in there
        numeric_model(robot, backend="numpy").ik(np.eye(4))
    for target in ("jax", "casadi"):  # their fixed graphs: tests/test_codegen_ik_numeric_traced.py
        description = describe(ModuleRequest(robot, target, inverse_kinematics=True))
        assert description.inverse_kinematics is None and description.numeric_ik == "jacobian"

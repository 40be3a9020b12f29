"""Generated closed-form inverse kinematics of a coupled robot: solutions in the independent coordinates.

The catalog palletizer (theta4 = -(theta2 + theta3) keeps the flange level; coordinates theta1, theta2, theta3,
theta5) in every target: each solution, fed to the forward kinematics of a generated module (which takes the
coordinates), reproduces the pose; the configuration that made the pose is among them; the solutions are those of
the Python front end (:func:`symjac.inverse_kinematics`, the plan's executor mapped to the coordinates).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp
from ik_generated import ik_solvers
from test_coordinates import ROBOTS

import symjac
from symjac.codegen.coupled import coordinates_of_joints
from symjac.codegen.inverse_kinematics import inverse_kinematics_of
from symjac.codegen.numeric_model import numeric_model
from symjac.errors import CodegenError
from symjac.model.coordinates import Coupling
from symjac.model.io import load_robot
from symjac.solvers.controlled import coordinate_bounds

TARGETS = ("python", "numpy", "c", "lambdify", "jax", "casadi", "c99", "cpp")


@pytest.fixture(scope="module")
def palletizer(tmp_path_factory):
    """The palletizer, every target's generated solver, 40 configurations within the limits and their poses."""
    robot = load_robot("palletizer")
    solvers = ik_solvers(tmp_path_factory.mktemp("ik_palletizer"), robot, TARGETS)
    lower, upper = coordinate_bounds(robot)
    q = np.random.default_rng(4).uniform(lower, upper, (40, robot.n_coordinates))
    return robot, solvers, q, numeric_model(robot, backend="numpy").fk(q)


def _turned(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Largest difference per pair of rows, angles modulo 2 pi (every coordinate of the palletizer is an angle)."""
    return np.abs((a[:, None, :] - b[None, :, :] + np.pi) % (2 * np.pi) - np.pi).max(axis=2)


def test_the_closed_form_is_lowered_in_the_coordinates():
    robot = load_robot("palletizer")
    ik = inverse_kinematics_of(robot)
    assert robot.coupling is not None and ik.n == robot.n_coordinates == 4 < robot.n_joints
    assert ik.family == "palletizer" and ik.revolute == (True,) * 4


def test_every_target_round_trips_through_the_generated_forward_kinematics(palletizer):
    robot, solvers, q, poses = palletizer
    fk = numeric_model(robot, backend="numpy").fk  # a generated module: q in the coordinates
    expected = [np.array([s.q for s in symjac.inverse_kinematics(robot, pose, method="closed_form",
                                                                  within_limits=False).solutions])
                for pose in poses]
    for target, solve in solvers.items():
        found = solve(poses)
        for k, (rows, reference) in enumerate(zip(found, expected, strict=True)):
            assert rows.shape[1:] == (robot.n_coordinates,) and len(rows) >= 1, (target, k)
            assert np.abs(fk(rows) - poses[k]).max() < 1e-10, (target, k)
            assert _turned(rows, q[k:k + 1]).min() < 1e-8, (target, k)  # the configuration that made the pose
            assert len(rows) == len(reference), (target, k)
            assert _turned(rows, reference).min(axis=1).max() < 1e-8, (target, k)


def test_the_numeric_model_solves_a_thousand_poses_in_the_coordinates():
    robot = load_robot("palletizer")
    model = numeric_model(robot)
    lower, upper = coordinate_bounds(robot)
    q = np.random.default_rng(1000).uniform(lower, upper, (1000, robot.n_coordinates))
    poses = model.fk(q)
    solutions, count, branches = model.ik(poses)
    assert solutions.shape == (1000, 4, 4) and count.min() >= 1
    assert np.array_equal(branches >= 0, np.arange(4) < count[:, None])
    flat = solutions.reshape(-1, 4)
    valid = ~np.isnan(flat).any(axis=1)
    assert valid.sum() == count.sum()
    assert np.abs(model.fk(flat[valid]) - np.repeat(poses, count, axis=0)).max() < 1e-10


def test_coordinates_of_joints_inverts_the_coupling():
    assert coordinates_of_joints(load_robot("puma560")) == load_robot("puma560").joint_variables
    t = sp.symbols("theta1:6", real=True)
    assert coordinates_of_joints(ROBOTS["palletizer"]()) == (t[0], t[1], t[2], t[4])
    scara = ROBOTS["belt_scara"]()  # d3 = k theta4 + d30: theta4 is read from joint 4, not from the screw
    assert coordinates_of_joints(scara) == (scara.joint_variables[0], scara.joint_variables[1],
                                            scara.joint_variables[3])
    a, b = sp.symbols("a b", real=True)
    planar = load_robot("planar2r")
    mixed = dataclasses.replace(planar, coupling=Coupling((a, b), (a + b + 1, a - b)))
    values = coordinates_of_joints(mixed)
    joints = dict(zip(planar.joint_variables, (a + b + 1, a - b), strict=True))
    assert [sp.simplify(v.xreplace(joints)) for v in values] == [a, b]
    same = dataclasses.replace(planar, coupling=Coupling((a, b), (a + b, 2 * a + 2 * b)))
    with pytest.raises(CodegenError, match="rank 1, fewer than its 2 columns"):
        coordinates_of_joints(same)

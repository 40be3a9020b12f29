"""The test reference itself: its numbers, read once per robot, follow the robot they were read from."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp
from reference import evaluate, finite_difference_jacobian, frames

from symjac import load_robot
from symjac.model.robot import Parameter


def test_a_robot_with_other_parameter_values_gets_its_own_numbers():
    robot = load_robot("planar2r")
    q = np.array([0.3, -0.5])
    L1 = float(robot.defaults[sp.Symbol("L1", real=True)])
    before = frames(robot, q)[-1]
    longer = dataclasses.replace(robot, parameters=tuple(
        Parameter(p.name, p.default * 2) if p.name == "L1" else p for p in robot.parameters))
    after = frames(longer, q)[-1]
    # the wrist moves by the extra length of link 1, along link 1
    np.testing.assert_allclose(after[:2, 3] - before[:2, 3], L1 * np.array([np.cos(0.3), np.sin(0.3)]), atol=1e-12)
    np.testing.assert_allclose(frames(robot, q)[-1], before, atol=0)


@pytest.mark.parametrize("name", ["planar2r", "ur5_poe"])
def test_changing_a_returned_frame_leaves_the_next_call_alone(name):
    robot = load_robot(name)
    q = np.linspace(-1, 1, robot.n_joints)
    first = frames(robot, q)
    kept = [T.copy() for T in first]
    for T in first:
        T[:] = 0
    for T, expected in zip(frames(robot, q), kept, strict=True):
        np.testing.assert_array_equal(T, expected)


def test_a_compiled_matrix_is_evaluated_afresh_at_each_configuration():
    robot = load_robot("planar2r")
    theta1 = robot.q[0]
    matrix = sp.Matrix([[sp.cos(theta1)]])
    assert evaluate(matrix, robot, np.array([0.0, 0.0]))[0, 0] == 1.0
    assert abs(evaluate(matrix, robot, np.array([np.pi / 2, 0.0]))[0, 0]) < 1e-15
    matrix[0, 0] = sp.sin(theta1)  # the same object changed: compiled again
    assert evaluate(matrix, robot, np.array([np.pi / 2, 0.0]))[0, 0] == 1.0


def test_finite_differences_of_a_coupled_robot_are_in_its_coordinates():
    robot = load_robot("palletizer")
    q = np.array([0.2, -0.4, 0.7, 0.1])
    J = finite_difference_jacobian(robot, q)
    assert J.shape == (6, robot.n_coordinates)
    # theta4 = -(theta2 + theta3) keeps the flange level: no coordinate tilts it about a horizontal axis
    np.testing.assert_allclose(J[3:5], 0, atol=1e-8)

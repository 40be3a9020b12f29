"""Every catalog robot's Jacobian, in every frame and at every point, against finite differences of plain-NumPy FK."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from marks import marked
from reference import evaluate, finite_difference_jacobian, frames, random_configuration

from symjac import (
    ArgumentError,
    FrameError,
    catalog,
    chain_of,
    change_frame,
    forward_kinematics,
    jacobian,
    load_robot,
    shift_point,
)

ROBOTS = sorted(catalog())


def _frames(robot):
    return ["world", *range(robot.n_joints + 1), "tool"]


def _points(robot):
    points = {"wrist": None, "offset": (sp.Rational(1, 10), sp.Rational(-1, 5), sp.Rational(3, 10))}
    if robot.tool is not None:
        points["tool"] = tuple(float(e) for e in robot.tool.matrix[:3, 3].subs(robot.defaults))
    return points


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_forward_kinematics_matches_numpy_reference(name):
    robot = load_robot(name)
    rng = np.random.default_rng(7)
    for _ in range(3):
        q = random_configuration(robot, rng)
        reference = frames(robot, q)
        for i in range(robot.n_joints + 1):
            np.testing.assert_allclose(evaluate(forward_kinematics(robot, 0, i), robot, q),
                                       np.linalg.inv(reference[1]) @ reference[i + 1], atol=1e-12)
        np.testing.assert_allclose(evaluate(forward_kinematics(robot, "world", "tool"), robot, q),
                                   reference[-1], atol=1e-12)


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_jacobian_matches_finite_differences_in_every_frame_and_point(name):
    robot = load_robot(name)
    rng = np.random.default_rng(2024)
    configurations = [random_configuration(robot, rng) for _ in range(2)]
    for frame in _frames(robot):
        for label, point in _points(robot).items():
            argument = "tool" if label == "tool" else "wrist" if point is None else point
            J = jacobian(robot, frame=frame, point=argument)
            assert J.shape == (6, robot.n_coordinates)
            for q in configurations:
                expected = finite_difference_jacobian(robot, q, frame, None if point is None else np.array(point,
                                                                                                          float))
                np.testing.assert_allclose(evaluate(J, robot, q), expected, atol=1e-7,
                                           err_msg=f"{name} frame {frame} point {label}")


@pytest.mark.parametrize("name", marked(ROBOTS))
@pytest.mark.parametrize("frame", [0, "mid", "last", "tool"])
def test_methods_agree_symbolically(name, frame):
    robot = load_robot(name)
    frame = {"mid": robot.n_joints // 2, "last": robot.n_joints}.get(frame, frame)
    point = "tool" if robot.tool is not None else "wrist"
    by_differentiation = jacobian(robot, frame=frame, point=point, method="differentiation")
    # the normal form is unique, so equal functions give identical expressions
    for method in ("cross_product", "velocity_propagation", "force_propagation"):
        assert jacobian(robot, frame=frame, point=point, method=method) == by_differentiation, method


def test_cross_product_in_frame_zero_from_position_differences():
    """The course chapter (4.150) variant: 0z_i x (x_P - p_0i) with everything in {0}, then compared exactly."""
    from symjac.symbolic.simplify import simplify_matrix

    robot = load_robot("puma560")
    chain = chain_of(robot)
    T_0_n = chain.transform(0, robot.n_joints)
    columns = []
    for i in range(1, robot.n_joints + 1):
        T_0_i = chain.transform(0, i)
        z, p_in = T_0_i[:3, 2], T_0_n[:3, 3] - T_0_i[:3, 3]
        columns.append(sp.Matrix.vstack(z.cross(p_in), z))
    J_0 = simplify_matrix(sp.Matrix.hstack(*columns), chain.angle_bases(0))
    assert jacobian(robot) == J_0


def test_frame_change_and_point_shift_helpers_agree_with_direct_derivation():
    robot = load_robot("planar3r")
    chain = chain_of(robot)
    J_0 = jacobian(robot, point="flange", simplify=False)  # planar3r has a tool: the default point is its own
    J_1 = change_frame(J_0, chain.rotation(1, 0))
    from symjac.symbolic.simplify import simplify_matrix

    assert simplify_matrix(J_1, chain.angle_bases(1)) == jacobian(robot, frame=1, point="flange")
    p_we = chain.rotation(0, 3) * robot.tool.matrix[:3, 3]
    J_e = shift_point(J_0, list(p_we))
    assert simplify_matrix(J_e, chain.angle_bases(0)) == jacobian(robot, point="tool")


def test_unsimplified_result_is_numerically_the_same():
    robot = load_robot("ur5")
    rng = np.random.default_rng(1)
    q = random_configuration(robot, rng)
    np.testing.assert_allclose(evaluate(jacobian(robot, frame=3, simplify=False), robot, q),
                               evaluate(jacobian(robot, frame=3), robot, q), atol=1e-12)


def test_jacobian_returns_a_fresh_mutable_copy():
    robot = load_robot("planar2r")
    J = jacobian(robot)
    J[0, 0] = 0
    assert jacobian(robot)[0, 0] != 0


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"frame": 7}, "frame 7 does not exist for puma560"),
        ({"frame": "base"}, "frame 'base' does not exist"),
        ({"frame": True}, "frame True does not exist"),
        ({"point": "tool"}, "puma560 has no tool transform"),
        ({"point": "elbow"}, "unknown point 'elbow'"),
        ({"point": (1, 2)}, "a point needs 3 coordinates"),
        ({"point": (1, 2, float("nan"))}, "not a finite number"),
        ({"method": "magic"}, "unknown method 'magic'"),
    ],
)
def test_bad_arguments_raise_clear_errors(kwargs, message):
    expected = ArgumentError if "method" in kwargs else FrameError  # an unknown method is not a frame error
    with pytest.raises(expected, match=message):
        jacobian(load_robot("puma560"), **kwargs)

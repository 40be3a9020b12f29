"""Velocity and force propagation, statics and the wrench/twist maps, against the notes and independent references."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from marks import marked
from reference import end_of_chain, evaluate, finite_difference_jacobian, random_configuration

from symjac import (
    catalog,
    chain_of,
    force_propagation,
    jacobian,
    joint_rate_symbols,
    joint_torques,
    load_robot,
    robot_from_mapping,
    robot_to_mapping,
    twist_transform,
    velocity_propagation,
    wrench_between,
    wrench_symbols,
    wrench_transform,
)
from symjac.errors import ArgumentError
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.simplify import is_identity
from symjac.symbolic.transforms import homogeneous, inverse_transform, rotation_rpy

L1, L2, L3 = sp.symbols("L1 L2 L3", real=True)
t1, t2, t3 = sp.symbols("theta1 theta2 theta3", real=True)
s1, c1, s12, c12 = sp.sin(t1), sp.cos(t1), sp.sin(t1 + t2), sp.cos(t1 + t2)

FLANGE = (0, 0, 0)
"""The origin of frame {n}, where the course notes' propagations end (the default is the end of the chain)."""


def _identical(left: sp.MatrixBase, right: sp.MatrixBase, robot) -> bool:
    basis = AngleBasis.of(robot.q)
    return left.shape == right.shape and all(is_identity(a, b, basis) for a, b in zip(left, right, strict=True))


# --- the notes' worked examples -----------------------------------------------------------------------------


def test_planar_3r_velocity_propagation_reproduces_seed_000_4_136_to_4_141():
    robot = load_robot("planar3r")
    chain = chain_of(robot)
    rates = sp.Matrix(joint_rate_symbols(robot))
    td1, td2, td3 = rates
    steps = {frame: (omega, v) for frame, omega, v in velocity_propagation(robot, FLANGE).velocities()}
    v_P2 = chain.rotation(0, 2) * steps[2][1]
    assert _identical(v_P2, sp.Matrix([-L1 * s1, L1 * c1, 0]) * td1, robot)  # (4.136)
    v_P3 = chain.rotation(0, 3) * steps[3][1]
    expected = sp.Matrix([-L1 * s1, L1 * c1, 0]) * td1 + sp.Matrix([-L2 * s12, L2 * c12, 0]) * (td1 + td2)
    assert _identical(v_P3, expected, robot)  # (4.138)
    omega_3 = chain.rotation(0, 3) * steps[3][0]
    assert _identical(omega_3, sp.Matrix([0, 0, td1 + td2 + td3]), robot)  # (4.139)
    J_v = sp.Matrix([[-(L1 * s1 + L2 * s12), -L2 * s12, 0], [L1 * c1 + L2 * c12, L2 * c12, 0], [0, 0, 0]])
    assert _identical(chain.rotation(0, 3) * sp.Matrix(velocity_propagation(robot, FLANGE).jacobian[:3, :]), J_v, robot)


def test_stretched_out_2r_arm_holds_a_radial_force_with_zero_torque():
    """The lecture slides: at theta2 = 0 a force F along the arm, F (c1, s1) in {0}, needs no joint torque."""
    robot = load_robot("planar2r")
    F = sp.Symbol("F", real=True)
    tau = joint_torques(robot, wrench=[F * c1, F * s1, 0, 0, 0, 0])
    printed_J_T = sp.Matrix([[-L1 * s1 - L2 * s12, L1 * c1 + L2 * c12], [-L2 * s12, L2 * c12]])  # the slide's 0J^T
    assert _identical(tau, printed_J_T * sp.Matrix([F * c1, F * s1]), robot)
    assert tau.subs(t2, 0).applyfunc(sp.simplify) == sp.zeros(2, 1)
    assert tau.subs(t2, sp.pi / 3).applyfunc(sp.simplify) != sp.zeros(2, 1)  # away from the singularity it does


def test_force_propagation_reproduces_the_transposed_jacobian():
    for name in ("planar3r", "stanford", "puma560"):
        robot = load_robot(name)
        propagation = force_propagation(robot, FLANGE)
        J_n = jacobian(robot, frame=robot.n_joints, point="flange")  # the propagation ends at the origin of {n}
        assert sp.Matrix(propagation.torques) == J_n.T
        tau = propagation.joint_torques()
        assert _identical(tau, J_n.T * sp.Matrix(wrench_symbols()), robot)


def test_method_frames_of_the_seed_002_table():
    """Explicit differentiation yields 0J, velocity propagation nJ, force propagation nJ^T; diag(R, R) links them."""
    robot = load_robot("stanford")
    chain = chain_of(robot)
    n = robot.n_coordinates
    J_n = velocity_propagation(robot, FLANGE).jacobian
    assert _identical(sp.diag(chain.rotation(0, n), chain.rotation(0, n)) * J_n,
                      jacobian(robot, frame=0, method="differentiation", simplify=False), robot)
    assert J_n == sp.Matrix(force_propagation(robot, FLANGE).torques).T


# --- propagation steps against finite differences -------------------------------------------------------------


@pytest.mark.parametrize("name", marked(sorted(catalog())))
def test_every_velocity_step_matches_finite_differences_of_its_frame(name):
    """Each intermediate {}^k(omega_k), {}^kv_k is the Jacobian of frame k's origin, expressed in k."""
    robot = load_robot(name)
    if robot.coupling is not None:
        pytest.skip("frame k is truncated to joints 1..k = coordinates 1..k; coupled steps: tests/test_coordinates.py")
    q = random_configuration(robot, np.random.default_rng(7))
    first, *steps = velocity_propagation(robot, FLANGE).steps
    assert first.frame == 0
    assert sp.Matrix.vstack(sp.Matrix(first.omega), sp.Matrix(first.v)) == sp.zeros(6, robot.n_coordinates)
    for step in steps:
        k = step.frame
        # joints beyond frame k do not move it (standard DH: joint k+1 turns about z_k, through k's origin)
        J_k = sp.Matrix.vstack(sp.Matrix(step.v), sp.Matrix(step.omega))
        assert J_k[:, k:] == sp.zeros(6, robot.n_coordinates - k)
        truncated = _truncated(robot, k)
        expected = finite_difference_jacobian(truncated, q[:k], frame=k)
        np.testing.assert_allclose(evaluate(J_k[:, :k], robot, q), expected, atol=1e-7, err_msg=f"{name} frame {k}")


def _truncated(robot, k):
    """The robot cut after joint k, without base or tool: its frame k is the robot's frame k."""
    data = robot_to_mapping(robot)
    data["joints"] = data["joints"][:k]
    data.pop("base", None)
    data.pop("tool", None)
    return robot_from_mapping(data)


def test_velocity_propagation_to_the_tool_frame_and_to_a_point():
    robot = load_robot("articulated3r")
    q = random_configuration(robot, np.random.default_rng(3))
    tool = velocity_propagation(robot, None)
    assert tool.steps[-1].frame == "tool"
    np.testing.assert_allclose(evaluate(tool.jacobian, robot, q),
                               finite_difference_jacobian(robot, q, frame="tool", point=[0.3, 0, 0]), atol=1e-7)
    point = (sp.Rational(1, 10), 0, sp.Rational(-1, 5))
    at_point = velocity_propagation(robot, point)
    assert at_point.steps[-1].frame == "point"
    np.testing.assert_allclose(evaluate(at_point.jacobian, robot, q),
                               finite_difference_jacobian(robot, q, frame=3, point=[0.1, 0, -0.2]), atol=1e-7)


def test_force_propagation_at_the_tool_frame_is_the_tool_jacobian_transposed():
    robot = load_robot("planar3r")
    propagation = force_propagation(robot, None)
    assert propagation.steps[0].frame == "tool"
    assert jacobian(robot, frame="tool", point="tool") == sp.Matrix(propagation.torques).T


# --- statics ------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", marked(["stanford", "puma560", "ur5", "panda"]))
def test_virtual_work_against_finite_differences(name):
    """tau . dq = F . dx, with tau from force propagation and dx from an independent numeric forward kinematics."""
    robot = load_robot(name)
    rng = np.random.default_rng(11)
    q = random_configuration(robot, rng)
    F = rng.normal(size=6)
    tau = np.array(joint_torques(robot, wrench=list(F), frame=robot.n_joints, q=list(q)), dtype=float).ravel()
    dq = rng.normal(size=robot.n_coordinates)
    dx = finite_difference_jacobian(robot, q, frame=robot.n_joints, point=end_of_chain(robot)) @ dq  # the default
    assert tau @ dq == pytest.approx(F @ dx, rel=1e-6, abs=1e-9)


def test_joint_torques_in_any_frame_agree():
    robot = load_robot("puma560")
    q = list(random_configuration(robot, np.random.default_rng(5)))
    F_3 = np.array([1.0, -2.0, 0.5, 0.1, 0.3, -0.2])
    R_0_3 = evaluate(chain_of(robot).rotation(0, 3), robot, np.array(q))
    F_0 = np.concatenate([R_0_3 @ F_3[:3], R_0_3 @ F_3[3:]])
    tau_3 = np.array(joint_torques(robot, wrench=list(F_3), frame=3, q=q), dtype=float)
    tau_0 = np.array(joint_torques(robot, wrench=list(F_0), frame=0, q=q), dtype=float)
    np.testing.assert_allclose(tau_3, tau_0, atol=1e-12)


def test_force_torque_sensor_reading_moved_to_the_tool_tip_needs_the_same_torques():
    """A reading at a sensor frame {S} fixed in {n}, carried to the tool tip, is held by the same joint torques."""
    robot = load_robot("puma560")
    robot = robot_from_mapping({**robot_to_mapping(robot), "tool": {"xyz": [0, 0.02, 0.15], "rpy": [0, 0.3, -0.5]}})
    chain = chain_of(robot)
    T_n_S = homogeneous(rotation_rpy(sp.Rational(1, 10), 0, sp.Rational(2, 5)), sp.Matrix([0, 0, sp.Rational(1, 20)]))
    T_T_S = chain.transform("tool", robot.n_joints) * T_n_S
    F_S = sp.Matrix([3, -1, 2, sp.Rational(1, 10), 0, sp.Rational(-3, 10)])
    q = list(random_configuration(robot, np.random.default_rng(9)))
    F_tool = list(wrench_transform(T_T_S) * F_S)
    F_wrist = list(wrench_transform(T_n_S) * F_S)
    at_tool = joint_torques(robot, wrench=F_tool, frame="tool", point="tool", q=q)
    at_wrist = joint_torques(robot, wrench=F_wrist, frame=robot.n_joints, point="flange", q=q)
    np.testing.assert_allclose(np.array(at_tool, dtype=float), np.array(at_wrist, dtype=float), atol=1e-10)


def test_twist_maps_between_wrist_and_tool_tip_both_ways():
    robot = load_robot("planar3r")
    chain = chain_of(robot)
    n = robot.n_coordinates
    J_wrist_n = jacobian(robot, frame=n, point="flange")
    J_tool_T = jacobian(robot, frame="tool", point="tool")
    assert _identical(twist_transform(chain.transform(n, "tool")) * J_tool_T, J_wrist_n, robot)
    assert _identical(twist_transform(chain.transform("tool", n)) * J_wrist_n, J_tool_T, robot)


def test_wrench_between_frames_of_a_robot():
    robot = load_robot("planar3r")
    f_y = sp.Symbol("f_y")
    assert list(wrench_between(robot, "tool", 3) * sp.Matrix([0, f_y, 0, 0, 0, 0])) == [0, f_y, 0, 0, 0, L3 * f_y]


# --- the 6 x 6 maps round-trip ----------------------------------------------------------------------------


def _random_transform(rng: np.random.Generator) -> sp.Matrix:
    roll, pitch, yaw, x, y, z = (sp.Rational(int(v), 100) for v in rng.integers(-300, 300, size=6))
    return homogeneous(rotation_rpy(roll, pitch, yaw), sp.Matrix([x, y, z]))


@pytest.mark.parametrize("seed", range(5))
@pytest.mark.slow
def test_wrench_and_twist_maps_round_trip_and_are_dual(seed):
    T = _random_transform(np.random.default_rng(seed))
    T_inv = inverse_transform(T)
    for transform in (wrench_transform, twist_transform):
        product = np.array((transform(T) * transform(T_inv)).evalf(), dtype=float)
        np.testing.assert_allclose(product, np.eye(6), atol=1e-12)
    dual = np.array((wrench_transform(T) - twist_transform(T_inv).T).evalf(), dtype=float)
    np.testing.assert_allclose(dual, np.zeros((6, 6)), atol=1e-12)


def test_maps_round_trip_symbolically():
    a, b, x, y = sp.symbols("a b x y", real=True)
    T = homogeneous(rotation_rpy(0, a, b), sp.Matrix([x, y, 0]))
    product = (wrench_transform(T) * wrench_transform(inverse_transform(T))).applyfunc(sp.trigsimp)
    assert product == sp.eye(6)


def test_twist_map_matches_finite_differences_of_a_rigid_body():
    """Velocities of two frames on one moving body, from the reference FK, are related by twist_transform."""
    robot = load_robot("ur5")
    q = random_configuration(robot, np.random.default_rng(4))
    n = robot.n_coordinates
    J_n = finite_difference_jacobian(robot, q, frame=n)
    offset = np.array([0.05, -0.1, 0.2])
    J_P = finite_difference_jacobian(robot, q, frame=n, point=offset)
    T_P_n = homogeneous(sp.eye(3), sp.Matrix(-offset))  # the point's frame, axes of {n}: origin n seen from P
    np.testing.assert_allclose(np.array(twist_transform(T_P_n).evalf(), dtype=float) @ J_n, J_P, atol=1e-7)


# --- bad input ----------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"wrench": [1, 2, 3]}, "wrench needs 6 entries"),
        ({"wrench": [1, 2, 3, 4, 5, float("nan")]}, r"wrench\[5\] is nan"),
        ({"wrench": "1,2,3,4,5,6"}, "wrench must be a sequence"),
        ({"wrench": [1, 2, 3, 4, 5, "x"]}, r"wrench\[5\] must be a finite number"),
        ({"q": [0.1]}, "q needs 2 entries"),
        ({"q": [0.1, float("inf")]}, r"q\[1\] is inf"),
    ],
)
def test_joint_torques_rejects_bad_input(kwargs, message):
    with pytest.raises(ArgumentError, match=message):
        joint_torques(load_robot("planar2r"), **kwargs)


def test_numeric_torques_accept_numpy_values():
    robot = load_robot("planar2r")
    tau = joint_torques(robot, wrench=np.array([1.0, 0, 0, 0, 0, 0]), q=np.array([np.pi / 2, 0.0]))
    np.testing.assert_allclose(np.array(tau, dtype=float).ravel(), [-0.9, -0.4])

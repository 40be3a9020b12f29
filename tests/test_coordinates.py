"""Coupled joints: a robot's independent coordinates q and joint variables theta(q) = C q + theta_0.

Fixtures build the robots directly (there is no coupling reader yet): a parallelogram palletizer whose flange stays
level (theta4 = -(theta2 + theta3)), the same arm without its flange joint (3 coordinates), and a SCARA whose ball
screw is belt-coupled to the wrist (d3 = k theta4 + d30, symbolic k and d30). Every Jacobian method, the Hessian,
J-dot, the bias, acceleration propagation and statics are checked against central differences of the plain-NumPy
forward kinematics of ``reference.py`` evaluated at theta(q); the identity coupling must change nothing.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp
from marks import marked
from reference import frames

from symjac import RobotFileError, forward_kinematics, jacobian, load_robot, robot_from_mapping
from symjac.analysis.singularity.determinant import determinant
from symjac.kinematics.acceleration import bias_acceleration, hessian, jacobian_derivative
from symjac.kinematics.acceleration_propagation import acceleration_propagation
from symjac.kinematics.chain import chain_of
from symjac.kinematics.coupling import coupling_matrix
from symjac.kinematics.numeric import numeric_jacobian
from symjac.kinematics.propagation import force_propagation, joint_rate_symbols, velocity_propagation
from symjac.kinematics.statics import joint_torques
from symjac.model.coordinates import Coupling
from symjac.model.robot import JointType, Parameter

METHODS = ("differentiation", "cross_product", "velocity_propagation", "force_propagation")
H = 1e-5


def _palletizer(flange: bool) -> object:
    joints = [{"type": "revolute", "alpha": 0, "a": 0, "d": "d1", "theta": 0},
              {"type": "revolute", "alpha": "-pi/2", "a": 0, "d": 0, "theta": 0},
              {"type": "revolute", "alpha": 0, "a": "L2", "d": 0, "theta": 0},
              {"type": "revolute", "alpha": 0, "a": "L3", "d": 0, "theta": 0}]
    if flange:
        joints.append({"type": "revolute", "alpha": "pi/2", "a": "L4", "d": "d5", "theta": 0})
    base = robot_from_mapping({"name": "palletizer", "convention": "modified",
                               "parameters": {"d1": 0.5, "L2": 0.8, "L3": 0.9, "L4": 0.2, "d5": 0.1},
                               "joints": joints})
    t = base.joint_variables
    values = (t[0], t[1], t[2], -t[1] - t[2], *t[4:])
    return dataclasses.replace(base, coupling=Coupling((t[0], t[1], t[2], *t[4:]), values))


def _belt_scara() -> object:
    base = load_robot("scara")
    k, d30 = sp.Symbol("k", real=True), sp.Symbol("d30", real=True)
    t1, t2, _, t4 = base.joint_variables
    parameters = (*base.parameters, Parameter("k", sp.Rational(-1, 50)), Parameter("d30", sp.Rational(-1, 10)))
    return dataclasses.replace(base, parameters=parameters,
                               coupling=Coupling((t1, t2, t4), (t1, t2, k * t4 + d30, t4)))


ROBOTS = {"palletizer": lambda: _palletizer(True), "palletizer3": lambda: _palletizer(False), "belt_scara": _belt_scara}
CACHE: dict[str, object] = {}


def _robot(name: str):
    if name not in CACHE:
        CACHE[name] = ROBOTS[name]()
    return CACHE[name]


def _theta(robot, q: np.ndarray) -> np.ndarray:
    values = {**robot.defaults, **dict(zip(robot.q, q, strict=True))}
    return np.array([float(v.xreplace(values)) for v in robot.joint_values])


def _pose(robot, q: np.ndarray, position: int, point) -> tuple[np.ndarray, np.ndarray]:
    """World pose (point position, rotation) of frame position ``position`` from the reference FK at theta(q)."""
    T = frames(dataclasses.replace(robot, coupling=None), _theta(robot, q))[position]
    return (T @ np.append(point, 1.0))[:3], T[:3, :3]


def _fd_jacobian(robot, q: np.ndarray, frame: int, point) -> np.ndarray:
    """6 x n_coordinates: [v; omega] of the point (in frame {n}) by central differences in q, expressed in {frame}."""
    n, tip = robot.n_coordinates, robot.n_joints + 1
    _, R = _pose(robot, q, tip, point)
    J = np.zeros((6, n))
    for j in range(n):
        step = np.zeros(n)
        step[j] = H
        (x_plus, R_plus), (x_minus, R_minus) = _pose(robot, q + step, tip, point), _pose(robot, q - step, tip, point)
        J[:3, j] = (x_plus - x_minus) / (2 * H)
        w = (R_plus - R_minus) / (2 * H) @ R.T  # angular velocity from R(q + h) R(q)^T
        J[3:, j] = (w[2, 1], w[0, 2], w[1, 0])
    R_k = _pose(robot, q, frame + 1, np.zeros(3))[1]
    return np.kron(np.eye(2), R_k.T) @ J


def _at(robot, matrix, q, qdot=None) -> np.ndarray:
    values = {**robot.defaults, **dict(zip(robot.q, q, strict=True))}
    if qdot is not None:
        values.update(zip(joint_rate_symbols(robot), qdot, strict=True))
    return np.array(sp.Matrix(matrix).xreplace(values).evalf(), dtype=float)


def _configurations(robot, count: int = 2) -> list[np.ndarray]:
    rng = np.random.default_rng(25)
    return [rng.uniform(-2.5, 2.5, robot.n_coordinates) for _ in range(count)]


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_sizes_and_coupling_matrix(name):
    robot = _robot(name)
    assert robot.n_joints == robot.n_coordinates + 1
    assert robot.q == robot.coordinates and len(robot.joint_variables) == robot.n_joints
    assert coupling_matrix(robot).shape == (robot.n_joints, robot.n_coordinates)
    assert forward_kinematics(robot).free_symbols.isdisjoint(set(robot.joint_variables) - set(robot.q))


@pytest.mark.parametrize("name", sorted(ROBOTS))
@pytest.mark.parametrize("method", METHODS)
def test_jacobian_by_every_method_matches_finite_differences(name, method):
    robot = _robot(name)
    offset = (sp.Rational(1, 10), sp.Rational(-1, 5), sp.Rational(3, 10))
    for frame in (0, 2, robot.n_joints):
        for point in ("wrist", offset):
            xyz = np.zeros(3) if point == "wrist" else np.array(offset, dtype=float)
            for simplify in (True, False):
                J = jacobian(robot, frame=frame, point=point, method=method, simplify=simplify)
                assert J.shape == (6, robot.n_coordinates)
                for q in _configurations(robot):
                    np.testing.assert_allclose(_at(robot, J, q), _fd_jacobian(robot, q, frame, xyz), atol=1e-7)


@pytest.mark.parametrize("name", sorted(ROBOTS))
@pytest.mark.parametrize("frame", [0, 2])
def test_hessian_jdot_and_bias_match_finite_differences(name, frame):
    robot = _robot(name)
    n = robot.n_coordinates
    Hq = hessian(robot, frame=frame)
    assert Hq.shape == (6, n, n)
    J = jacobian(robot, frame=frame)
    rates = sp.Matrix(joint_rate_symbols(robot))
    for q in _configurations(robot):
        qdot = np.linspace(-0.7, 0.9, n)
        for m in range(n):
            step = np.zeros(n)
            step[m] = H
            slice_m = np.array([[float(_at(robot, sp.Matrix([Hq[i, j, m]]), q)[0, 0]) for j in range(n)]
                                for i in range(6)])
            central = (numeric_jacobian(robot, q + step, frame) - numeric_jacobian(robot, q - step, frame)) / (2 * H)
            np.testing.assert_allclose(slice_m, central, atol=1e-7)
        path = (numeric_jacobian(robot, q + H * qdot, frame) - numeric_jacobian(robot, q - H * qdot, frame)) / (2 * H)
        for method in ("hessian", "differentiation"):
            Jdot = jacobian_derivative(robot, frame=frame, method=method)
            np.testing.assert_allclose(_at(robot, Jdot, q, qdot), path, atol=1e-7)
            np.testing.assert_allclose(_at(robot, bias_acceleration(robot, frame=frame, method=method), q, qdot),
                                       path @ qdot[:, None], atol=1e-7)
        if frame == 0:  # the linear bias is the point's acceleration along q + t qdot: a second difference of FK
            tip = robot.n_joints + 1
            x = [_pose(robot, q + s * 1e-4 * qdot, tip, np.zeros(3))[0] for s in (-1, 0, 1)]
            np.testing.assert_allclose(_at(robot, bias_acceleration(robot), q, qdot)[:3, 0],
                                       (x[2] - 2 * x[1] + x[0]) / 1e-8, atol=1e-5)
        assert J.shape == (6, n) and rates.shape == (n, 1)


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_acceleration_propagation_in_the_coordinates(name):
    """The wrist's [vdot; omegadot] in {n} equals diag(R_n0, R_n0) (J_0 qddot + Jdot_0 qdot)."""
    robot = _robot(name)
    n = robot.n_coordinates
    result = acceleration_propagation(robot)
    assert result.rates == joint_rate_symbols(robot) and len(result.accelerations) == n
    for q in _configurations(robot):
        qdot, qddot = np.linspace(-0.7, 0.9, n), np.linspace(0.4, -0.5, n)
        values = dict(zip(result.accelerations, qddot, strict=True))
        got = _at(robot, result.acceleration.xreplace(values), q, qdot)[:, 0]
        R = _pose(robot, q, robot.n_joints + 1, np.zeros(3))[1]
        expected = numeric_jacobian(robot, q, 0) @ qddot + _at(robot, bias_acceleration(robot), q, qdot)[:, 0]
        np.testing.assert_allclose(got, np.kron(np.eye(2), R.T) @ expected, atol=1e-9)


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_statics_is_c_transpose_j_transpose_f(name):
    robot = _robot(name)
    joints = dataclasses.replace(robot, coupling=None)
    C = np.array(coupling_matrix(robot).xreplace(robot.defaults), dtype=float)
    F = np.array([0.3, -1.2, 2.0, 0.1, 0.4, -0.6])
    torques = force_propagation(robot).torques
    assert torques.shape == (robot.n_coordinates, 6)
    for q in _configurations(robot):
        J_joints = numeric_jacobian(joints, _theta(robot, q), 2)
        expected = C.T @ J_joints.T @ F
        np.testing.assert_allclose(_at(robot, joint_torques(robot, F.tolist(), frame=2), q)[:, 0], expected,
                                   atol=1e-9)
        J_n = numeric_jacobian(robot, q, robot.n_joints)
        np.testing.assert_allclose(_at(robot, torques, q), J_n.T, atol=1e-9)


def test_velocity_propagation_steps_are_in_the_coordinate_rates():
    robot = _robot("palletizer")
    result = velocity_propagation(robot)
    assert result.rates == joint_rate_symbols(robot) == tuple(sp.symbols("thetadot1 thetadot2 thetadot3 thetadot5",
                                                                         real=True))
    assert all(step.omega.shape == (3, 4) for step in result.steps)


def test_palletizer_flange_stays_level_and_its_square_jacobian_is_singular_where_the_arm_folds():
    robot = _robot("palletizer")
    J = jacobian(robot)
    assert J[3:5, :] == sp.zeros(2, 4)  # the parallelogram keeps the flange level: no roll or pitch, ever
    det = determinant(robot, rows=(0, 1, 2, 5))
    factors = {str(f) for f, _ in det.factors}
    assert "sin(theta3)" in factors and "L2*cos(theta2) + L3*cos(theta2 + theta3) + L4" in factors


def test_three_coordinate_arm_position_determinant():
    robot = _robot("palletizer3")
    J = jacobian(robot)[:3, :]
    assert J.shape == (3, 3)
    for q in _configurations(robot, 3):
        expected = np.linalg.det(_fd_jacobian(robot, q, 0, np.zeros(3))[:3, :])
        assert float(_at(robot, sp.Matrix([J.det()]), q)[0, 0]) == pytest.approx(expected, abs=1e-7)


def test_symbolic_coefficient_appears_in_the_jacobian():
    robot = _robot("belt_scara")
    k = sp.Symbol("k", real=True)
    J = jacobian(robot)
    assert J[2, 2] == k  # the screw descends k per radian of the wrist
    assert robot.coordinate_types == (JointType.REVOLUTE,) * 3


@pytest.mark.parametrize("name", marked(["planar3r", "scara", "stanford"]))
def test_identity_coupling_changes_nothing(name):
    robot = load_robot(name)
    identity = dataclasses.replace(robot, coupling=Coupling(robot.joint_variables, robot.joint_variables))
    assert identity.coupling is None and identity == robot and chain_of(identity) is chain_of(robot)
    for method in METHODS:
        assert jacobian(identity, frame=1, method=method) == jacobian(robot, frame=1, method=method)
    assert hessian(identity) == hessian(robot)
    assert jacobian_derivative(identity) == jacobian_derivative(robot)
    assert bias_acceleration(identity, frame=2) == bias_acceleration(robot, frame=2)
    assert forward_kinematics(identity, 0, "tool") == forward_kinematics(robot, 0, "tool")
    assert force_propagation(identity).torques == force_propagation(robot).torques


@pytest.mark.parametrize("name", marked(["planar3r", "scara", "stanford"]))
def test_renamed_coordinates_give_todays_results_renamed(name):
    """theta_i = q_i goes through every step of the coupling (substitution, C = I, layout) and changes only names."""
    robot = load_robot(name)
    q = tuple(sp.Symbol(f"q{i + 1}", real=True) for i in range(robot.n_joints))
    renamed = dataclasses.replace(robot, coupling=Coupling(q, q))
    names = dict(zip(robot.joint_variables, q, strict=True))
    rates = dict(zip(joint_rate_symbols(robot), joint_rate_symbols(renamed), strict=True))
    assert joint_rate_symbols(renamed)[0] == sp.Symbol("qdot1", real=True)
    for method in METHODS:
        assert jacobian(renamed, frame=1, method=method) == jacobian(robot, frame=1, method=method).xreplace(names)
    assert hessian(renamed) == hessian(robot).xreplace(names)
    assert sp.expand(jacobian_derivative(renamed) - jacobian_derivative(robot).xreplace({**names, **rates})) == (
        sp.zeros(6, robot.n_joints))


@pytest.mark.parametrize(("values", "message"), [
    (lambda t: (t[0], t[1]), "2 joint values for 3 joints"),
    (lambda t: (t[0], t[1], t[1] ** 2), "joint 3: theta2\\*\\*2 is not affine"),
    (lambda t: (t[0], t[1], t[1] + sp.Symbol("zeta", real=True)), "joint 3: unknown symbol zeta"),
    (lambda t: (t[0], t[1], t[1] * t[0]), "not affine in the coordinates \\(theta1, theta2\\)"),
])
def test_invalid_couplings_say_what_is_wrong(values, message):
    robot = load_robot("planar3r")
    t = robot.joint_variables
    with pytest.raises(RobotFileError, match=message):
        dataclasses.replace(robot, coupling=Coupling((t[0], t[1]), values(t)))


def test_coordinate_names_are_checked():
    robot = load_robot("planar3r")
    t = robot.joint_variables
    with pytest.raises(RobotFileError, match="must be a real symbol"):
        dataclasses.replace(robot, coupling=Coupling((sp.Symbol("q1"), t[1], t[2]), (sp.Symbol("q1"), t[1], t[2])))
    with pytest.raises(RobotFileError, match="coordinate theta3 is the variable of joint 3"):
        dataclasses.replace(robot, coupling=Coupling((t[0], t[2]), (t[0], t[2], t[0])))
    with pytest.raises(RobotFileError, match="coordinate L1 is also a parameter"):
        L1 = sp.Symbol("L1", real=True)
        dataclasses.replace(robot, coupling=Coupling((t[0], t[1], L1), (t[0], t[1], L1)))

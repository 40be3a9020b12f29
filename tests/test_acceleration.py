"""Acceleration level: the kinematic Hessian, the Jacobian's time derivative, the bias and acceleration propagation.

Independent checks: central differences of the numeric Jacobian and of the plain-NumPy forward kinematics in
``reference.py``, exact symbolic identities (the planar 2R closed form; three routes to the bias on every built-in
arm), and hypothesis over random DH chains. Each robot is derived once (the chain memoizes), and every numeric
check compiles one stacked matrix per robot, frame and point.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from marks import marked
from reference import frame_index, frames, random_configuration
from strategies import general_robots, robots

from symjac import (
    catalog,
    chain_of,
    jacobian,
    load_robot,
    numeric_jacobian,
    robot_from_mapping,
    robot_to_mapping,
    urdf_catalog,
)
from symjac.errors import ArgumentError, FrameError
from symjac.kinematics.acceleration import bias_acceleration, hessian, hessian_slice, jacobian_derivative
from symjac.kinematics.acceleration_propagation import acceleration_propagation, joint_accelerations
from symjac.kinematics.coupling import coordinate_bases, in_coordinates
from symjac.kinematics.propagation import joint_rate_symbols
from symjac.printing.steps import propagation_steps
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.nested import lambdify_cse
from symjac.symbolic.simplify import is_identity
from symjac.symbolic.trigpoly import image_of

ROBOTS = sorted(catalog()) + sorted(urdf_catalog())
RTOL = 1e-6


@cache
def _robot(name: str):
    if name == "articulated3r+base":  # a base transform makes "world" differ from {0}
        data = robot_to_mapping(load_robot("articulated3r"))
        data["base"] = {"xyz": [0.1, -0.2, 0.3], "rpy": [0.4, -0.3, 1.2]}
        return robot_from_mapping(data)
    return load_robot(name)


def _close(actual: np.ndarray, expected: np.ndarray, rtol: float = RTOL) -> bool:
    """Agreement to ``rtol`` relative to the larger of the expected magnitude and 1 (lengths here are O(1))."""
    scale = max(1.0, float(np.max(np.abs(expected), initial=0.0)))
    return bool(np.max(np.abs(np.asarray(actual) - expected), initial=0.0) <= rtol * scale)


def _state(robot, seed: int = 7) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    n = robot.n_coordinates
    return random_configuration(robot, rng), rng.uniform(-1.5, 1.5, n), rng.uniform(-2.0, 2.0, n)


def _compile(robot, matrices: list[sp.MatrixBase]):
    """One numeric function of (q, qdot, qddot) for several symbolic matrices (parameters at their defaults)."""
    shapes = [m.shape for m in matrices]
    stacked = sp.Matrix.vstack(*[sp.Matrix(m).reshape(m.rows * m.cols, 1) for m in matrices])
    stacked = stacked.xreplace(robot.defaults)
    args = [list(robot.q), list(joint_rate_symbols(robot)), list(joint_accelerations(robot))]
    function = sp.lambdify(args, stacked, modules="numpy", cse=lambdify_cse)  # nested results (generic twists)
    ends = np.cumsum([rows * cols for rows, cols in shapes])

    def evaluate(q, qd, qdd) -> list[np.ndarray]:
        values = np.asarray(function(q, qd, qdd), dtype=float).reshape(-1)
        return [part.reshape(shape) for part, shape in zip(np.split(values, ends[:-1]), shapes, strict=True)]

    return evaluate


def _cases():
    """(robot, frame, point, methods): every frame kind on every arm; differentiation where it stays cheap.

    SymPy's derivative of a Jacobian expressed in a far moving frame is ten times the size of the Hessian route
    (Panda in its tool frame: about 200k operations against 20k), so that route is checked numerically in {0} and a
    middle frame of the arms up to six joints, and symbolically in {0} on every arm (test_three_routes_...).
    ``"world"`` is {0} for every built-in arm (none has a base transform): an arm given one exercises it.
    """
    both, hessian_only = ("hessian", "differentiation"), ("hessian",)
    for name in ROBOTS:
        robot = _robot(name)
        n = robot.n_coordinates
        yield name, 0, "wrist", both if n < 7 else hessian_only
        if not name.endswith(".urdf"):  # the URDF arms are catalog arms in the general convention
            yield name, n // 2, "wrist", both if n < 7 else hessian_only
        if name != "panda":  # its tool frame is panda.urdf's (the same arm); planar3r, articulated3r: modified DH
            yield (name, "tool", "tool", hessian_only) if robot.tool else (name, n, "wrist", hessian_only)
    yield "articulated3r+base", "world", "tool", both
    yield "articulated3r+base", 0, "wrist", both
    yield "articulated3r+base", "tool", "wrist", both


CASES = {(name, frame, point): methods for name, frame, point, methods in _cases()}
MOVING = [case for case in CASES if case[1] not in (0, "world") and case[2] == "wrist"]


def _ids(cases) -> list[str]:
    return ["-".join(map(str, case)) for case in cases]


@cache
def _numeric_derivatives(name: str, frame, point: str):
    """H (6 x n x n), then per method of :data:`CASES` Jdot and the bias: one compiled function per case."""
    methods = CASES[name, frame, point]
    robot = _robot(name)
    n = robot.n_coordinates
    H = hessian(robot, frame, point, simplify=False)
    matrices = [sp.Matrix(H.reshape(6, n * n).tolist())]
    for method in methods:
        matrices += [jacobian_derivative(robot, frame, point, method, simplify=False),
                     bias_acceleration(robot, frame, point, method, simplify=False)]
    return _compile(robot, matrices)


# --- against central differences ------------------------------------------------------------------------------


@pytest.mark.parametrize(("name", "frame", "point"), marked(CASES), ids=_ids(CASES))
def test_hessian_and_jacobian_derivative_match_central_differences(name, frame, point):
    robot = _robot(name)
    n, h = robot.n_coordinates, 1e-6
    q, qd, qdd = _state(robot)
    H, *derivatives = _numeric_derivatives(name, frame, point)(q, qd, qdd)
    H = H.reshape(6, n, n)

    def J(values):
        return numeric_jacobian(robot, values, frame, point)

    for m in range(n):
        step = np.eye(n)[m] * h
        assert _close(H[:, :, m], (J(q + step) - J(q - step)) / (2 * h)), f"dJ/dq{m + 1}"
    Jdot_fd = (J(q + h * qd) - J(q - h * qd)) / (2 * h)  # along q + t qdot
    for Jdot, bias in zip(derivatives[::2], derivatives[1::2], strict=True):
        assert _close(Jdot, Jdot_fd)
        assert _close(bias[:, 0], Jdot_fd @ qd)


FIXED = [case for case in CASES if case[1] in (0, "world")]


@pytest.mark.parametrize(("name", "frame", "point"), marked(FIXED), ids=_ids(FIXED))
def test_fixed_frame_linear_hessian_rows_are_symmetric_exactly(name, frame, point):
    n = _robot(name).n_coordinates
    H = hessian(_robot(name), frame, point, simplify=False)
    assert all(H[i, j, m] == H[i, m, j] for i in range(3) for j in range(n) for m in range(n))


def _omega_world(robot, q_of_t, t: float, h: float = 1e-5) -> np.ndarray:
    """Angular velocity of every frame, world axes, from (R(t+h) - R(t-h)) R(t)^T / 2h (a list over frames)."""
    plus, minus, mid = frames(robot, q_of_t(t + h)), frames(robot, q_of_t(t - h)), frames(robot, q_of_t(t))
    result = []
    for P, M, T in zip(plus, minus, mid, strict=True):
        W = (P[:3, :3] - M[:3, :3]) / (2 * h) @ T[:3, :3].T
        result.append(np.array([W[2, 1], W[0, 2], W[1, 0]]))
    return np.array(result)


def _reference_motion(robot, q, qd, qdd):
    """Per frame position (world, 0..n, tool): omega, alpha, v, a of its origin, world axes, from differences.

    Along q(t) = q + t qdot + t^2/2 qddot; fourth-order stencils keep the truncation error near 1e-10.
    """
    def q_of_t(t: float) -> np.ndarray:
        return q + t * qd + 0.5 * t * t * qdd

    H = 1e-3
    origins = {s: np.array([T[:3, 3] for T in frames(robot, q_of_t(s * H))]) for s in (-2, -1, 0, 1, 2)}
    v = (origins[-2] - 8 * origins[-1] + 8 * origins[1] - origins[2]) / (12 * H)
    a = (-origins[-2] + 16 * origins[-1] - 30 * origins[0] + 16 * origins[1] - origins[2]) / (12 * H * H)
    omegas = {s: _omega_world(robot, q_of_t, s * H) for s in (-2, -1, 0, 1, 2)}
    alpha = (omegas[-2] - 8 * omegas[-1] + 8 * omegas[1] - omegas[2]) / (12 * H)
    return omegas[0], alpha, v, a


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_every_propagation_step_matches_differences_of_the_forward_kinematics(name):
    robot = _robot(name)
    q, qd, qdd = _state(robot, seed=11)
    result = acceleration_propagation(robot, None, simplify=False)
    values = _compile(robot, [sp.Matrix.hstack(s.omega, s.omegadot, s.v, s.vdot) for s in result.steps])(q, qd, qdd)
    omega, alpha, v, a = _reference_motion(robot, q, qd, qdd)
    poses = frames(robot, q)
    for step, computed in zip(result.steps, values, strict=True):
        index = frame_index(robot, step.frame)
        R = poses[index][:3, :3]  # world axes -> the step frame's axes by R^T
        expected = np.column_stack([R.T @ omega[index], R.T @ alpha[index], R.T @ v[index], R.T @ a[index]])
        assert _close(computed, expected), f"frame {step.frame}"


def test_a_point_fixed_in_the_last_frame_moves_like_the_hessian_says():
    robot = _robot("articulated3r")
    point = (sp.Rational(1, 10), 0, sp.Rational(1, 5))
    result = acceleration_propagation(robot, point, simplify=False)
    assert result.tip.frame == "point"
    chain = chain_of(robot)
    R = chain.rotation(0, robot.n_joints)
    tip = sp.Matrix.vstack(R * result.acceleration[:3, :], R * result.acceleration[3:, :])
    J = jacobian(robot, 0, list(point), simplify=False)
    expected = J * sp.Matrix(joint_accelerations(robot)) + bias_acceleration(robot, 0, list(point), simplify=False)
    q, qd, qdd = _state(robot)
    computed, wanted = _compile(robot, [tip, expected])(q, qd, qdd)
    assert _close(computed, wanted)


# --- frames: fixed and moving ---------------------------------------------------------------------------------


@pytest.mark.parametrize(("name", "frame", "point"), marked(MOVING), ids=_ids(MOVING))
def test_moving_frame_derivative_is_the_rotated_fixed_one_minus_the_frame_spin(name, frame, point):
    robot = _robot(name)
    if robot.coupling is not None:
        pytest.skip("the expected spin takes joints 1..k as coordinates 1..k; coupled: tests/test_coordinates.py")
    q, qd, qdd = _state(robot)
    n = robot.n_coordinates
    J_0 = numeric_jacobian(robot, q, 0, point)
    Jdot_0 = _numeric_derivatives(name, 0, point)(q, qd, qdd)[1]
    index = frame_index(robot, frame)
    poses = frames(robot, q)
    R_0_k = (np.linalg.inv(poses[1]) @ poses[index])[:3, :3]  # poses[1] is {0} in the world
    carried = min(index - 1, n)  # joints 1..k turn {k}
    w = R_0_k.T @ (J_0[3:, :carried] @ qd[:carried])
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    expected = np.kron(np.eye(2), R_0_k.T) @ Jdot_0 - np.kron(np.eye(2), W) @ numeric_jacobian(robot, q, frame, point)
    assert _close(_numeric_derivatives(name, frame, point)(q, qd, qdd)[1], expected)


@pytest.mark.parametrize("name", marked(["puma560", "ur5", "stanford"]))
def test_wrist_frame_derivative_gives_pinocchio_local_spatial_acceleration(name):
    robot = _robot(name)
    n = robot.n_coordinates
    q, qd, qdd = _state(robot, seed=3)
    Jdot_n = _numeric_derivatives(name, n, "wrist")(q, qd, qdd)[1]  # d/dt of the Jacobian in {n}
    spatial = Jdot_n @ qd + numeric_jacobian(robot, q, n) @ qdd
    omega, alpha, v, a = _reference_motion(robot, q, qd, qdd)
    index = frame_index(robot, n)
    R = frames(robot, q)[index][:3, :3]
    w_n, v_n, a_n = R.T @ omega[index], R.T @ v[index], R.T @ a[index]
    assert _close(spatial, np.concatenate([a_n - np.cross(w_n, v_n), R.T @ alpha[index]]))
    assert not _close(spatial[:3], a_n)  # the classical acceleration is a different vector


# --- exact symbolic identities --------------------------------------------------------------------------------


def _all_zero(differences: list[sp.Expr], basis: AngleBasis) -> bool:
    """Whether every expression vanishes identically in the joint angles (one polynomial ring for all)."""
    _, polys = image_of(differences, basis)
    return not any(polys)


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_three_routes_to_the_bias_agree_symbolically(name):
    """Hessian columns, differentiation of J, and the propagation at zero joint acceleration rotated into {0}."""
    robot = _robot(name)
    chain = chain_of(robot)
    point, tip = ("tool", None) if name in ("planar3r", "articulated3r", "ur5.urdf") else ("wrist", (0, 0, 0))
    result = acceleration_propagation(robot, tip, simplify=False)
    R = in_coordinates(chain, sp.Matrix(chain.rotation(0, result.tip.frame if result.tip.frame == "tool"
                                                     else robot.n_joints)))
    propagated = sp.Matrix.vstack(R * result.bias[:3, :], R * result.bias[3:, :])
    by_hessian = bias_acceleration(robot, 0, point, "hessian", simplify=False)
    by_differentiation = bias_acceleration(robot, 0, point, "differentiation", simplify=False)
    differences = [*(propagated - by_hessian), *(by_differentiation - by_hessian)]
    assert _all_zero(differences, coordinate_bases(chain, 0)[0])


def test_full_tip_acceleration_is_J_qddot_plus_bias_symbolically():
    robot = _robot("stanford")  # revolute and prismatic joints
    chain = chain_of(robot)
    result = acceleration_propagation(robot, simplify=False)
    R = chain.rotation(0, robot.n_joints)
    propagated = sp.Matrix.vstack(R * result.acceleration[:3, :], R * result.acceleration[3:, :])
    expected = jacobian(robot, 0, simplify=False) * sp.Matrix(joint_accelerations(robot)) + bias_acceleration(
        robot, 0, simplify=False)
    assert _all_zero(list(propagated - expected), chain.angle_bases(0)[0])


def test_planar_2r_bias_is_the_textbook_closed_form():
    robot = _robot("planar2r")
    L1, L2, t1, t2 = sp.symbols("L1 L2 theta1 theta2", real=True)
    td1, td2 = joint_rate_symbols(robot)
    expected = [-L1 * sp.cos(t1) * td1**2 - L2 * sp.cos(t1 + t2) * (td1 + td2) ** 2,
                -L1 * sp.sin(t1) * td1**2 - L2 * sp.sin(t1 + t2) * (td1 + td2) ** 2, 0, 0, 0, 0]
    basis = AngleBasis.of(robot.q)
    for method in ("hessian", "differentiation"):
        bias = bias_acceleration(robot, 0, method=method)
        assert all(is_identity(a, b, basis) for a, b in zip(bias, expected, strict=True))
    assert not is_identity(bias[0], expected[0] + L2 * td1 * td2, basis)


def test_acceleration_steps_print_as_equations():
    lines = propagation_steps(acceleration_propagation(_robot("planar2r")), "latex")
    assert len(lines) == 12  # frames 0, 1, 2; four vectors each
    assert lines[-1].startswith(r"{}^{2}\dot v_{2} = ")
    assert r"\ddot{\theta}_{1}" in lines[-1]
    assert r"\left(\dot{\theta}_{1} + \dot{\theta}_{2}\right)^{2}" in lines[-1]  # rate sums factored
    pretty = propagation_steps(acceleration_propagation(_robot("scara")), "pretty")
    assert any(line.startswith("v̇_4 (in frame 4)") and "d̈₃" in line for line in pretty)


# --- the comparison can fail ----------------------------------------------------------------------------------


def test_a_perturbed_hessian_entry_is_caught():
    robot = _robot("ur5")
    q, qd, qdd = _state(robot)
    n, h = robot.n_coordinates, 1e-6
    H = _numeric_derivatives("ur5", 0, "wrist")(q, qd, qdd)[0].reshape(6, n, n)
    step = np.eye(n)[2] * h
    fd = (numeric_jacobian(robot, q + step) - numeric_jacobian(robot, q - step)) / (2 * h)
    assert _close(H[:, :, 2], fd)
    wrong = H[:, :, 2].copy()
    wrong[1, 4] *= 1 + 1e-5
    wrong[1, 4] += 1e-5  # also when the entry is zero
    assert not _close(wrong, fd)
    H_sym = hessian(robot, simplify=False)
    basis = chain_of(robot).angle_bases(0)[0]
    assert _all_zero([H_sym[0, 1, 2] - H_sym[0, 2, 1]], basis)
    tiny = sp.Rational(1, 10**9) * sp.cos(robot.q[0]) ** 2  # symbolically, a nonzero remainder of any size counts
    assert not _all_zero([H_sym[0, 1, 2] - H_sym[0, 2, 1] + tiny], basis)


# --- errors ---------------------------------------------------------------------------------------------------


def test_errors_name_the_problem():
    robot = _robot("planar2r")
    with pytest.raises(ArgumentError, match="unknown method 'numeric'"):
        jacobian_derivative(robot, method="numeric")  # type: ignore[arg-type]
    with pytest.raises(ArgumentError, match="unknown method"):
        bias_acceleration(robot, method="finite")  # type: ignore[arg-type]
    with pytest.raises(FrameError, match="frame 5 does not exist"):
        hessian(robot, 5)
    with pytest.raises(FrameError, match="no 'tool' point"):
        bias_acceleration(robot, 0, "tool")
    with pytest.raises(ArgumentError, match=r"outside 0\.\.1"):
        hessian_slice(hessian(robot), 2)


# --- random chains --------------------------------------------------------------------------------------------


@settings(max_examples=5, deadline=None)
@given(robot=robots(max_joints=7))
def test_random_chains_hessian_and_three_bias_routes(robot):
    n, h = robot.n_coordinates, 1e-6
    q, qd, qdd = _state(robot, seed=n)
    frame = n // 2
    H = hessian(robot, frame, simplify=False)
    biases = [bias_acceleration(robot, 0, method=m, simplify=False) for m in ("hessian", "differentiation")]
    result = acceleration_propagation(robot, simplify=False)
    R = chain_of(robot).rotation(0, n)
    biases.append(sp.Matrix.vstack(R * result.bias[:3, :], R * result.bias[3:, :]))
    values = _compile(robot, [sp.Matrix(H.reshape(6, n * n).tolist()), *biases])(q, qd, qdd)
    H_num = values[0].reshape(6, n, n)
    for m in range(n):
        step = np.eye(n)[m] * h
        fd = (numeric_jacobian(robot, q + step, frame) - numeric_jacobian(robot, q - step, frame)) / (2 * h)
        assert _close(H_num[:, :, m], fd)
    fd_bias = (numeric_jacobian(robot, q + h * qd) - numeric_jacobian(robot, q - h * qd)) / (2 * h) @ qd
    for bias in values[1:]:
        assert _close(bias[:, 0], fd_bias)


@settings(max_examples=3, deadline=None)
@given(robot=general_robots(max_joints=4))
def test_random_general_chains_propagate_the_bias(robot):
    n = robot.n_coordinates
    q, qd, qdd = _state(robot, seed=n)
    result = acceleration_propagation(robot, None, simplify=False)
    R = chain_of(robot).rotation(0, "tool")
    propagated = sp.Matrix.vstack(R * result.acceleration[:3, :], R * result.acceleration[3:, :])
    J = jacobian(robot, 0, "tool" if robot.tool else "wrist", simplify=False)
    expected = J * sp.Matrix(joint_accelerations(robot)) + bias_acceleration(
        robot, 0, "tool" if robot.tool else "wrist", simplify=False)
    computed, wanted = _compile(robot, [propagated, expected])(q, qd, qdd)
    assert _close(computed, wanted)

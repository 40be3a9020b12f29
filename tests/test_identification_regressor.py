"""The regressor form tau = Y pi against the torques of Newton-Euler, an independent numeric one, and pinocchio's.

Three independent checks of Y: (a) exactly, with the robot's own symbolic inertial data (m2, cx2, Izz2, ...) turned
into standard parameters (``standard_values``), Y pi equals ``newton_euler``'s torques as an identity in the joint
angles (normal forms); (b) numerically, on random chains (hypothesis) with random physical bodies, Y pi equals the
spatial-vector Newton-Euler of ``reference_dynamics`` (nothing of symjac's dynamics) to 1e-9; (c) on the URDF arms
of example-robot-data, against pinocchio's ``computeJointTorqueRegressor``, column by column once each library's
parameters are written in the other's frame (pinocchio's body frame is the URDF joint frame; symjac's link frame
{i} of the general convention is turned so that z is the joint axis), and Y pi against pinocchio's ``rnea``.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import frames
from reference_dynamics import NumericDynamics
from strategies import general_robots, robots

from symjac import load_robot, regressor, robot_from_mapping
from symjac.analysis.dynamics import Gravity, dynamics_defaults, newton_euler
from symjac.analysis.identification import standard_parameters, standard_values
from symjac.errors import ArgumentError, NoInertialDataError
from symjac.kinematics.chain import Chain
from symjac.model.inertia import Inertial, combined_inertial
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.nested import lambdify_cse
from symjac.symbolic.simplify import is_identity


def _torques(Y, values: dict) -> sp.Matrix:
    return Y.matrix * sp.Matrix([values.get(p, 0) for p in Y.parameters])


@pytest.mark.parametrize(("name", "gravity"), [("planar2r", Gravity(direction=(0, -1, 0))),
                                               ("planar3r", Gravity(direction=(1, -1, 0))),
                                               ("stanford", Gravity()), ("palletizer", Gravity())])
def test_y_pi_is_the_newton_euler_torques_exactly(name, gravity):
    """Symbolic inertial data of every link: Y pi = tau as an identity, gravity in the arm's plane for planar arms."""
    arm = load_robot(name)
    Y = regressor(arm, gravity)
    assert Y.matrix.shape == (len(arm.q), 10 * arm.n_joints)
    assert Y.names == tuple(p.name for p in Y.parameters) == tuple(p.name for p in standard_parameters(arm))
    tau = newton_euler(arm, gravity).torques
    basis = AngleBasis.of(list(arm.q))
    assert all(is_identity(a, b, basis) for a, b in zip(_torques(Y, standard_values(arm)), tau, strict=True))
    assert any(entry.has(gravity.magnitude) for entry in Y.matrix)  # gravity is in it: the check can fail


def _body(rng: np.random.Generator) -> Inertial:
    """A rigid body of three point masses at rational points: always physical, inertia about the centre not zero."""
    return combined_inertial([Inertial(sp.Rational(int(rng.integers(1, 9)), 4),
                                       tuple(sp.Rational(int(v), 10) for v in rng.integers(-3, 4, 3)))
                              for _ in range(3)])


@settings(max_examples=12, deadline=None)
@given(robot=st.one_of(robots(max_joints=5), general_robots(max_joints=4)), seed=st.integers(0, 2**16))
def test_random_chains_y_pi_equals_a_numeric_newton_euler(robot, seed):
    rng = np.random.default_rng(seed)
    arm = dataclasses.replace(robot, inertials=tuple(_body(rng) for _ in robot.joints))
    Y = regressor(arm)
    numbers = {s: float(v) for s, v in dynamics_defaults(arm).items()}
    pi = np.array([float(sp.sympify(standard_values(arm)[p]).xreplace(arm.defaults)) for p in Y.parameters])
    args = [*arm.q, *arm.coordinate_rates, *arm.coordinate_accelerations, *numbers]
    function = sp.lambdify(args, sp.Matrix(Y.matrix), cse=lambdify_cse)
    reference = NumericDynamics(arm)
    for _ in range(2):
        q, qd, qdd = (rng.uniform(-2, 2, arm.n_joints) for _ in range(3))
        expected = reference.tau(q, qd, qdd)
        got = np.array(function(*q, *qd, *qdd, *numbers.values()), dtype=float) @ pi
        assert np.abs(got - expected).max() <= 1e-9 * max(1.0, np.abs(expected).max())


def test_the_nested_route_gives_the_same_regressor():
    """A chain built nested (generic geometry's route: every entry named) gives the exact route's Y."""
    arm = load_robot("stanford")
    exact, nested = regressor(arm).matrix, regressor(Chain(arm, nested=True)).matrix
    numbers = {s: float(v) for s, v in dynamics_defaults(arm).items()}
    args = [*arm.q, *arm.coordinate_rates, *arm.coordinate_accelerations, *numbers]
    point = np.random.default_rng(3).uniform(-2, 2, 3 * arm.n_joints)
    values = [np.array(sp.lambdify(args, sp.Matrix(Y), cse=lambdify_cse)(*point, *numbers.values()), dtype=float)
              for Y in (exact, nested)]
    assert np.abs(values[0]).max() > 1
    assert np.allclose(values[0], values[1], rtol=0, atol=1e-10)


def test_drive_columns_follow_each_link_and_add_armature_friction_and_offset():
    arm = load_robot("planar2r")
    Y = regressor(arm, armature=True, viscous=True, coulomb=True, offset=True)
    assert Y.names[9:15] == ("M1", "Ia1", "Fv1", "Fc1", "Fo1", "XX2")
    t1, t2 = arm.joints
    drive = [s for s in Y.parameters if s.name[:2] in {"Ia", "Fv", "Fc", "Fo"}]
    extra = _torques(Y, dict.fromkeys(drive, 2))
    assert list(extra) == [2 * (t.acceleration + t.rate + sp.sign(t.rate) + 1) for t in (t1, t2)]
    assert Y.matrix[:, [i for i, name in enumerate(Y.names) if name[:2] not in {"Ia", "Fv", "Fc", "Fo"}]] == \
        regressor(arm).matrix
    eps = sp.Symbol("epsilon", positive=True)
    smooth = regressor(arm, coulomb=True, smooth=eps)
    assert smooth.matrix[1, smooth.names.index("Fc2")] == sp.tanh(t2.rate / eps)


def test_a_coupled_robots_drive_terms_are_moved_to_the_coordinates():
    """Joint j's viscous friction Fv_j (C qdot)_j does the work C^T (...) in the coordinates."""
    arm = load_robot("palletizer")
    Y = regressor(arm, viscous=True)
    C = sp.Matrix(arm.coupling.matrix)
    columns = [Y.names.index(f"Fv{j}") for j in range(1, arm.n_joints + 1)]
    rates = C * sp.Matrix(arm.coordinate_rates)
    assert (Y.matrix[:, columns] - C.T * sp.diag(*rates)).applyfunc(sp.expand) == sp.zeros(len(arm.q), arm.n_joints)


def test_no_inertial_data_is_needed_but_standard_values_names_what_is_missing():
    arm = robot_from_mapping({"name": "bare", "convention": "modified",
                              "joints": [{"type": "revolute"}, {"type": "prismatic", "alpha": "pi/2"}]})
    Y = regressor(arm)
    assert Y.matrix[1, Y.names.index("M2")] != 0
    with pytest.raises(NoInertialDataError, match="bare: links 1, 2 have no inertial data"):
        standard_values(arm)


def test_bad_options_and_name_clashes_are_refused():
    arm = load_robot("planar2r")
    with pytest.raises(ArgumentError, match="coulomb=True"):
        regressor(arm, smooth=0.01)
    with pytest.raises(ArgumentError, match="epsilon > 0"):
        regressor(arm, coulomb=True, smooth=-1)
    clashing = load_robot("planar2r")
    clashing = dataclasses.replace(clashing, parameters=(*clashing.parameters,
                                                         dataclasses.replace(clashing.parameters[0], name="M2")))
    with pytest.raises(ArgumentError, match="'M2' has the name of a standard dynamic parameter"):
        regressor(clashing)


# --- against pinocchio ------------------------------------------------------------------------------------------

PINOCCHIO_ARMS = ["ur5", "panda", "talos-left-arm", "xarm7", "so100"]
"""Exact geometry (UR5), lumped off-chain bodies (Panda's fingers, TALOS's gripper) and generic geometry (nested)."""

TURNED = {"ur5", "talos-left-arm", "so100"}
"""The arms where symjac's frame {i} is turned from pinocchio's joint frame (a URDF axis other than z)."""


def _in_frame(pi: np.ndarray, R: np.ndarray, p: np.ndarray) -> np.ndarray:
    """pinocchio's [m, mx, my, mz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz] (about the origin of frame A) as symjac's standard
    parameters in frame B, whose pose in A is (R, p): h_B = R^T (h - m p), I_B = R^T I_p R about B's origin."""
    m, h = pi[0], pi[1:4]
    I_o = np.array([[pi[4], pi[5], pi[7]], [pi[5], pi[6], pi[8]], [pi[7], pi[8], pi[9]]])
    I_p = I_o + m * (p @ p * np.eye(3) - np.outer(p, p)) - 2 * (h @ p) * np.eye(3) + np.outer(h, p) + np.outer(p, h)
    I_B, h_B = R.T @ I_p @ R, R.T @ (h - m * p)
    return np.array([I_B[0, 0], I_B[0, 1], I_B[0, 2], I_B[1, 1], I_B[1, 2], I_B[2, 2], *h_B, m])


@pytest.mark.external
@pytest.mark.parametrize("name", PINOCCHIO_ARMS)
def test_pinocchios_joint_torque_regressor(name):
    from pinocchio_arms import PinocchioArm, close, pin, states

    pair = PinocchioArm(name)
    arm, model, data = pair.robot, pair.model, pair.data
    n = arm.n_joints
    Y = regressor(arm)
    numbers = {s: float(v) for s, v in dynamics_defaults(arm).items()}
    args = [*arm.q, *arm.coordinate_rates, *arm.coordinate_accelerations, *numbers]
    function = sp.lambdify(args, sp.Matrix(Y.matrix), cse=lambdify_cse)
    pi = np.array([float(sp.sympify(standard_values(arm)[p]).xreplace(arm.defaults)) for p in Y.parameters])
    ids = [model.getJointId(joint.name) for joint in arm.joints]
    pi_pin = np.concatenate([model.inertias[i].toDynamicParameters() for i in ids])
    transforms = None
    for q, qd, qdd in states(n, 2):
        Q = pair.configuration(q)
        Y_pin = pin.computeJointTorqueRegressor(model, data, Q, qd, qdd)
        Y_pin = np.hstack([Y_pin[:, 10 * (i - 1):10 * i] for i in ids])
        Y_sym = np.array(function(*q, *qd, *qdd, *numbers.values()), dtype=float)
        tau = pin.rnea(model, data, Q, qd, qdd)
        close(Y_pin @ pi_pin, tau)  # pinocchio's own order and frame, as read here
        close(Y_sym @ pi, tau)
        # the pose of symjac's frame {i} in pinocchio's joint frame: constant, whatever q is
        world = frames(arm, q)
        pin.forwardKinematics(model, data, Q)
        poses = [data.oMi[i].inverse().homogeneous @ np.linalg.inv(world[1]) @ world[k + 1]
                 for k, i in enumerate(ids, start=1)]
        if transforms is not None:
            assert max(np.abs(a - b).max() for a, b in zip(poses, transforms, strict=True)) < 1e-9
        transforms = poses
        # column by column: each pinocchio parameter, written in symjac's frame, gives pinocchio's column
        T = np.zeros((10 * n, 10 * n))
        for k, X in enumerate(poses):
            for c in range(10):
                T[10 * k:10 * k + 10, 10 * k + c] = _in_frame(np.eye(10)[c], X[:3, :3], X[:3, 3])
        close(Y_sym @ T, Y_pin)
    turned = any(np.abs(X[:3, :3] - np.eye(3)).max() > 0.5 for X in transforms)
    assert turned == (name in TURNED)  # where the frames differ, the transformation is checked too

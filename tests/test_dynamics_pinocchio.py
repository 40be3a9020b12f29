"""Dynamics against pinocchio on real arms with their published inertial data (example-robot-data's URDFs).

pinocchio (PyPI ``pin``) reads the same file: ``rnea`` (inverse dynamics), ``crba`` (mass matrix),
``computeGeneralizedGravity``, ``computeCoriolisMatrix`` and ``aba`` (forward dynamics) at random (q, qd, qdd), with
its default gravity (9.81 m/s^2 along -z of the root link, which is symjac's frame {0} for these files). symjac's
results are derived once symbolically, then evaluated with the inertial numbers of the file and g = 9.81, to 1e-10
relative to the largest entry (the raw torques of a 7-joint arm are a sum of about 150 000 operations); its forward
dynamics is a solve with its own M, qdd = M^-1 (tau - C qd - g). M, C and g are the compact forms;
the torques and the Newton-Euler mass matrix are the raw products (``simplify=False``: laid out, the UR5's torques take
about 30 s; the compact forms are checked exactly on smaller arms in test_dynamics_textbook). Arms with generic
geometry (xArm7, SO-100) come as nested results, compiled through their intermediates.

The arms are the UR5 and the Panda, and the six arms of six makers whose Jacobians test_robot_collection compares.
Joints off the chain (the Panda's fingers, the grippers of TALOS's arm and of the Z1) are held at zero by symjac,
which lumps their bodies into the chain link that carries them (parallel-axis theorem); pinocchio's model is reduced
the same way (``buildReducedModel``, those joints locked at zero), so that its forward dynamics is that of the same
rigid arm.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from pinocchio_arms import ARMS, FOLDER, PinocchioArm, close, pin, states

from symjac.analysis.dynamics import (
    coriolis_matrix,
    dynamics_defaults,
    gravity_torques,
    mass_matrix,
    newton_euler,
    newton_euler_mass_matrix,
)
from symjac.symbolic.nested import lambdify_cse

pytestmark = pytest.mark.external


class Pair(PinocchioArm):
    """One arm read by both libraries, and symjac's results compiled to numeric functions of (q, qd, qdd)."""

    def __init__(self, name: str):
        super().__init__(name)
        arm = self.robot
        numbers = {s: float(v) for s, v in dynamics_defaults(arm).items()}
        args = [*arm.q, *arm.coordinate_rates, *arm.coordinate_accelerations, *numbers]

        def compiled(matrix: sp.MatrixBase):
            function = sp.lambdify(args, sp.Matrix(matrix), cse=lambdify_cse)
            return lambda *x: np.array(function(*x, *numbers.values()), dtype=float)

        self.tau = compiled(newton_euler(arm, simplify=False).torques)
        self.M = compiled(mass_matrix(arm))
        self.M_ne = compiled(newton_euler_mass_matrix(arm, simplify=False))
        self.g = compiled(gravity_torques(arm))
        self.C = compiled(coriolis_matrix(arm))


@pytest.fixture(scope="module", params=sorted(ARMS))
def pair(request) -> Pair:
    return Pair(request.param)


LOCKED = {"panda": ["panda_finger_joint1", "panda_finger_joint2"],  # the joints off the chain, held at zero
          "talos-left-arm": ["gripper_left_joint"], "z1": ["jointGripper"]}


def test_the_off_chain_joints_are_locked_and_their_bodies_count(pair):
    """pinocchio without the locked bodies' inertia is another arm: lumping them is what the comparison checks."""
    name = pair.name
    assert pair.locked == LOCKED.get(name, [])
    if not pair.locked:
        return
    path, _ = ARMS[name]
    bare = pin.buildModelFromUrdf(str(FOLDER / path))
    for joint in pair.locked:
        bare.inertias[bare.getJointId(joint)] = pin.Inertia.Zero()
    ids = [bare.getJointId(joint.name) for joint in pair.robot.joints]
    bare = pin.buildReducedModel(bare, [i for i in range(1, bare.njoints) if i not in ids], pin.neutral(bare))
    q, _, _ = states(pair.robot.n_joints, 1)[0]
    g = pin.computeGeneralizedGravity(pair.model, pair.data, pair.configuration(q))
    assert np.abs(pin.computeGeneralizedGravity(bare, bare.createData(), pair.configuration(q)) - g).max() > 1e-3


def test_inverse_dynamics_mass_matrix_gravity_coriolis_and_forward_dynamics_equal_pinocchios(pair):
    model, data = pair.model, pair.data
    for q, qd, qdd in states(pair.robot.n_joints):
        args = (*q, *qd, *qdd)
        Q = pair.configuration(q)
        tau = pin.rnea(model, data, Q, qd, qdd)
        M = pin.crba(model, data, Q)
        M = np.triu(M) + np.triu(M, 1).T
        g = pin.computeGeneralizedGravity(model, data, Q)
        C = pin.computeCoriolisMatrix(model, data, Q, qd)
        close(pair.tau(*args).ravel(), tau)
        close(pair.M(*args), M)
        close(pair.M_ne(*args), M)
        close(pair.g(*args).ravel(), g)
        close(pair.C(*args) @ qd, C @ qd)
        close(pair.C(*args), C)  # both the Christoffel form
        assert np.abs(tau).max() > 0.1  # real torques: the comparison can fail
        # forward dynamics: symjac's M solved against the torques, pinocchio's articulated-body algorithm
        torques = np.random.default_rng(7).uniform(-1, 1, len(q)) * np.abs(g).max()
        solved = np.linalg.solve(pair.M(*args), torques - pair.C(*args) @ qd - pair.g(*args).ravel())
        close(solved, pin.aba(model, data, Q, qd, torques), 1e-9)
        close(np.linalg.solve(pair.M(*args), pair.tau(*args).ravel() - pair.tau(*q, *qd, *0 * qdd).ravel()), qdd,
              1e-9)


def test_mdot_minus_twice_c_is_skew_and_the_routes_add_up(pair):
    n = pair.robot.n_joints
    h = 1e-6
    for q, qd, qdd in states(n, 2):
        args = (*q, *qd, *qdd)
        M_dot = (pair.M(*(q + h * qd), *qd, *qdd) - pair.M(*(q - h * qd), *qd, *qdd)) / (2 * h)
        N = M_dot - 2 * pair.C(*args)
        close(N, -N.T, 1e-7)
        total = pair.M(*args) @ qdd + pair.C(*args) @ qd + pair.g(*args).ravel()
        close(pair.tau(*args).ravel(), total)
        assert np.all(np.linalg.eigvalsh(pair.M(*args)) > 0)


def test_gravity_compensation_three_ways(pair):
    """g(q) is what pinocchio's rnea needs to hold the arm still, and the static route -sum J_ci^T m_i g0."""
    from symjac.kinematics.jacobian import jacobian

    arm = pair.robot
    numbers = {s: float(v) for s, v in dynamics_defaults(arm).items()}
    static = sp.zeros(arm.n_joints, 1)
    for i, body in enumerate(arm.inertials, start=1):
        J_v = jacobian(arm, 0, point=body.com, link=i, simplify=False)[:3, :]
        static -= J_v.T * body.mass * sp.Matrix([0, 0, -sp.Symbol("g", positive=True)])
    static = sp.lambdify([*arm.q, *numbers], static, cse=lambdify_cse)
    zero = np.zeros(arm.n_joints)
    for q, _, _ in states(arm.n_joints, 2):
        held = pin.rnea(pair.model, pair.data, pair.configuration(q), zero, zero)
        close(pair.g(*q, *zero, *zero).ravel(), held)
        close(np.array(static(*q, *numbers.values()), dtype=float).ravel(), held)

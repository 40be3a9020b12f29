"""Dynamics against pinocchio on real arms with their published inertial data (example-robot-data's URDFs).

pinocchio (PyPI ``pin``) reads the same file: ``rnea`` (inverse dynamics), ``crba`` (mass matrix),
``computeGeneralizedGravity`` and ``computeCoriolisMatrix`` at random (q, qd, qdd), with its default gravity
(9.81 m/s^2 along -z of the root link, which is symjac's frame {0} for these files). symjac's results are derived
once symbolically, then evaluated with the inertial numbers of the file and g = 9.81, to 1e-10 relative to the
largest entry (the raw torques of a 6-joint arm are a sum of about 150 000 operations). M, C and g are the compact
forms; the torques and the Newton-Euler mass matrix are the raw products (``simplify=False``: laid out, the UR5's
torques take about 30 s; the compact forms are checked exactly on smaller arms in test_dynamics_textbook).

The Panda's fingers hang from prismatic joints off the chain: symjac holds them at zero and lumps their bodies into
link 7 with the hand (fixed to link 8); pinocchio keeps them as joints of their own, here at rest at zero, which is
the same load on the arm.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from collection import example_robots

from symjac.analysis.dynamics import (
    coriolis_matrix,
    dynamics_defaults,
    gravity_torques,
    mass_matrix,
    newton_euler,
    newton_euler_mass_matrix,
)
from symjac.model.io import load_robot

pytestmark = pytest.mark.external
pin = pytest.importorskip("pinocchio", reason="pinocchio is not installed (pip install pin, or the [compare] extra)")


FOLDER = example_robots()

ARMS = {  # name: (file, tip link)
    "ur5": ("ur_description/urdf/ur5_robot.urdf", "tool0"),
    "panda": ("panda_description/urdf/panda.urdf", "panda_link8"),
}


class Pair:
    """One arm read by both libraries, and symjac's results compiled to numeric functions of (q, qd, qdd)."""

    def __init__(self, name: str):
        path, tip = ARMS[name]
        self.robot = load_robot(str(FOLDER / path), tip_link=tip)
        self.model = pin.buildModelFromUrdf(str(FOLDER / path))
        self.data = self.model.createData()
        ids = [self.model.getJointId(joint.name) for joint in self.robot.joints]
        self.index = [self.model.joints[i].idx_q for i in ids]
        arm = self.robot
        args = [*arm.q, *arm.coordinate_rates, *arm.coordinate_accelerations]
        numbers = {s: sp.Float(v, 30) for s, v in dynamics_defaults(arm).items()}

        def compiled(matrix: sp.MatrixBase):
            return sp.lambdify(args, sp.Matrix(matrix).xreplace(numbers), cse=True)

        self.tau = compiled(newton_euler(arm, simplify=False).torques)
        self.M = compiled(mass_matrix(arm))
        self.M_ne = compiled(newton_euler_mass_matrix(arm, simplify=False))
        self.g = compiled(gravity_torques(arm))
        self.C = compiled(coriolis_matrix(arm))

    def full(self, x: np.ndarray) -> np.ndarray:
        """A vector of the chain's joints placed in pinocchio's (joints off the chain at zero)."""
        out = np.zeros(self.model.nv)
        out[self.index] = x
        return out

    def chain(self, X: np.ndarray) -> np.ndarray:
        """pinocchio's vector or matrix restricted to the chain's joints."""
        return X[np.ix_(self.index, self.index)] if X.ndim == 2 else X[self.index]


@pytest.fixture(scope="module", params=sorted(ARMS))
def pair(request) -> Pair:
    return Pair(request.param)


def _states(n: int, count: int = 5):
    rng = np.random.default_rng(44)
    return [tuple(rng.uniform(-2, 2, n) for _ in range(3)) for _ in range(count)]


def _close(got: np.ndarray, expected: np.ndarray, tolerance: float = 1e-10) -> None:
    scale = max(1.0, float(np.abs(expected).max()))
    assert np.abs(got - expected).max() <= tolerance * scale, np.abs(got - expected).max()


def test_inverse_dynamics_mass_matrix_gravity_and_coriolis_equal_pinocchios(pair):
    n = pair.robot.n_joints
    for q, qd, qdd in _states(n):
        args = (*q, *qd, *qdd)
        Q, V, A = pair.full(q), pair.full(qd), pair.full(qdd)
        tau = pair.chain(pin.rnea(pair.model, pair.data, Q, V, A))
        M = pin.crba(pair.model, pair.data, Q)
        M = pair.chain(np.triu(M) + np.triu(M, 1).T)
        g = pair.chain(pin.computeGeneralizedGravity(pair.model, pair.data, Q))
        C = pair.chain(pin.computeCoriolisMatrix(pair.model, pair.data, Q, V))
        _close(pair.tau(*args).ravel(), tau)
        _close(pair.M(*args), M)
        _close(pair.M_ne(*args), M)
        _close(pair.g(*args).ravel(), g)
        _close(pair.C(*args) @ qd, C @ qd)
        _close(pair.C(*args), C)  # both the Christoffel form
        assert np.abs(tau).max() > 1  # real torques: the comparison can fail


def test_mdot_minus_twice_c_is_skew_and_the_routes_add_up(pair):
    n = pair.robot.n_joints
    h = 1e-6
    for q, qd, qdd in _states(n, 3):
        args = (*q, *qd, *qdd)
        M_dot = (pair.M(*(q + h * qd), *qd, *qdd) - pair.M(*(q - h * qd), *qd, *qdd)) / (2 * h)
        N = M_dot - 2 * pair.C(*args)
        _close(N, -N.T, 1e-7)
        total = pair.M(*args) @ qdd + pair.C(*args) @ qd + pair.g(*args).ravel()
        _close(pair.tau(*args).ravel(), total)
        assert np.all(np.linalg.eigvalsh(pair.M(*args)) > 0)


def test_gravity_compensation_three_ways(pair):
    """g(q) is what pinocchio's rnea needs to hold the arm still, and the static route -sum J_ci^T m_i g0."""
    from symjac.kinematics.jacobian import jacobian

    arm = pair.robot
    numbers = {s: sp.Float(v, 30) for s, v in dynamics_defaults(arm).items()}
    static = sp.zeros(arm.n_joints, 1)
    for i, body in enumerate(arm.inertials, start=1):
        J_v = jacobian(arm, 0, point=body.com, link=i, simplify=False)[:3, :]
        static -= J_v.T * body.mass * sp.Matrix([0, 0, -sp.Symbol("g", positive=True)])
    static = sp.lambdify(arm.q, static.xreplace(numbers))
    zero = np.zeros(arm.n_joints)
    for q, _, _ in _states(arm.n_joints, 3):
        held = pair.chain(pin.rnea(pair.model, pair.data, pair.full(q), pair.full(zero), pair.full(zero)))
        _close(pair.g(*q, *zero, *zero).ravel(), held)
        _close(np.array(static(*q), dtype=float).ravel(), held)

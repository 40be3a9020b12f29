"""Dynamics of random chains against two independent numeric references, and the symbolic routes against each other.

Exact to 1e-9: random chains of every convention (standard and modified DH, general, product of exponentials), with
prismatic joints and coupled joints, against the numeric Newton-Euler of ``reference_dynamics`` (spatial vectors in
frame {0}, nothing of symjac's dynamics): tau, M, C qd and g. Properties under hypothesis: M symmetric positive
definite, Mdot - 2C skew-symmetric, and without gravity d/dt(1/2 qd^T M qd) = qd^T tau along random trajectories.

The reference uses nothing of symjac but the robot's data: frame poses from ``reference.frames`` (plain NumPy), the
Jacobians of the link centres and the angular velocities by central differences, M = sum m J_v^T J_v + J_w^T R I R^T
J_w, g = dV/dq by central differences of V = sum m g z_c, and tau = M qdd + Mdot qd - 1/2 d(qd^T M qd)/dq + g with
the derivatives of M again by central differences (hence the 1e-5 tolerance). symjac's routes (Newton-Euler torques
and mass matrix, M from the link Jacobians, C from the Christoffel symbols, g from V) must agree with each other to
1e-9 and Mdot - 2C be skew-symmetric. The inertial data are random but physical: each link is a cloud of point masses.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from marks import marked
from reference import frames
from reference_dynamics import NumericDynamics
from strategies import general_robots, robots

from symjac import robot_from_mapping
from symjac.analysis.dynamics import (
    coriolis_matrix,
    dynamics_defaults,
    gravity_torques,
    mass_matrix,
    newton_euler,
    newton_euler_mass_matrix,
)
from symjac.model.inertia import Inertial, combined_inertial
from symjac.model.io import catalog
from symjac.symbolic.nested import lambdify_cse

G = 9.81


def _cloud(rng: np.random.Generator) -> Inertial:
    """A rigid body made of three point masses at rational points: always physically possible."""
    parts = [Inertial(sp.Rational(int(rng.integers(1, 9)), 4),
                      tuple(sp.Rational(int(v), 10) for v in rng.integers(-3, 4, 3))) for _ in range(3)]
    return combined_inertial(parts)


def _with_bodies(robot, seed: int):
    rng = np.random.default_rng(seed)
    return dataclasses.replace(robot, inertials=tuple(_cloud(rng) for _ in robot.joints))


def _compiled(robot, matrix: sp.MatrixBase):
    numbers = {s: float(v) for s, v in dynamics_defaults(robot).items()}
    args = [*robot.q, *robot.coordinate_rates, *robot.coordinate_accelerations, *numbers]
    function = sp.lambdify(args, sp.Matrix(matrix), cse=lambdify_cse)
    return lambda q, qd, qdd: np.array(function(*q, *qd, *qdd, *numbers.values()), dtype=float)


class Reference:
    """The numeric Lagrangian of the module docstring, from the robot's data alone."""

    def __init__(self, robot, h: float = 1e-5):
        self.robot, self.h = robot, h
        self.bodies = [(float(b.mass), np.array(b.com, dtype=float), np.array(b.inertia, dtype=float))
                       for b in robot.inertials]

    def _poses(self, q: np.ndarray) -> list[np.ndarray]:
        world = frames(self.robot, q)
        base_inverse = np.linalg.inv(world[1])
        return [base_inverse @ world[k + 1] for k in range(1, self.robot.n_joints + 1)]

    def _centres(self, q):
        poses = zip(self._poses(q), self.bodies, strict=True)
        return [(T[:3, :3], T[:3, :3] @ c + T[:3, 3]) for T, (_, c, _) in poses]

    def M(self, q: np.ndarray) -> np.ndarray:
        n, h = len(q), self.h
        plus, minus = [], []
        for j in range(n):
            step = np.zeros(n)
            step[j] = h
            plus.append(self._centres(q + step))
            minus.append(self._centres(q - step))
        M = np.zeros((n, n))
        for i, ((R, _), (m, _, inertia)) in enumerate(zip(self._centres(q), self.bodies, strict=True)):
            J_v = np.array([(plus[j][i][1] - minus[j][i][1]) / (2 * h) for j in range(n)]).T
            spins = [(plus[j][i][0] - minus[j][i][0]) / (2 * h) @ R.T for j in range(n)]
            J_w = np.array([(w[2, 1], w[0, 2], w[1, 0]) for w in spins]).T
            M += m * J_v.T @ J_v + J_w.T @ R @ inertia @ R.T @ J_w
        return M

    def V(self, q: np.ndarray) -> float:
        return sum(m * G * p[2] for (m, _, _), (_, p) in zip(self.bodies, self._centres(q), strict=True))

    def tau(self, q, qd, qdd, h: float = 1e-4) -> np.ndarray:
        n = len(q)
        M_dot = (self.M(q + h * qd) - self.M(q - h * qd)) / (2 * h)
        gradient, g = np.zeros(n), np.zeros(n)
        for k in range(n):
            step = np.zeros(n)
            step[k] = h
            gradient[k] = (qd @ self.M(q + step) @ qd - qd @ self.M(q - step) @ qd) / (2 * h)
            g[k] = (self.V(q + step) - self.V(q - step)) / (2 * h)
        return self.M(q) @ qdd + M_dot @ qd - gradient / 2 + g


def _close(got, expected, tolerance):
    scale = max(1.0, float(np.abs(expected).max()))
    assert np.abs(np.asarray(got) - expected).max() <= tolerance * scale


@settings(max_examples=15, deadline=None)
@given(robot=robots(max_joints=5), seed=st.integers(0, 2**16))
def test_random_chains_three_routes_and_a_numeric_lagrangian(robot, seed):
    _check(_with_bodies(robot, seed), seed)


REVOLUTE_CHAINS = {  # the random draws are mostly prismatic-heavy: arms of revolute joints, generic twists too
    "standard-5r-generic": ("standard", [("revolute", 0.3, 0.2, 0.1), ("revolute", "pi/2", 0.4, 0),
                                         ("revolute", 0, 0.3, 0.05), ("revolute", "-pi/3", 0, 0.2),
                                         ("revolute", "pi/2", 0.1, 0)]),
    "modified-6r-puma-like": ("modified", [("revolute", 0, 0, 0), ("revolute", "-pi/2", 0, 0.2),
                                           ("revolute", 0, 0.43, -0.09), ("revolute", "-pi/2", 0.02, 0.43),
                                           ("revolute", "pi/2", 0, 0), ("revolute", "-pi/2", 0, 0)]),
    "standard-rrprr": ("standard", [("revolute", "pi/2", 0.1, 0.3), ("revolute", 0, 0.25, 0),
                                    ("prismatic", "pi/2", 0, 0.1), ("revolute", "-pi/2", 0, 0.2),
                                    ("revolute", 0, 0.05, 0)]),
}


@pytest.mark.parametrize("name", sorted(REVOLUTE_CHAINS))
def test_revolute_chains_three_routes_and_a_numeric_lagrangian(name):
    from symjac import robot_from_mapping

    convention, rows = REVOLUTE_CHAINS[name]
    joints = [{"type": kind, "alpha": alpha, "a": a, "d": d} for kind, alpha, a, d in rows]
    robot = robot_from_mapping({"name": name.replace("-", "_"), "convention": convention, "joints": joints})
    _check(_with_bodies(robot, 44), 44)


def _check(arm, seed: int) -> None:
    n = arm.n_joints
    tau = _compiled(arm, newton_euler(arm, simplify=False).torques)
    M_ne = _compiled(arm, newton_euler_mass_matrix(arm, simplify=False))
    M, C, g = (_compiled(arm, x) for x in (mass_matrix(arm), coriolis_matrix(arm), gravity_torques(arm)))
    reference = Reference(arm)
    rng = np.random.default_rng(seed)
    zero = np.zeros(n)
    for _ in range(2):
        q, qd, qdd = (rng.uniform(-1.5, 1.5, n) for _ in range(3))
        got = tau(q, qd, qdd).ravel()
        _close(got, reference.tau(q, qd, qdd), 1e-5)
        _close(got, M(q, qd, qdd) @ qdd + C(q, qd, qdd) @ qd + g(q, qd, qdd).ravel(), 1e-9)
        _close(M_ne(q, qd, qdd), M(q, qd, qdd), 1e-9)
        _close(M(q, zero, zero), reference.M(q), 1e-7)
        _close(g(q, qd, qdd).ravel(), tau(q, zero, zero).ravel(), 1e-9)
        h = 1e-6
        M_dot = (M(q + h * qd, qd, qdd) - M(q - h * qd, qd, qdd)) / (2 * h)
        N = M_dot - 2 * C(q, qd, qdd)
        _close(N, -N.T, 1e-6)
        assert np.linalg.eigvalsh(M(q, zero, zero)).min() > 0


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_the_reference_can_fail(convention):
    """A wrong mass (the last link doubled) is caught: the reference sees the arm's own data."""
    from symjac import robot_from_mapping

    arm = _with_bodies(robot_from_mapping({"name": "arm", "convention": convention, "joints": [
        {"type": "revolute", "alpha": "pi/2", "a": 0.3}, {"type": "prismatic", "alpha": 0, "a": 0.2, "theta": 0.4},
        {"type": "revolute", "alpha": 0, "a": 0.1}]}), 7)
    heavier = dataclasses.replace(arm, inertials=(*arm.inertials[:-1], dataclasses.replace(
        arm.inertials[-1], mass=2 * arm.inertials[-1].mass)))
    q, qd, qdd = np.array([0.3, 0.2, -0.4]), np.array([0.5, -0.1, 0.7]), np.array([-0.2, 0.3, 0.1])
    expected = Reference(arm).tau(q, qd, qdd)
    _close(_compiled(arm, newton_euler(arm).torques)(q, qd, qdd).ravel(), expected, 1e-5)
    wrong = _compiled(heavier, newton_euler(heavier).torques)(q, qd, qdd).ravel()
    assert np.abs(wrong - expected).max() > 1e-2


# ------------------------------------------------------------------ every convention, prismatic and coupled joints


class Numeric:
    """symjac's tau (Newton-Euler), M, C and g of ``arm``, compiled once to functions of (q, qd, qdd)."""

    def __init__(self, arm):
        self.tau = _compiled(arm, newton_euler(arm, simplify=False).torques)
        self.M, self.C, self.g = (_compiled(arm, x) for x in (mass_matrix(arm), coriolis_matrix(arm),
                                                              gravity_torques(arm)))


def _exact(arm, seed: int, states: int = 2) -> Numeric:
    """tau, M, C qd and g equal the numeric Newton-Euler's to 1e-9; M is symmetric positive definite."""
    ours, theirs = Numeric(arm), NumericDynamics(arm)
    rng = np.random.default_rng(seed)
    n = arm.n_coordinates
    for _ in range(states):
        q, qd, qdd = (rng.uniform(-1.5, 1.5, n) for _ in range(3))
        M = ours.M(q, qd, qdd)
        _close(ours.tau(q, qd, qdd).ravel(), theirs.tau(q, qd, qdd), 1e-9)
        _close(M, theirs.M(q), 1e-9)
        _close(ours.C(q, qd, qdd) @ qd, theirs.C_qd(q, qd), 1e-9)
        _close(ours.g(q, qd, qdd).ravel(), theirs.g(q), 1e-9)
        _close(M, M.T, 1e-12)
        assert np.linalg.eigvalsh(M).min() > 0
    return ours


@settings(max_examples=8, deadline=None, derandomize=True)
@given(robot=robots(max_joints=4), seed=st.integers(0, 2**16))
def test_random_dh_chains_equal_a_numeric_newton_euler(robot, seed):
    _exact(_with_bodies(robot, seed), seed)


@settings(max_examples=6, deadline=None, derandomize=True)
@given(robot=general_robots(max_joints=3), seed=st.integers(0, 2**16))
def test_random_general_chains_equal_a_numeric_newton_euler(robot, seed):
    _exact(_with_bodies(robot, seed), seed)


@st.composite
def coupled_chains(draw: st.DrawFn):
    """A 3-4 joint DH chain with one or two joints coupled affinely to free ones before them (prismatic ones too)."""
    n = draw(st.integers(3, 4))
    joints = [{"type": draw(st.sampled_from(["revolute", "revolute", "prismatic"])),
               "alpha": draw(st.sampled_from([0, "pi/2", "-pi/2", 0.4])), "a": draw(st.sampled_from([0, 0.3, 0.2])),
               "d": draw(st.sampled_from([0, 0.1]))} for _ in range(n)]
    for k in sorted(draw(st.lists(st.integers(1, n - 1), min_size=1, max_size=2, unique=True))):
        leader = draw(st.integers(0, k - 1))
        if "coupled" in joints[leader]:
            continue
        variable = ("theta" if joints[leader]["type"] == "revolute" else "d") + str(leader + 1)
        joints[k]["coupled"] = f"{draw(st.sampled_from([-1, 2, 0.5]))}*{variable} + {draw(st.sampled_from([0, 0.3]))}"
        if joints[k]["type"] == "prismatic":
            joints[k].pop("d")
    convention = draw(st.sampled_from(["standard", "modified"]))
    return robot_from_mapping({"name": "coupled", "convention": convention, "joints": joints})


@settings(max_examples=6, deadline=None, derandomize=True)
@given(robot=coupled_chains(), seed=st.integers(0, 2**16))
def test_random_coupled_chains_equal_a_numeric_newton_euler(robot, seed):
    arm = _with_bodies(robot, seed)
    assert arm.n_coordinates < arm.n_joints
    _exact(arm, seed)


POE = {"name": "poe3", "convention": "poe", "home": {"matrix": [[1, 0, 0, 0.6], [0, 1, 0, 0], [0, 0, 1, 0.2],
                                                                 [0, 0, 0, 1]]},
       "joints": [{"type": "revolute", "screw": [0, 0, 1, 0, 0, 0]},
                  {"type": "revolute", "screw": [0, 1, 0, -0.2, 0, 0.1]},
                  {"type": "prismatic", "screw": [0, 0, 0, 0.6, 0, 0.8]}]}


def test_a_product_of_exponentials_chain_equals_a_numeric_newton_euler():
    _exact(_with_bodies(robot_from_mapping(POE), 3), 3)


def test_the_numeric_newton_euler_can_fail():
    """A body moved by a quarter turn in its link frame changes the torques: the reference reads the frames."""
    arm = _with_bodies(robot_from_mapping(POE), 3)
    turned = dataclasses.replace(arm, inertials=(*arm.inertials[:-1], arm.inertials[-1].expressed_in(
        sp.Matrix([[0, -1, 0, 0], [1, 0, 0, 0.1], [0, 0, 1, 0], [0, 0, 0, 1]]))))
    q, qd, qdd = np.array([0.3, -0.2, 0.4]), np.array([0.5, 0.1, -0.7]), np.array([0.2, -0.3, 0.1])
    assert np.abs(NumericDynamics(turned).tau(q, qd, qdd) - Numeric(arm).tau(q, qd, qdd).ravel()).max() > 1e-3


@settings(max_examples=6, deadline=None, derandomize=True)
@given(robot=robots(max_joints=3), seed=st.integers(0, 2**16))
def test_kinetic_energy_changes_by_the_power_of_the_torques_without_gravity(robot, seed):
    """Along q(t) = q0 + v t + a t^2/2: d/dt(1/2 qd^T M qd) = qd^T (tau - g) at t = 0 (central differences)."""
    arm = _with_bodies(robot, seed)
    ours = Numeric(arm)
    rng = np.random.default_rng(seed)
    n = arm.n_joints
    q0, v, a = (rng.uniform(-1.5, 1.5, n) for _ in range(3))

    def energy(t: float) -> float:
        q, qd = q0 + v * t + a * t**2 / 2, v + a * t
        return float(qd @ ours.M(q, qd, a) @ qd) / 2

    h = 1e-4
    rate = (energy(h) - energy(-h)) / (2 * h)
    power = float(v @ (ours.tau(q0, v, a).ravel() - ours.g(q0, v, a).ravel()))
    assert abs(rate - power) <= 1e-6 * max(1.0, abs(power))
    h_dot = 1e-6  # and Mdot - 2C is skew-symmetric
    N = (ours.M(q0 + h_dot * v, v, a) - ours.M(q0 - h_dot * v, v, a)) / (2 * h_dot) - 2 * ours.C(q0, v, a)
    _close(N, -N.T, 1e-6)


@pytest.mark.parametrize("name", marked(sorted(catalog()), keep=["puma560"]))  # the PUMA: published data, fast
def test_every_catalog_robot_runs_the_dynamics_with_symbolic_inertial_parameters(name):
    """m1, cx1, .., Izz_n as parameters (the published numbers as defaults where the file has them): the torques at
    those defaults equal the numeric Newton-Euler's."""
    from symjac import load_robot
    from symjac.model.inertial_parameters import with_symbolic_inertials

    robot = load_robot(name)
    arm = with_symbolic_inertials(robot)
    assert all(str(inertial.mass) == f"m{k}" for k, inertial in enumerate(arm.inertials, start=1))
    tau = _compiled(arm, newton_euler(arm, simplify=False).torques)
    rng = np.random.default_rng(len(name))
    q, qd, qdd = (rng.uniform(-1.5, 1.5, arm.n_coordinates) for _ in range(3))
    _close(tau(q, qd, qdd).ravel(), NumericDynamics(arm).tau(q, qd, qdd), 1e-9)
    if any(robot.inertials):  # the published data: the same torques from the file's own numbers
        _close(tau(q, qd, qdd).ravel(), NumericDynamics(robot).tau(q, qd, qdd), 1e-9)


@pytest.mark.parametrize("name", ["puma560", "panda"])
@pytest.mark.parametrize("to", ["standard", "poe"])
def test_converting_published_inertial_data_keeps_the_dynamics(name, to):
    """symjac convert moves each body with its link's frame: the numeric Newton-Euler sees the same arm."""
    from symjac import load_robot
    from symjac.kinematics.convert import convert

    arm = load_robot(name)
    other = convert(arm, to)
    assert other.convention == to and any(other.inertials)
    rng = np.random.default_rng(44)
    for _ in range(2):
        q, qd, qdd = (rng.uniform(-2, 2, arm.n_joints) for _ in range(3))
        _close(NumericDynamics(other).tau(q, qd, qdd), NumericDynamics(arm).tau(q, qd, qdd), 1e-12)

"""The lowered dynamics (symjac.codegen.dynamics) evaluated numerically, against symjac's symbolic dynamics and an
independent numeric Newton-Euler (tests/spatial_reference.py), for every strategy.

Each LoweredFunction is evaluated as generated code would run it: sines and cosines of its angles, then its
temporaries in order, then its outputs. The arms: the planar 2R with symbolic inertial parameters (their defaults as
numbers), the PUMA 560 with random physical inertial data, a random chain with a prismatic joint, and a coupled arm.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp
from spatial_reference import inverse_dynamics, mass_matrix

from symjac import load_robot, robot_from_mapping
from symjac.analysis.dynamics import dynamics_defaults, newton_euler
from symjac.codegen.dynamics import (
    lowered_bias_forces,
    lowered_coriolis_matrix,
    lowered_gravity_torques,
    lowered_inverse_dynamics,
    lowered_mass_matrix,
)
from symjac.codegen.lower import LoweredFunction
from symjac.model.inertia import Inertial, combined_inertial
from symjac.model.inertial_parameters import with_symbolic_inertials


def evaluate(lowered: LoweredFunction, robot, **inputs: np.ndarray) -> np.ndarray:
    """Run ``lowered`` at the given inputs (``q``, ``qdot``, ``qddot``) with the robot's default parameters."""
    env: dict[sp.Symbol, float] = {s: float(v) for s, v in dynamics_defaults(robot).items()}
    for name, symbols in lowered.inputs:
        env.update(zip(symbols, (float(v) for v in inputs[name]), strict=True))
    for sine, cosine, angle in lowered.angles:
        x = float(angle.xreplace(env))
        env[sine], env[cosine] = np.sin(x), np.cos(x)
    for symbol, expr in lowered.temporaries:
        env[symbol] = float(expr.xreplace(env))
    return np.array([float(e.xreplace(env)) for e in lowered.outputs]).reshape(lowered.shape)


def _cloud(rng: np.random.Generator) -> Inertial:
    """Three point masses at rational points: a physically possible body."""
    return combined_inertial([Inertial(sp.Rational(int(rng.integers(1, 9)), 4),
                                       tuple(sp.Rational(int(v), 10) for v in rng.integers(-3, 4, 3)))
                              for _ in range(3)])


def _with_bodies(robot, seed: int):
    rng = np.random.default_rng(seed)
    return dataclasses.replace(robot, inertials=tuple(_cloud(rng) for _ in robot.joints))


def _arms():
    planar = with_symbolic_inertials(load_robot("planar2r"))
    prismatic = _with_bodies(robot_from_mapping({"name": "rrpr", "convention": "standard", "joints": [
        {"type": "revolute", "alpha": "pi/2", "a": 0.1, "d": 0.3}, {"type": "revolute", "alpha": 0, "a": 0.25},
        {"type": "prismatic", "alpha": "pi/2", "a": 0, "theta": 0.1}, {"type": "revolute", "alpha": "-pi/3",
                                                                        "a": 0.05, "d": 0.2}]}), 3)
    data = {"name": "coupled", "convention": "modified", "joints": [
        {"type": "revolute", "alpha": 0, "d": 0.4}, {"type": "revolute", "alpha": "-pi/2", "a": 0.1},
        {"type": "revolute", "alpha": 0, "a": 0.5}, {"type": "revolute", "alpha": 0, "a": 0.4,
                                                     "coupled": "-(theta2 + theta3)"}]}
    rigid_puma = dataclasses.replace(load_robot("puma560"), drives=())  # its motors' friction: test_drives
    return {"planar2r": planar, "puma560": _with_bodies(rigid_puma, 44), "rrpr": prismatic,
            "coupled": _with_bodies(robot_from_mapping(data), 5)}


ARMS = _arms()
CASES = [(name, "fastest") for name in sorted(ARMS)] + [("planar2r", "raw"), ("coupled", "raw")]
"""The raw strategy (the symbolic recursion lowered) on small arms: its Christoffel symbols take minutes on the PUMA."""


def _states(robot, count: int = 2):
    rng = np.random.default_rng(7)
    n = robot.n_coordinates
    return [tuple(rng.uniform(-1.5, 1.5, n) for _ in range(3)) for _ in range(count)]


def _close(got, expected, tolerance=1e-9):
    scale = max(1.0, float(np.abs(expected).max()))
    assert np.abs(np.asarray(got) - expected).max() <= tolerance * scale, np.abs(np.asarray(got) - expected).max()


@pytest.mark.parametrize(("name", "strategy"), CASES)
def test_lowered_dynamics_equal_an_independent_newton_euler(name, strategy):
    arm = ARMS[name]
    tau = lowered_inverse_dynamics(arm, strategy)
    M, C = lowered_mass_matrix(arm, strategy), lowered_coriolis_matrix(arm, strategy)
    b, g = lowered_bias_forces(arm, strategy), lowered_gravity_torques(arm, strategy)
    zero = np.zeros(arm.n_coordinates)
    for q, qd, qdd in _states(arm):
        expected_g = inverse_dynamics(arm, q, zero, zero)
        _close(evaluate(tau, arm, q=q, qdot=qd, qddot=qdd), inverse_dynamics(arm, q, qd, qdd))
        _close(evaluate(M, arm, q=q), mass_matrix(arm, q))
        _close(evaluate(g, arm, q=q), expected_g)
        _close(evaluate(b, arm, q=q, qdot=qd), inverse_dynamics(arm, q, qd, zero))
        _close(evaluate(C, arm, q=q, qdot=qd) @ qd + expected_g, inverse_dynamics(arm, q, qd, zero))


def test_the_coriolis_matrix_is_christoffels():
    """Mdot - 2C skew-symmetric (Mdot by central differences of the lowered M): C is not just any C with C qd right."""
    arm = ARMS["puma560"]
    M, C = lowered_mass_matrix(arm, "fastest"), lowered_coriolis_matrix(arm, "fastest")
    q, qd, _ = _states(arm)[0]
    h = 1e-6
    M_dot = (evaluate(M, arm, q=q + h * qd) - evaluate(M, arm, q=q - h * qd)) / (2 * h)
    N = M_dot - 2 * evaluate(C, arm, q=q, qdot=qd)
    _close(N, -N.T, 1e-7)


def test_the_fastest_torques_are_the_symbolic_ones_exactly():
    """The planar 2R's traced torques, temporaries substituted back, are symjac's Newton-Euler torques."""
    arm = ARMS["planar2r"]
    lowered = lowered_inverse_dynamics(arm, "fastest")
    values = {}
    for sine, cosine, angle in lowered.angles:
        values[sine], values[cosine] = sp.sin(angle), sp.cos(angle)
    for symbol, expr in lowered.temporaries:
        values[symbol] = expr.xreplace(values)
    g = sp.Symbol("g", positive=True)
    expected = newton_euler(arm).torques.subs(g, sp.Rational(981, 100))
    for got, want in zip(lowered.outputs, expected, strict=True):
        assert sp.simplify(sp.nsimplify(got.xreplace(values).subs(g, sp.Rational(981, 100))) - want) == 0


def test_the_reference_can_fail():
    """A heavier last link changes the reference's torques: it reads the arm's own data."""
    arm = ARMS["rrpr"]
    heavier = dataclasses.replace(arm, inertials=(*arm.inertials[:-1], dataclasses.replace(
        arm.inertials[-1], mass=2 * arm.inertials[-1].mass)))
    q, qd, qdd = _states(arm)[0]
    got = evaluate(lowered_inverse_dynamics(arm, "fastest"), arm, q=q, qdot=qd, qddot=qdd)
    assert np.abs(got - inverse_dynamics(heavier, q, qd, qdd)).max() > 1e-3


def test_the_fastest_functions_are_smaller_than_the_raw_ones():
    arm = ARMS["puma560"]
    for lower in (lowered_inverse_dynamics, lowered_mass_matrix, lowered_gravity_torques):
        assert lower(arm, "fastest").op_count < lower(arm, "raw").op_count

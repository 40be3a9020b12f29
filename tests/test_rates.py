"""Joint rates: the closed-form inverse against the notes and numerics, damped least squares near singularities."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp
from marks import marked
from reference import finite_difference_jacobian, random_configuration

from symjac import damped_least_squares, inverse_rates, load_robot, rates_along_path
from symjac.analysis.inverse_rates import RATE_SYMBOLS, damping
from symjac.errors import ArgumentError
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.simplify import is_identity

t2, t3 = sp.symbols("theta2 theta3", real=True)
L1, L2, L3 = sp.symbols("L1 L2 L3", real=True)


def test_seed_002_theta1_rate_blows_up_at_the_shoulder_singularity():
    rates = inverse_rates(load_robot("articulated3r"), frame="tool")
    v_z = RATE_SYMBOLS[2]
    expected = v_z / (-L1 - L2 * sp.cos(t2) - L3 * sp.cos(t2 + t3))
    assert sp.simplify(rates.rates[0] - expected) == 0
    assert is_identity(rates.determinant, -L2 * L3 * sp.sin(t3) * (L1 + L2 * sp.cos(t2) + L3 * sp.cos(t2 + t3)),
                       AngleBasis.of([sp.Symbol("theta1", real=True), t2, t3]))


@pytest.mark.parametrize("name", marked(["planar2r", "planar3r", "articulated3r"]))
def test_closed_form_rates_reproduce_the_commanded_velocity(name):
    robot = load_robot(name)
    rates = inverse_rates(robot)
    rng = np.random.default_rng(5)
    point = np.array([float(c.xreplace(robot.defaults)) for c in rates_point(robot)])
    for _ in range(3):
        q = random_configuration(robot, rng)
        xdot = rng.normal(size=len(rates.rows))
        values = {**robot.defaults, **dict(zip(robot.q, q, strict=True)),
                  **dict(zip(rates.velocity, xdot, strict=True))}
        qdot = np.array([float(r.xreplace(values).evalf()) for r in rates.rates])
        J = finite_difference_jacobian(robot, q, frame=rates.frame, point=point)[list(rates.rows), :]
        assert np.allclose(J @ qdot, xdot, rtol=1e-5, atol=1e-6)


def rates_point(robot):
    if robot.tool is None:
        return (sp.S.Zero,) * 3
    return tuple(robot.tool.matrix[:3, 3])


def test_damping_rule_is_zero_away_and_grows_smoothly_near_a_singularity():
    assert damping(np.array([1.0, 0.2])) == 0.0
    assert damping(np.array([1.0, 0.05])) == 0.0
    assert damping(np.array([1.0, 0.0])) == pytest.approx(0.05)
    values = [damping(np.array([1.0, s])) for s in np.linspace(0.0, 0.05, 11)]
    assert all(a >= b for a, b in itertools.pairwise(values))


def test_damped_least_squares_is_exact_away_from_singularities():
    rng = np.random.default_rng(1)
    J = rng.normal(size=(3, 3)) + 3 * np.eye(3)
    xdot = rng.normal(size=3)
    assert np.allclose(damped_least_squares(J, xdot), np.linalg.solve(J, xdot))
    with pytest.raises(ArgumentError, match="shape"):
        damped_least_squares(J, xdot[:2])
    with pytest.raises(ArgumentError, match="finite"):
        damped_least_squares(J, np.array([np.nan, 0, 0]))


def test_rates_blow_up_towards_the_elbow_singularity_while_damped_rates_stay_bounded():
    robot = load_robot("planar2r")
    path = np.array([[0.3, angle] for angle in np.geomspace(0.5, 1e-6, 25)])
    result = rates_along_path(robot, path, xdot=[1.0, 0.0])  # radial-ish command near the stretched arm
    exact = np.abs(result.exact).max(axis=1)
    assert exact[-1] > 1e4 * exact[0]
    assert np.abs(result.damped).max() < 100
    assert np.all(np.diff(result.smallest_singular_value) < 0)
    far = result.tracking_error[0]
    assert far < 1e-9 and result.tracking_error[-1] > 0.1
    with pytest.raises(ArgumentError, match="path"):
        rates_along_path(robot, np.zeros((3, 3)), xdot=[1.0, 0.0])
    with pytest.raises(ArgumentError, match="xdot"):
        rates_along_path(robot, path, xdot=[1.0])

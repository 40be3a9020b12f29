"""Long chains stay exact and compact: every method against finite differences, and the planar arm's closed form."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from reference import evaluate, finite_difference_jacobian, random_configuration

from symjac import Chain, jacobian, robot_from_mapping
from symjac.jacobian import METHODS
from symjac.reporting import reporting_to

LENGTH = sp.Rational(1, 10)


def planar(n):
    joints = [{"type": "revolute", "alpha": 0, "a": 0.1} for _ in range(n)]
    return robot_from_mapping({"name": f"planar{n}", "convention": "standard", "joints": joints})


def snake(n):
    joints = [{"type": "revolute", "alpha": "pi/2" if i % 2 else "-pi/2", "a": "L"} for i in range(n)]
    return robot_from_mapping({"name": f"snake{n}", "convention": "standard", "parameters": {"L": 0.1},
                               "joints": joints})


@pytest.mark.parametrize("method", METHODS)
def test_planar_12r_entries_are_sums_of_cumulative_sines(method):
    """-J[0, j] = sum_{k >= j} L sin(theta_1 + ... + theta_k), J[1, j] the same with cosines, exactly."""
    robot = planar(12)
    J = jacobian(Chain(robot), method=method)
    theta = [joint.variable for joint in robot.joints]
    for j in range(12):
        sines = sum(LENGTH * sp.sin(sum(theta[:k + 1])) for k in range(j, 12))
        cosines = sum(LENGTH * sp.cos(sum(theta[:k + 1])) for k in range(j, 12))
        assert sp.expand(J[0, j]) == -sines
        assert sp.expand(J[1, j]) == cosines
        assert list(J[2:, j]) == [0, 0, 0, 1]


@pytest.mark.parametrize("robot", [planar(12), snake(12)], ids=["planar12", "snake12"])
def test_long_chains_match_finite_differences_by_every_method(robot):
    chain = Chain(robot)
    q = random_configuration(robot, np.random.default_rng(12))
    expected = finite_difference_jacobian(robot, q, 0, None)
    first = jacobian(chain, method="differentiation")
    np.testing.assert_allclose(evaluate(first, robot, q), expected, atol=1e-6)
    for method in METHODS[1:]:
        assert jacobian(chain, method=method) == first, method  # one normal form, so exactly equal


def test_long_derivations_report_their_stages():
    stages = []
    with reporting_to(stages.append):
        jacobian(Chain(planar(4)), method="velocity_propagation")
    assert "velocity propagation, link 4 of 4" in stages
    assert any(stage.startswith("simplifying") for stage in stages)

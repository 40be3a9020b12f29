"""Property-based checks over random DH chains: Jacobians against finite differences, methods against each other."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference import evaluate, finite_difference_jacobian, random_configuration
from strategies import robots

from symjac import chain_of, jacobian

SETTINGS = settings(deadline=None, max_examples=25, suppress_health_check=[HealthCheck.too_slow])


@pytest.mark.slow
@SETTINGS
@given(robot=robots(), data=st.data())
def test_jacobian_matches_finite_differences(robot, data):
    n = robot.n_coordinates
    frame = data.draw(st.sampled_from(["world", *range(n + 1), "tool"]), label="frame")
    point = data.draw(st.sampled_from(["wrist", "tool", (0.2, -0.1, 0.3)]), label="point")
    if point == "tool" and robot.tool is None:
        point = "wrist"
    J = jacobian(robot, frame=frame, point=point)
    coordinates = None
    if point == "tool":
        coordinates = np.array(robot.tool.matrix[:3, 3].subs(robot.defaults), dtype=float).ravel()
    elif point != "wrist":
        coordinates = np.array(point)
    rng = np.random.default_rng(data.draw(st.integers(0, 2**16), label="seed"))
    q = random_configuration(robot, rng)
    np.testing.assert_allclose(evaluate(J, robot, q), finite_difference_jacobian(robot, q, frame, coordinates),
                               atol=1e-6)


@pytest.mark.slow
@SETTINGS
@given(robot=robots(), data=st.data())
def test_methods_agree_exactly(robot, data):
    frame = data.draw(st.sampled_from(["world", *range(robot.n_joints + 1), "tool"]), label="frame")
    assert jacobian(robot, frame=frame, method="differentiation") == jacobian(robot, frame=frame,
                                                                             method="cross_product")


@pytest.mark.slow
@SETTINGS
@given(robot=robots())
def test_transforms_compose_and_invert(robot):
    """T_0_n = T_0_k T_k_n and T_n_0 T_0_n = I, numerically, for the raw structured products."""
    chain = chain_of(robot)
    n = robot.n_coordinates
    k = n // 2
    rng = np.random.default_rng(0)
    q = random_configuration(robot, rng)
    T_0_n = evaluate(chain.transform(0, n), robot, q)
    np.testing.assert_allclose(evaluate(chain.transform(0, k) * chain.transform(k, n), robot, q), T_0_n, atol=1e-12)
    np.testing.assert_allclose(evaluate(chain.transform(n, 0), robot, q) @ T_0_n, np.eye(4), atol=1e-12)
    np.testing.assert_allclose(evaluate(chain.transform("tool", "world"), robot, q)
                               @ evaluate(chain.transform("world", "tool"), robot, q), np.eye(4), atol=1e-12)


@pytest.mark.slow
@settings(deadline=None, max_examples=15, suppress_health_check=[HealthCheck.too_slow])
@given(robot=robots(), data=st.data())
def test_propagation_methods_agree_with_differentiation_at_random_configurations(robot, data):
    frame = data.draw(st.sampled_from([0, robot.n_joints, "tool"]), label="frame")
    point = "tool" if robot.tool is not None else "wrist"
    q = random_configuration(robot, np.random.default_rng(data.draw(st.integers(0, 2**16), label="seed")))
    expected = evaluate(jacobian(robot, frame=frame, point=point, simplify=False), robot, q)
    for method in ("velocity_propagation", "force_propagation"):
        J = jacobian(robot, frame=frame, point=point, method=method)
        np.testing.assert_allclose(evaluate(J, robot, q), expected, atol=1e-9, err_msg=method)

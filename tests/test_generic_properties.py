"""Property checks over random generic arms (issue 41): nested results against an independent NumPy reference.

Every arm (DH standard and modified, general joints, PoE in space and body form; prismatic joints; 3 to 8 joints;
calibrated-looking float geometry, :mod:`generic_arms`) must be derived nested, and every result, whether written
out or a :class:`~symjac.symbolic.nested.NestedMatrix`, evaluated with
:func:`~symjac.symbolic.nested.substitute`, must match central differences of the reference forward kinematics:
1e-9 for first derivatives (scaled by the largest entry), 1e-7 for second derivatives.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
import sympy as sp
from generic_arms import KINDS, Arm, derivative, generic_arms, point_jacobian, screw_jacobians
from hypothesis import HealthCheck, Phase, event, given, settings
from hypothesis import strategies as st

from symjac import (
    METHODS,
    Chain,
    body_jacobian,
    forward_kinematics,
    hessian,
    jacobian,
    jacobian_derivative,
    joint_rate_symbols,
    robot_from_toml,
    space_jacobian,
)
from symjac.symbolic.nested import substitute


def examples(count: int) -> settings:
    """Few examples, no deadline, and no explain phase (it re-runs a failing symbolic example about a hundred
    times: 165 s for one failure)."""
    return settings(deadline=None, max_examples=count, suppress_health_check=[HealthCheck.too_slow],
                    phases=[Phase.explicit, Phase.reuse, Phase.generate, Phase.shrink])


FIRST, SECOND = 1e-9, 1e-7

POE_SLOW = [pytest.param(kind, marks=pytest.mark.slow) if kind.startswith("poe") else kind for kind in KINDS]
"""The kinds for the derivative checks: a PoE arm costs 3-10 s per example there (its exact screws), so the fast
loop covers PoE through forward kinematics and the space and body Jacobians."""


def load(arm: Arm) -> tuple[Any, Chain]:
    """The arm's robot and chain, checked to be generic: derived nested."""
    event(f"{arm.kind}, {arm.n} joints")
    robot = robot_from_toml(arm.text)
    chain = Chain(robot)
    assert chain.nested, f"a generic arm was not derived nested:\n{arm.text}"
    return robot, chain


def evaluate(result: Any, robot: Any, q: np.ndarray, rates: np.ndarray | None = None) -> np.ndarray:
    """A symbolic result (Matrix, NestedMatrix or array) in numbers, every intermediate substituted once."""
    values = dict(zip(robot.joint_variables, (float(v) for v in q), strict=True))
    if rates is not None:
        values.update(zip(joint_rate_symbols(robot), (float(v) for v in rates), strict=True))
    entries = sp.flatten(result.tolist()) if isinstance(result, sp.NDimArray) else list(result)
    return np.array([float(e) for e in substitute(entries, values)]).reshape(result.shape)


def close(actual: np.ndarray, expected: np.ndarray, tolerance: float, what: str, arm: Arm) -> None:
    scale = max(1.0, float(np.abs(expected).max()))
    np.testing.assert_allclose(actual, expected, rtol=0, atol=tolerance * scale, err_msg=f"{what}\n{arm.text}")


def configuration(data: st.DataObject, n: int) -> np.ndarray:
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1), label="configuration seed"))
    return rng.uniform(-2, 2, n)


def frame_and_point(data: st.DataObject, arm: Arm) -> tuple[Any, dict[str, Any], Any, np.ndarray]:
    """A frame to express the Jacobian in (0, a middle one, the tool or the last frame, the world with a base) and
    a point: the tool's origin, the wrist, or a point of a middle link. Returns the frame, the jacobian arguments,
    and the reference's link and point coordinates."""
    n = arm.n
    tool = arm.tool is not None or arm.kind.startswith("poe")
    frames = [0, n // 2, "tool" if tool else n, *(["world"] if arm.base is not None else [])]
    frame = data.draw(st.sampled_from(frames), label="frame")
    choice = data.draw(st.sampled_from(["end", "middle link"]), label="point")
    if choice == "middle link":
        link = data.draw(st.integers(1, n - 1), label="link")
        point = np.random.default_rng(link).uniform(-0.4, 0.4, 3)
        return frame, {"point": [float(c) for c in point], "link": link}, link, point
    if tool:
        return frame, {"point": "tool"}, "tool", np.zeros(3)
    return frame, {"point": "wrist"}, n, np.zeros(3)


@pytest.mark.parametrize("kind", KINDS)
@examples(3)
@given(data=st.data())
def test_forward_kinematics_matches_the_reference(kind, data):
    arm = data.draw(generic_arms(kinds=(kind,)), label="arm")
    robot, chain = load(arm)
    q = configuration(data, arm.n)
    target = "tool" if robot.tool is not None or arm.kind.startswith("poe") else arm.n
    close(evaluate(forward_kinematics(robot, target=target), robot, q), arm.pose(q, "tool"), FIRST, "FK", arm)
    k = arm.n // 2
    close(evaluate(forward_kinematics(chain, target=k), robot, q), arm.pose(q, k), FIRST, f"FK to {k}", arm)


def check_jacobians(arm: Arm, data: st.DataObject) -> None:
    robot, _ = load(arm)
    q = configuration(data, arm.n)
    frame, arguments, link, point = frame_and_point(data, arm)
    expected = point_jacobian(arm, q, frame, link, point)
    for method in METHODS:
        J = jacobian(robot, frame=frame, method=method, **arguments)
        close(evaluate(J, robot, q), expected, FIRST, f"{method} in frame {frame} at {arguments}", arm)


@pytest.mark.parametrize("kind", POE_SLOW)
@examples(3)
@given(data=st.data())
def test_jacobian_all_methods_match_finite_differences(kind, data):
    check_jacobians(data.draw(generic_arms(max_joints=4, kinds=(kind,)), label="arm"), data)


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
@examples(1)
@given(data=st.data())
def test_long_jacobian_all_methods_match_finite_differences(kind, data):
    check_jacobians(data.draw(generic_arms(min_joints=6, max_joints=8, kinds=(kind,)), label="arm"), data)


def check_screw_jacobians(arm: Arm, data: st.DataObject) -> None:
    robot, _ = load(arm)
    q = configuration(data, arm.n)
    J_s, J_b = screw_jacobians(arm, q)
    close(evaluate(space_jacobian(robot), robot, q), J_s, FIRST, "J_s", arm)
    close(evaluate(body_jacobian(robot), robot, q), J_b, FIRST, "J_b", arm)


POE = ("poe", "poe body")


@examples(5)
@given(arm=generic_arms(max_joints=4, kinds=POE), data=st.data())
def test_space_and_body_jacobians_match_finite_differences(arm, data):
    check_screw_jacobians(arm, data)


@pytest.mark.slow
@examples(4)
@given(arm=generic_arms(min_joints=6, max_joints=8, kinds=POE), data=st.data())
def test_long_space_and_body_jacobians_match_finite_differences(arm, data):
    check_screw_jacobians(arm, data)


def reference_jacobian(arm: Arm, frame: Any, link: Any, point: np.ndarray) -> Any:
    return lambda qq: point_jacobian(arm, qq, frame, link, point)


def check_hessian(arm: Arm, data: st.DataObject) -> None:
    robot, _ = load(arm)
    q = configuration(data, arm.n)
    frame, arguments, link, point = frame_and_point(data, arm)
    H = evaluate(hessian(robot, frame=frame, **arguments), robot, q)
    J = reference_jacobian(arm, frame, link, point)
    for m in range(arm.n):
        close(H[:, :, m], derivative(J, q, np.eye(arm.n)[m]), SECOND, f"dJ/dq{m + 1} in {frame} at {arguments}",
              arm)


@pytest.mark.parametrize("kind", POE_SLOW)
@examples(2)
@given(data=st.data())
def test_hessian_matches_finite_differences(kind, data):
    check_hessian(data.draw(generic_arms(max_joints=4, kinds=(kind,)), label="arm"), data)


@pytest.mark.slow
@pytest.mark.parametrize("kind", KINDS)
@examples(1)
@given(data=st.data())
def test_long_hessian_matches_finite_differences(kind, data):
    check_hessian(data.draw(generic_arms(min_joints=6, max_joints=8, kinds=(kind,)), label="arm"), data)


@pytest.mark.parametrize("kind", POE_SLOW)
@examples(2)
@given(data=st.data())
def test_jacobian_derivative_matches_finite_differences(kind, data):
    """dJ/dt along a random rate vector against the directional difference of J; SymPy's chain rule through the
    intermediates (method "differentiation", 1.5 s at 4 joints, 7-17 s at 6-8) only up to 3 joints."""
    arm = data.draw(generic_arms(max_joints=5, kinds=(kind,)), label="arm")
    robot, _ = load(arm)
    q = configuration(data, arm.n)
    rates = np.random.default_rng(arm.n).uniform(-1, 1, arm.n)
    frame, arguments, link, point = frame_and_point(data, arm)
    expected = derivative(reference_jacobian(arm, frame, link, point), q, rates)
    for method in ("hessian", "differentiation") if arm.n <= 3 else ("hessian",):
        Jdot = jacobian_derivative(robot, frame=frame, method=method, **arguments)
        close(evaluate(Jdot, robot, q, rates), expected, SECOND, f"{method} in {frame} at {arguments}", arm)


CRASHING_POE = """name = "generic_poe"
convention = "poe"
[home]
matrix = [[-0.8534754844461716, 0.22806003952911924, 0.46858106643285213, 0.6055682954660062], \
[-0.5035517675633784, -0.12931694656970477, -0.854232254550064, -0.636288124924681], \
[-0.13422076900826385, -0.965021111530657, 0.22520887963614045, 0.5596293399458461], [0.0, 0.0, 0.0, 1.0]]
[[joints]]
type = "revolute"
screw = [0.6189840189585, -0.7750997066071, 0.1268039001431, -0.1347041960957, -0.0368734788274, 0.4321564398837]
[[joints]]
type = "revolute"
screw = [0.9786246769927, -0.2041550689291, 0.0247880901147, -0.0537797295155, -0.3196483528553, -0.5094245270991]
"""
"""Two generic revolute screws in space form (joints 1 and 4 of a random 6R arm, 13 decimals)."""


def test_generic_space_screws_do_not_crash_the_exact_twist_between_joints():
    """SymPy 1.14's sqrt of some long integers raises (sympy/sympy#28621): a nested chain takes no exact twist."""
    robot = robot_from_toml(CRASHING_POE)
    assert Chain(robot).nested
    T = forward_kinematics(robot, target="tool")
    assert T.shape == (4, 4)

"""The notebooks' answer checker: equivalent forms pass, wrong answers fail naming the entry that differs.

The hints themselves (and that they never give the answer away) are tested in ``test_teaching_hints.py``.
"""

from __future__ import annotations

import pytest
import sympy as sp

from symjac import load_robot
from symjac.teaching.exercises import check

t1, t2 = sp.symbols("theta1 theta2", real=True)


@pytest.mark.parametrize(("answer", "expected"), [
    (2 * sp.sin(t1) * sp.cos(t1), sp.sin(2 * t1)),
    (sp.cos(t2) / sp.sin(t2), sp.cot(t2)),
    (1 / sp.cos(t1) ** 2, 1 + sp.tan(t1) ** 2),
    (sp.sin(t1 + t2) / (sp.cos(t1) * sp.cos(t2)), sp.tan(t1) + sp.tan(t2)),
    (sp.Matrix([[sp.csc(t1)], [sp.sec(t2)]]), sp.Matrix([[1 / sp.sin(t1)], [1 / sp.cos(t2)]])),
])
def test_equivalent_forms_pass(answer, expected):
    assert check(answer, expected)


@pytest.mark.parametrize(("answer", "expected"), [
    (sp.cos(t2) / sp.sin(t2), sp.tan(t2)),
    (sp.sin(t1) * sp.cos(t1), sp.sin(2 * t1)),
    (sp.cot(t1), sp.cot(t2)),
])
def test_wrong_answers_fail(answer, expected):
    with pytest.raises(AssertionError, match="your answer"):
        check(answer, expected)


def test_matrix_answers_name_the_entry_and_shapes_must_match():
    robot = load_robot("planar2r")
    q1, q2 = robot.q
    with pytest.raises(AssertionError, match=r"entry 2 \(index 1 in Python\)"):
        check(sp.Matrix([[sp.sin(q1)], [sp.cos(q2)]]), sp.Matrix([[sp.sin(q1)], [sp.sin(q2)]]), robot)
    with pytest.raises(AssertionError, match="transpose it"):
        check(sp.Matrix([1, 2]), sp.Matrix([[1, 2]]))


def test_numbers_are_compared_to_a_tolerance():
    assert check(0.9 + 1e-12, 0.9)
    with pytest.raises(AssertionError):
        check(0.91, 0.9)


def test_plain_symbols_are_matched_by_name():
    """Issue 14: symbols without assumptions are the robot's symbols of the same name."""
    from symjac import jacobian

    robot = load_robot("planar2r")
    J = jacobian(robot)
    L1, L2 = sp.symbols("L1 L2")
    p1, p2 = sp.symbols("theta1 theta2")
    assert check(-L2 * sp.sin(p1 + p2), J[0, 1], robot)
    assert check(sp.Matrix([-L1 * sp.sin(p1) - L2 * sp.sin(p1 + p2), -L2 * sp.sin(p1 + p2)]).T, J[0, :], robot)
    assert check(-L2 * sp.sin(p1) * sp.cos(p2) - L2 * sp.cos(p1) * sp.sin(p2), J[0, 1])  # no robot: by expected
    with pytest.raises(AssertionError, match="your answer"):
        check(-L1 * sp.sin(p1 + p2), J[0, 1], robot)
    with pytest.raises(AssertionError, match="your answer"):
        check(-L2 * sp.sin(p1 - p2), J[0, 1], robot)
    with pytest.raises(AssertionError, match="your answer"):
        check(-sp.Symbol("L3") * sp.sin(p1 + p2), J[0, 1], robot)


def test_a_placeholder_is_not_an_answer():
    with pytest.raises(AssertionError, match="no answer yet"):
        check(..., sp.sin(t1))
    with pytest.raises(AssertionError, match="no answer yet"):
        check(None, 0.5)

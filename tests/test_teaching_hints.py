"""Wrong answers get a hint of what is wrong, never the answer; the answer only with ``reveal=True``.

Each case is a wrong answer to a question whose expected answer has a distinctive printed form; the message must
name what is wrong (the sign, a factor, a symbol, the shape, an entry, values missing from a set) and must not
contain the expected answer, nor any of its entries that the answer got wrong.
"""

from __future__ import annotations

import pytest
import sympy as sp

from symjac import jacobian, load_robot
from symjac.teaching.exercises import check, check_set

ROBOT = load_robot("planar2r")
J = jacobian(ROBOT)
L1, L2, t1, t2 = sp.symbols("L1 L2 theta1 theta2")  # plain symbols, as a student writes them
RIGHT = -L2 * sp.sin(t1 + t2)  # J[0, 1]


def _message(answer, expected, **options):
    with pytest.raises(AssertionError) as failure:
        check(answer, expected, ROBOT, **options)
    return str(failure.value)


def _hidden(message, expected):
    """None of the expected answer's printed entries (nor the whole) appears in ``message``."""
    entries = list(expected) if isinstance(expected, sp.MatrixBase) else [expected]
    return all(sp.sstr(e) not in message for e in [*entries, expected] if e != 0)


@pytest.mark.parametrize(("answer", "hint"), [
    (L2 * sp.sin(t1 + t2), "has the wrong sign"),
    (-2 * L2 * sp.sin(t1 + t2), "off by a constant factor"),
    (-L2**2 * sp.sin(t1 + t2), "off by a factor in L2"),
    (-L2 * sp.sin(t1 + t2) + 1, "off by a constant term"),
    (-L2 * sp.cos(t1 + t2), "different function"),
    (-L1 * sp.sin(t1 + t2), "depends on L1, which it should not, and should depend on L2"),
    (-L2 * sp.sin(t1), "should depend on theta2"),
    (0, "is zero, but it should not be"),
])
def test_a_wrong_expression_gets_a_hint_not_the_answer(answer, hint):
    message = _message(answer, J[0, 1])
    assert hint in message
    assert _hidden(message, J[0, 1])


def test_a_wrong_matrix_names_the_entry_and_counts_the_wrong_ones():
    answer = J[:2, :].copy()
    answer[0, 1] = -answer[0, 1]
    message = _message(answer, J[:2, :])
    assert message == "the entry in row 1, column 2 ([0, 1] in Python) has the wrong sign"
    answer[1, 0] = 0
    message = _message(answer, J[:2, :])
    assert message.startswith("2 of 4 entries are wrong; the entry in row 1, column 2")
    assert _hidden(message, J[:2, :])


@pytest.mark.parametrize(("answer", "expected", "hint"), [
    (-J[:2, :], J[:2, :], "the whole answer has the wrong sign"),
    (J[:2, :].T, J[:2, :], "transpose of the right one"),
    (J[:2, 0].T, J[:2, 0], "a row of 2, the question asks for a column of 2: transpose it"),
    (J[:3, 0], J[:2, 0], "a column of 3, the question asks for a column of 2"),
    (sp.Matrix([0, L1]), sp.Matrix([0, 0]), "entry 2 (index 1 in Python) should be zero"),
])
def test_shapes_signs_and_transposes(answer, expected, hint):
    message = _message(answer, expected)
    assert hint in message
    assert _hidden(message, expected)


@pytest.mark.parametrize(("answer", "hint"), [(0.5, "too large"), (0.3, "too small"), (-0.4, "wrong sign")])
def test_numbers_say_which_way_they_are_off(answer, hint):
    message = _message(answer, 0.4)
    assert hint in message and "0.4" not in message


def test_true_or_false():
    assert check(True, True) and check(sp.true, True)
    assert "not right" in _message(False, True) and "True" not in _message(False, True).replace("True or False", "")
    assert "True or False, not 'yes'" in _message("yes", True)


def test_the_answer_only_on_request():
    assert "the expected answer: -L2*sin(theta1 + theta2)" in _message(L2, J[0, 1], reveal=True)
    assert "the expected answer" not in _message(L2, J[0, 1])
    assert "the expected answer: -L2*sin(theta1 + theta2)" in _message(..., J[0, 1], reveal=True)
    assert check(RIGHT, J[0, 1], ROBOT, reveal=True)


@pytest.mark.parametrize("answer", [{0, sp.pi}, [sp.pi, 0], (0.0, 3.141592653589793), sp.FiniteSet(0, sp.pi),
                                    [2 * sp.pi, -sp.pi], [0, sp.pi, 2 * sp.pi]])
def test_any_form_of_a_set_of_angles_passes(answer):
    assert check_set(answer, {0, sp.pi})


@pytest.mark.parametrize(("answer", "hint"), [
    ({0}, "your set misses 1 value"),
    ({0, 3 * sp.pi / 4, sp.pi / 2}, "your set has pi/2, which is not a solution"),
    ([sp.pi / 2], "your set misses 2 values, and pi/2 is not one of them"),
    (sp.Interval(0, sp.pi), "give the values one by one"),
    ({"elbow"}, "'elbow' in your set is not a real number"),
    (..., "no answer yet"),
])
def test_a_wrong_set_says_what_is_missing_or_extra_without_the_missing_values(answer, hint):
    with pytest.raises(AssertionError) as failure:
        check_set(answer, {0, 3 * sp.pi / 4})
    message = str(failure.value)
    assert hint in message
    assert "3*pi/4" not in message or answer == {0, 3 * sp.pi / 4, sp.pi / 2}


def test_a_set_answer_shows_the_solutions_on_request():
    with pytest.raises(AssertionError, match=r"the expected answer: \{0, pi\}"):
        check_set({0}, {0, sp.pi}, reveal=True)


def test_a_set_is_not_an_answer_to_a_value_question():
    assert "not a set" in _message({1}, 1)


def test_a_hint_reads_the_expected_answer_simplified():
    """A raw det J holds theta1 that cancels: the hint must not ask for theta1 (it named it before)."""
    robot = load_robot("planar2r")
    raw = jacobian(robot, simplify=False)[:2, :].det()
    L1, L2, theta2 = sp.symbols("L1 L2 theta2")
    with pytest.raises(AssertionError) as wrong:
        check(L1 * L2 * sp.cos(theta2), raw, robot)
    assert "theta1" not in str(wrong.value) and "θ" not in str(wrong.value)

"""Every sine and cosine of joint variables in a printed result is shorthand, and the printed result is the result.

Robots: a SCARA whose screw points down (its propagation steps hold theta2 - theta4, printed c_{2-4}), the catalog
SCARA and PUMA 560, a 2R with a 45-degree DH twist and a pi/4 joint offset, and a product-of-exponentials arm with a
45-degree screw axis. The LaTeX printed is read back into SymPy (a small reader of what the printer writes, below:
shorthand, fractions, roots, powers, implicit products) and compared with the unprinted expression at random
configurations and parameters; the pretty text is checked for the same shorthand and no ``sin``/``cos``.
"""

from __future__ import annotations

import random
import re

import pytest
import sympy as sp

from symjac import (
    body_jacobian,
    force_propagation,
    forward_kinematics,
    jacobian,
    load_robot,
    representation_jacobian,
    robot_from_toml,
)
from symjac.printing import latex, pretty, propagation_steps, step_equations
from symjac.printing.pretty import one_line
from symjac.printing.shorthand import shorthand_indices, textbook_form

SCARA_DOWN = """\
name = "scara_down"
description = "SCARA whose prismatic axis points down (alpha3 = pi): the last rotation is subtracted"
convention = "modified"
[parameters]
d1 = 0.2
L1 = 0.175
L2 = 0.175
[[joints]]
type = "revolute"
alpha = 0
a = 0
d = "d1"
theta = 0
[[joints]]
type = "revolute"
alpha = 0
a = "L1"
d = 0
theta = 0
[[joints]]
type = "prismatic"
alpha = "pi"
a = "L2"
d = 0
theta = 0
[[joints]]
type = "revolute"
alpha = 0
a = 0
d = 0
theta = 0
"""

TILT45 = """\
name = "tilt45"
description = "2R with a 45-degree twist and a pi/4 offset on joint 2"
convention = "standard"
[parameters]
L1 = 0.3
L2 = 0.2
[[joints]]
type = "revolute"
alpha = "pi/4"
a = "L1"
d = 0
theta = 0
[[joints]]
type = "revolute"
alpha = 0
a = "L2"
d = 0
theta = "pi/4"
"""

POE45 = """\
name = "poe45"
description = "3R whose last screw axis is [0, sqrt(2)/2, sqrt(2)/2]"
convention = "poe"
[parameters]
L1 = 0.3
L2 = 0.2
[home]
matrix = [[1, 0, 0, "L1 + L2"], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
[[joints]]
type = "revolute"
screw = [0, 0, 1, 0, 0, 0]
[[joints]]
type = "revolute"
screw = [0, 1, 0, 0, 0, "L1"]
[[joints]]
type = "revolute"
screw = [0, "sqrt(2)/2", "sqrt(2)/2", 0, "-sqrt(2)*(L1 + L2)/2", "sqrt(2)*(L1 + L2)/2"]
"""

ROBOTS = {"scara_down": SCARA_DOWN, "tilt45": TILT45, "poe45": POE45}
FULL_TRIG = re.compile(r"\\(sin|cos)\b|\b(sin|cos)\b")


def robot(name: str):
    return robot_from_toml(ROBOTS[name]) if name in ROBOTS else load_robot(name)


# --- reading printed LaTeX back --------------------------------------------------------------------------------

_TOKEN = re.compile(r"\\dot\{\\[A-Za-z]+\}_\{[^{}]*\}|[sc]_\{[0-9,\-]+\}|\\?[A-Za-z]+_\{[^{}]*\}|\\left\(|\\right\)"
                    r"|\\[bB]igl\(|\\[bB]igr\)|\\[A-Za-z]+|\d+\.\d+|\d+|[A-Za-z]|[-+(){}^&]|\\\\")


def _angle(indices: str) -> sp.Expr:
    """``"12-4" -> theta1 + theta2 - theta4``; with commas the indices are whole numbers (``"8,9-10"``)."""
    parts = re.findall(r"(-?)(\d+)", indices) if "," in indices else re.findall(r"(-?)(\d)", indices)
    return sum((-1 if sign else 1) * sp.Symbol(f"theta{number}", real=True) for sign, number in parts)


class _Reader:
    """A recursive-descent reader of the LaTeX the textbook printer writes for one expression."""

    def __init__(self, tex: str, names: dict[str, sp.Symbol]):
        self.tokens = [t for t in _TOKEN.findall(tex) if t not in (r"\cdot",)]
        self.names = names
        self.at = 0

    def read(self) -> sp.Expr:
        value = self.sum()
        assert self.at == len(self.tokens), f"unread: {self.tokens[self.at:]}"
        return value

    def peek(self) -> str | None:
        return self.tokens[self.at] if self.at < len(self.tokens) else None

    def take(self, expected: str | None = None) -> str:
        token = self.tokens[self.at]
        assert expected is None or token == expected, (token, expected, self.tokens)
        self.at += 1
        return token

    def sum(self) -> sp.Expr:
        total = sp.S.Zero
        sign = 1
        if self.peek() in ("+", "-"):
            sign = -1 if self.take() == "-" else 1
        total += sign * self.product()
        while self.peek() in ("+", "-"):
            sign = -1 if self.take() == "-" else 1
            total += sign * self.product()
        return total

    def product(self) -> sp.Expr:
        value = self.power()
        while self.peek() not in (None, "+", "-", ")", r"\right)", r"\bigr)", r"\Bigr)", "}", "&", "\\\\"):
            value *= self.power()
        return value

    def power(self) -> sp.Expr:
        base = self.atom()
        if self.peek() == "^":
            self.take()
            base = base ** self.group()
        return base

    def group(self) -> sp.Expr:
        self.take("{")
        value = self.sum()
        self.take("}")
        return value

    def atom(self) -> sp.Expr:
        token = self.take()
        closing = {"(": ")", r"\left(": r"\right)", r"\bigl(": r"\bigr)", r"\Bigl(": r"\Bigr)"}
        if token in closing:
            value = self.sum()
            self.take(closing[token])
            return value
        if token == "{":
            self.at -= 1
            return self.group()
        if token == r"\frac":
            return self.group() / self.group()
        if token == r"\sqrt":
            return sp.sqrt(self.group())
        if token == r"\pi":
            return sp.pi
        if re.fullmatch(r"\d+(\.\d+)?", token):
            return sp.Rational(token) if "." not in token else sp.Float(token)
        if match := re.fullmatch(r"([sc])_\{([0-9,\-]+)\}", token):
            return (sp.sin if match.group(1) == "s" else sp.cos)(_angle(match.group(2)))
        assert token in self.names, f"unknown token {token!r} (names: {sorted(self.names)})"
        return self.names[token]


def read_latex(tex: str, expr: sp.Expr) -> sp.Expr:
    """The SymPy expression ``tex`` writes, its symbols those of ``expr`` (matched by how they print)."""
    return _Reader(tex, {latex(symbol): symbol for symbol in expr.free_symbols}).read()


def read_matrix(tex: str, matrix: sp.MatrixBase) -> sp.Matrix:
    body = tex[tex.index(r"\begin{bmatrix}") + len(r"\begin{bmatrix}"):tex.rindex(r"\end{bmatrix}")]
    rows = [row.split("&") for row in body.split("\\\\")]
    assert (len(rows), len(rows[0])) == matrix.shape
    return sp.Matrix([[read_latex(cell, matrix[i, j]) for j, cell in enumerate(row)] for i, row in enumerate(rows)])


def assert_same(printed: sp.Expr, expr: sp.Expr, points: int = 3) -> None:
    """``printed == expr`` at random values of every symbol (a wrong sign or index fails by far)."""
    generator = random.Random(42)
    symbols = sorted(sp.Matrix([expr]).free_symbols | sp.Matrix([printed]).free_symbols, key=str)
    for _ in range(points):
        values = {s: sp.Float(generator.uniform(-2.0, 2.0)) for s in symbols}
        a, b = complex(sp.N(printed.xreplace(values))), complex(sp.N(expr.xreplace(values)))
        assert abs(a - b) <= 1e-9 * (1 + abs(b)), (printed, expr, a, b)


def assert_printed_exactly(tex: str, matrix: sp.MatrixBase) -> None:
    assert not FULL_TRIG.search(tex), tex
    read = read_matrix(tex, matrix)
    for printed, entry in zip(read, matrix, strict=True):
        assert_same(printed, entry)


# --- the results ------------------------------------------------------------------------------------------------

def _results(name: str) -> dict[str, sp.MatrixBase]:
    arm = robot(name)
    results = {"fk": forward_kinematics(arm), "body": body_jacobian(arm)}
    if name != "puma560":
        results["jacobian"] = jacobian(arm)
    return results


@pytest.mark.parametrize("name", ["scara_down", "tilt45", "poe45", "puma560", "scara"])
def test_results_print_in_shorthand_and_equal_what_they_print(name):
    for what, matrix in _results(name).items():
        tex = latex(matrix)
        assert_printed_exactly(tex, matrix)
        text = pretty(matrix)
        assert not FULL_TRIG.search(text), f"{name} {what}:\n{text}"


@pytest.mark.parametrize("name", ["scara_down", "scara", "tilt45"])
def test_force_propagation_steps_print_in_shorthand(name):
    propagation = force_propagation(robot(name))
    equations = step_equations(propagation)
    for equation, tex, text in zip(equations, propagation_steps(propagation, "latex"),
                                   propagation_steps(propagation, "pretty"), strict=True):
        assert_printed_exactly(tex, equation.rhs)
        assert not FULL_TRIG.search(text), text


def test_the_scara_with_its_screw_down_prints_differences():
    propagation = force_propagation(robot("scara_down"))
    tex = "\n".join(propagation_steps(propagation, "latex"))
    text = "\n".join(propagation_steps(propagation, "pretty"))
    assert "c_{2-4}" in tex and "s_{12-4}" in tex
    assert "c₂₋₄" in text and "s₁₂₋₄" in text


def test_a_45_degree_offset_prints_collected():
    t2, t6, L = sp.symbols("theta2 theta6 L", real=True)
    assert latex(sp.sin(t2 + sp.pi / 4)) == r"\frac{\sqrt{2} \left(s_{2} + c_{2}\right)}{2}"
    assert latex(sp.sqrt(2) * (sp.sin(t6) / 2 + sp.cos(t6) / 2)) == r"\frac{\sqrt{2} \left(s_{6} + c_{6}\right)}{2}"
    assert latex(sp.sin(t6) / 2 + sp.cos(t6) / 2) == r"\frac{s_{6} + c_{6}}{2}"  # a whole entry too
    assert latex(sp.sin(t6) / 2 + sp.cos(t6) / 3) == r"\frac{s_{6}}{2} + \frac{c_{6}}{3}"  # no common fraction
    assert one_line(sp.cos(t2 - t6) * L) == "L⋅c₂₋₆"
    body = body_jacobian(robot("poe45"))  # before: L_2 (c_3/2 - 1/2), halves inside the parentheses
    assert r"\left(\frac" not in latex(body) and "(c₃ - 1)" in pretty(body)


def test_representation_angles_print_in_shorthand_in_every_format():
    rates = representation_jacobian(load_robot("planar3r"), "zyz").E
    assert rates.atoms(sp.sin) and not FULL_TRIG.search(pretty(rates)) and not FULL_TRIG.search(latex(rates))
    alpha, beta = sp.symbols("alpha beta", real=True)
    assert one_line(sp.cos(alpha) / sp.sin(beta)) == "c_\N{GREEK SMALL LETTER ALPHA}/s_β"


@pytest.mark.parametrize("argument, indices", [
    ("theta2 - theta4", "2-4"), ("theta1 + theta2 - theta4", "12-4"), ("theta3 - theta1 - theta2", "3-1-2"),
    ("theta8 + theta9 - theta10", "8,9-10"), ("2*theta1", None), ("theta1 + pi/4", None), ("-theta1 - theta2", None)])
def test_shorthand_indices(argument, indices):
    expr = sp.sympify(argument, locals={f"theta{i}": sp.Symbol(f"theta{i}", real=True) for i in range(11)})
    assert shorthand_indices(expr) == indices


def test_the_rewriting_is_an_identity():
    t1, t2, t3, a = sp.symbols("theta1 theta2 theta3 a", real=True)
    exprs = [sp.sin(t1 - t2 + sp.pi / 4) * a, sp.cos(t3 + sp.pi / 6) ** 2, a * (sp.cos(t1) / 3 - sp.Rational(2, 3)),
             sp.cos(t2 + sp.Float(0.3)) - sp.sin(t1 + t2 + 1), sp.sin(sp.pi / 3 - t2) * a, sp.sin(sp.pi / 4 - t2)]
    for expr in exprs:
        assert_same(textbook_form(expr), expr)
        functions = [f for f in textbook_form(expr).atoms(sp.sin, sp.cos) if f.free_symbols]  # sin(1) is a number
        assert functions and all(shorthand_indices(f.args[0]) is not None for f in functions), textbook_form(expr)


# --- the checks can fail ----------------------------------------------------------------------------------------

def test_the_checks_catch_a_wrong_or_full_print():
    t2, t4 = sp.symbols("theta2 theta4", real=True)
    matrix = sp.Matrix([[sp.cos(t2 - t4)]])
    with pytest.raises(AssertionError):
        assert_printed_exactly(r"\begin{bmatrix}c_{24}\end{bmatrix}", matrix)  # a sum printed for a difference
    with pytest.raises(AssertionError):
        assert_printed_exactly(r"\begin{bmatrix}\cos{\left(\theta_{2} - \theta_{4} \right)}\end{bmatrix}", matrix)
    assert_printed_exactly(r"\begin{bmatrix}c_{2-4}\end{bmatrix}", matrix)
    with pytest.raises(AssertionError):
        assert_same(read_latex(r"\frac{\sqrt{2} \left(s_{2} - c_{2}\right)}{2}", sp.sin(t2)), sp.sin(t2 + sp.pi / 4))

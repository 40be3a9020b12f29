r"""Checking students' answers: any equivalent form passes; a wrong one gets a hint, never the answer itself.

Used by the teaching notebooks; a student writes an answer in any algebraically equivalent form (``-s1*L1 - ...``,
with or without the angle-sum identities applied) and :func:`check` decides whether it is right. A wrong answer
raises an ``AssertionError`` that says *what* is wrong (the shape, which entry, a sign, a factor, a symbol that
should or should not appear, values missing from a set or not in it) without printing the expected answer; the
answer is shown only on request, with ``reveal=True`` (every checker takes it):

* :func:`check`: expressions, vectors and matrices (exactly, as functions of the joint angles), numbers (to a
  tolerance), and True/False questions;
* :func:`check_set`: a set of solutions, given as a set, list, tuple or SymPy ``FiniteSet``, angles compared modulo
  :math:`2\pi`.
"""

from __future__ import annotations

import random
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
import sympy as sp

from symjac.model.robot import Robot
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.simplify import is_identity

__all__ = ["check", "check_set"]

_TRUTH = (bool, np.bool_, sp.logic.boolalg.BooleanAtom)


def check(answer: Any, expected: Any, robot: Robot | None = None, *, tolerance: float = 1e-9,
          reveal: bool = False) -> bool:
    """``True`` if ``answer`` equals ``expected``; otherwise an ``AssertionError`` with a hint of what is wrong.

    Symbolic answers (expressions or matrices) are compared exactly as functions of the robot's joint angles (or of
    every symbol named ``theta<i>`` if no robot is given), fractions and tan/cot/sec/csc included; numeric answers
    entry by entry to ``tolerance``; a True/False question by its truth value. Symbols are matched by name:
    ``sp.symbols("L2 theta1")`` without assumptions stand for the robot's (or the expected answer's) ``L2`` and
    ``theta1``, whatever assumptions those carry. The message of a wrong answer names the first wrong entry and what
    is wrong with it (a sign, a constant factor, a factor in the parameters, a constant term, a symbol too many or
    missing), never the expected value; ``reveal=True`` adds the expected answer (also to "no answer yet").

    Examples
    --------
    >>> t = sp.Symbol("theta1", real=True)
    >>> check(2 * sp.sin(t) * sp.cos(t), sp.sin(2 * t))
    True
    >>> check(sp.cos(t) / sp.sin(t), sp.cot(t))
    True
    >>> check(sp.sin(sp.Symbol("theta1")), sp.sin(t))  # a plain symbol of the same name is the same quantity
    True
    >>> check(-sp.sin(t), sp.sin(t))
    Traceback (most recent call last):
    ...
    AssertionError: your answer has the wrong sign
    """
    try:
        _check(answer, expected, robot, tolerance)
    except AssertionError as wrong:
        raise AssertionError(_revealed(str(wrong), expected, reveal)) from None
    return True


def check_set(answer: Any, expected: Iterable[Any], *, period: Any = 2 * sp.pi, tolerance: float = 1e-9,
              reveal: bool = False) -> bool:
    r"""``True`` if ``answer`` holds the same values as ``expected``; otherwise an ``AssertionError`` with a hint.

    ``answer`` may be a set, list, tuple, NumPy array or SymPy ``FiniteSet`` (or one value); the order and repeated
    values do not matter, and numbers are compared modulo ``period`` (default :math:`2\pi`, angles; ``None``: as
    they are) to ``tolerance``. The message says how many values are missing and which of the answer's values are
    not solutions, never the missing ones; ``reveal=True`` adds the expected set.

    Examples
    --------
    >>> check_set([sp.pi, 2 * sp.pi], {0, sp.pi})  # 2 pi is the angle 0
    True
    >>> check_set({sp.pi / 2}, {0, sp.pi})
    Traceback (most recent call last):
    ...
    AssertionError: your set misses 2 values, and pi/2 is not one of them
    """
    try:
        _check_set(answer, expected, period, tolerance)
    except AssertionError as wrong:
        shown = sp.FiniteSet(*_elements(expected)) if reveal else None
        raise AssertionError(_revealed(str(wrong), shown, reveal)) from None
    return True


def _revealed(message: str, expected: Any, reveal: bool) -> str:
    return f"{message}\nthe expected answer: {sp.sstr(expected)}" if reveal else message


def _no_answer(answer: Any) -> None:
    if answer is Ellipsis or answer is None:
        raise AssertionError("no answer yet: replace the ... with your answer and run the cell again")


def _check(answer: Any, expected: Any, robot: Robot | None, tolerance: float) -> None:
    _no_answer(answer)
    if isinstance(expected, _TRUTH):
        if not isinstance(answer, _TRUTH):
            raise AssertionError(f"the answer is True or False, not {answer!r}")
        if bool(answer) != bool(expected):
            raise AssertionError("that is not right: look again at the reasoning (the answer is True or False)")
        return
    right = _as_matrix(expected)
    names = _symbols_by_name(robot, right)
    right = _renamed(right, names)
    left = _renamed(_as_matrix(answer), names)
    if left.shape != right.shape:
        raise AssertionError(_shape_hint(left, right))
    basis = _basis(robot, [*left, *right])
    wrong = [index for index, (a, b) in enumerate(zip(left, right, strict=True))
             if not _same(a, b, basis, tolerance)]
    if not wrong:
        return
    if len(left) > 1 and all(_same(a, -b, basis, tolerance) for a, b in zip(left, right, strict=True)):
        raise AssertionError("the whole answer has the wrong sign")
    if left.is_square and all(_same(a, b, basis, tolerance) for a, b in zip(left.T, right, strict=True)):
        raise AssertionError("your answer is the transpose of the right one (rows and columns swapped)")
    first = wrong[0]
    expected_entry = right[first]  # hints read its symbols: simplified first (a raw det J holds theta1 that cancels)
    if sp.count_ops(expected_entry) < 400:
        expected_entry = sp.simplify(expected_entry)
    hint = _entry_hint(left[first], expected_entry, basis, tolerance)
    if left.shape == (1, 1):
        raise AssertionError(f"your answer {hint}")
    count = f"{len(wrong)} of {len(left)} entries are wrong; " if len(wrong) > 1 else ""
    raise AssertionError(f"{count}{_position(left, first)} {hint}")


def _shape_hint(left: sp.Matrix, right: sp.Matrix) -> str:
    def size(m: sp.Matrix) -> str:
        if m.shape == (1, 1):
            return "a single value"
        if m.cols == 1:
            return f"a column of {m.rows}"
        return f"a row of {m.cols}" if m.rows == 1 else f"a {m.rows} x {m.cols} matrix"

    message = f"your answer is {size(left)}, the question asks for {size(right)}"
    if left.T.shape == right.shape:
        message += ": transpose it"
    return message


def _position(matrix: sp.Matrix, index: int) -> str:
    row, col = divmod(index, matrix.cols)
    if matrix.cols == 1 or matrix.rows == 1:
        return f"entry {max(row, col) + 1} (index {max(row, col)} in Python)"
    return f"the entry in row {row + 1}, column {col + 1} ([{row}, {col}] in Python)"


def _same(a: sp.Expr, b: sp.Expr, basis: AngleBasis, tolerance: float) -> bool:
    if a.free_symbols or b.free_symbols:
        return _same_function(a, b, basis)
    return abs(complex(a) - complex(b)) <= tolerance * max(1.0, abs(complex(b)))


def _entry_hint(a: sp.Expr, b: sp.Expr, basis: AngleBasis, tolerance: float) -> str:
    """What is wrong with ``a`` where ``b`` is right, in words that do not give ``b`` away."""
    if _same(b, sp.S.Zero, basis, tolerance):
        return "should be zero"
    if _same(a, sp.S.Zero, basis, tolerance):
        return "is zero, but it should not be"
    if _same(a, -b, basis, tolerance):
        return "has the wrong sign"
    if not (a.free_symbols or b.free_symbols):
        return "is too large" if abs(complex(a)) > abs(complex(b)) else "is too small"
    extra = sorted(str(s) for s in a.free_symbols - b.free_symbols)
    missing = sorted(str(s) for s in b.free_symbols - a.free_symbols)
    if extra or missing:
        parts = ([f"depends on {', '.join(extra)}, which it should not"] if extra else []) + (
            [f"should depend on {', '.join(missing)}"] if missing else [])
        return ", and ".join(parts)
    return _shape_of_error(a, b)


def _shape_of_error(a: sp.Expr, b: sp.Expr) -> str:
    """Compare ``a`` and ``b`` at random values of their symbols: a constant ratio or difference, or neither."""
    symbols = sorted(a.free_symbols | b.free_symbols, key=str)
    angles = [s for s in symbols if s.name.startswith(("theta", "q"))]
    others = [s for s in symbols if s not in angles]
    rng = random.Random(0)

    def values(base: dict[sp.Symbol, float] | None = None) -> dict[sp.Symbol, float]:
        point = {s: rng.uniform(0.3, 1.3) for s in others} if base is None else dict(base)
        point.update({s: rng.uniform(-3.0, 3.0) for s in angles})
        return point

    def at(point: dict[sp.Symbol, float]) -> tuple[complex, complex]:
        return complex(a.xreplace(point).evalf()), complex(b.xreplace(point).evalf())

    def constant(samples: list[complex]) -> bool:
        return all(abs(s - samples[0]) <= 1e-8 * max(1.0, abs(samples[0])) for s in samples)

    fixed = values()
    same_parameters = [at(values(fixed)) for _ in range(4)]
    everywhere = same_parameters + [at(values()) for _ in range(4)]
    if all(abs(y) > 1e-12 for _, y in everywhere):
        if constant([x / y for x, y in everywhere]):
            return "is off by a constant factor"
        if constant([x / y for x, y in same_parameters]):
            involved = [str(s) for s in others if not constant([
                x / y for x, y in (at({**fixed, s: fixed[s] * scale}) for scale in (1.0, 1.7))])]
            return f"is off by a factor in {', '.join(involved) or 'the parameters'} (one missing or one too many)"
    if constant([x - y for x, y in everywhere]):
        return "is off by a constant term"
    return "has the right symbols but is a different function of them"


def _check_set(answer: Any, expected: Iterable[Any], period: Any, tolerance: float) -> None:
    _no_answer(answer)
    if isinstance(answer, sp.Set) and not isinstance(answer, sp.FiniteSet):
        raise AssertionError(f"give the values one by one, as a set {{a, b, ...}}, not as {type(answer).__name__}")
    given, right = _elements(answer), _elements(expected)
    wrap = None if period is None else float(period)

    def equal(x: Any, y: Any) -> bool:
        x, y = sp.sympify(x), sp.sympify(y)
        if x.free_symbols or y.free_symbols:
            return sp.simplify(x - y) == 0
        distance = abs(float(x) - float(y))
        if wrap is not None:
            distance %= wrap
            distance = min(distance, wrap - distance)
        return distance <= tolerance * max(1.0, abs(float(y)))

    extra = [x for x in given if not any(equal(x, y) for y in right)]
    missing = [y for y in right if not any(equal(x, y) for x in given)]
    if not (extra or missing):
        return
    parts = []
    if missing:
        parts.append(f"misses {len(missing)} value{'s' if len(missing) > 1 else ''}")
    if extra:
        names = ", ".join(sp.sstr(x) for x in extra)
        verb = "is" if len(extra) == 1 else "are"
        parts.append(f"{names} {verb} not one of them" if missing else f"has {names}, which {verb} not a solution")
    raise AssertionError("your set " + ", and ".join(parts))


def _elements(value: Any) -> list[sp.Expr]:
    """The values of a set, list, tuple, array or ``FiniteSet`` (or one value), as SymPy numbers or expressions."""
    values = np.ravel(value) if isinstance(value, np.ndarray) else value
    items = values if isinstance(values, sp.FiniteSet | set | frozenset | list | tuple | np.ndarray) else [values]
    elements = []
    for item in items:
        try:
            element = sp.sympify(item, strict=True)
        except (sp.SympifyError, TypeError):
            element = None
        if not isinstance(element, sp.Expr) or (not element.free_symbols and not element.is_real):
            raise AssertionError(f"{item!r} in your set is not a real number")
        elements.append(element)
    return elements


def _symbols_by_name(robot: Robot | None, expected: sp.Matrix) -> dict[str, sp.Symbol]:
    """Every symbol of the robot and of ``expected`` under its name -> the one symbol of that name to compare with.

    The robot's symbols win over the expected answer's, so every symbol of either side ends up as one symbol.
    """
    canonical: dict[str, sp.Symbol] = {}
    if robot is not None:
        for symbol in (*robot.q, *robot.parameter_symbols):
            canonical.setdefault(symbol.name, symbol)
    for symbol in sorted(expected.free_symbols, key=str):
        if isinstance(symbol, sp.Symbol):
            canonical.setdefault(symbol.name, symbol)
    return canonical


def _renamed(matrix: sp.Matrix, canonical: dict[str, sp.Symbol]) -> sp.Matrix:
    """``matrix`` with each symbol replaced by the canonical symbol of the same name (others unchanged)."""
    return matrix.xreplace({symbol: canonical[symbol.name] for symbol in matrix.free_symbols
                            if isinstance(symbol, sp.Symbol) and symbol.name in canonical})


def _same_function(a: sp.Expr, b: sp.Expr, basis: AngleBasis) -> bool:
    """Whether ``a == b`` identically.

    tan, cot, sec and csc are written with sin and cos, the difference is put over one denominator, and its
    numerator is reduced to the normal form (a fraction is zero where its numerator is).
    """
    numerator, _ = sp.fraction(sp.together(_sines_and_cosines(a) - _sines_and_cosines(b)))
    return is_identity(numerator, sp.S.Zero, basis)


def _sines_and_cosines(expr: sp.Expr) -> sp.Expr:
    return sp.sympify(expr).replace(sp.tan, lambda u: sp.sin(u) / sp.cos(u)).replace(
        sp.cot, lambda u: sp.cos(u) / sp.sin(u)).replace(sp.sec, lambda u: 1 / sp.cos(u)).replace(
        sp.csc, lambda u: 1 / sp.sin(u))


def _as_matrix(value: Any) -> sp.Matrix:
    if isinstance(value, sp.MatrixBase):
        return sp.Matrix(value)
    if isinstance(value, np.ndarray | Sequence) and not isinstance(value, str):
        array = np.asarray(value, dtype=object)
        return sp.Matrix(array.reshape(array.shape[0], -1) if array.ndim else array.reshape(1, 1))
    if isinstance(value, sp.Set | set | frozenset | dict):
        raise AssertionError(f"the answer is a value or a matrix, not a {type(value).__name__}")
    return sp.Matrix([[sp.sympify(value)]])


def _basis(robot: Robot | None, exprs: list[sp.Expr]) -> AngleBasis:
    if robot is not None:
        return AngleBasis.of(joint.variable for joint in robot.joints if joint.is_revolute)
    symbols = set().union(*(sp.sympify(e).free_symbols for e in exprs)) if exprs else set()
    angles = sorted((s for s in symbols if s.name.startswith("theta")), key=lambda s: s.name)
    return AngleBasis.of(angles)

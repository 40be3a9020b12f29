"""Checking students' answers: symbolic answers exactly (any equivalent form is accepted), numbers to a tolerance.

Used by the teaching notebooks; a student writes an answer in any algebraically equivalent form (``-s1*L1 - ...``,
with or without the angle-sum identities applied) and :func:`check` decides whether it is right.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import sympy as sp

from symjac.model.robot import Robot
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.simplify import is_identity

__all__ = ["check"]


def check(answer: Any, expected: Any, robot: Robot | None = None, *, tolerance: float = 1e-9) -> bool:
    """``True`` if ``answer`` equals ``expected``; otherwise an ``AssertionError`` saying which entry differs.

    Symbolic answers (expressions or matrices) are compared exactly as functions of the robot's joint angles (or of
    every symbol named ``theta<i>`` if no robot is given), fractions and tan/cot/sec/csc included; numeric answers
    entry by entry to ``tolerance``. Symbols are matched by name: ``sp.symbols("L2 theta1")`` without assumptions
    stand for the robot's (or the expected answer's) ``L2`` and ``theta1``, whatever assumptions those carry.

    Examples
    --------
    >>> t = sp.Symbol("theta1", real=True)
    >>> check(2 * sp.sin(t) * sp.cos(t), sp.sin(2 * t))
    True
    >>> check(sp.cos(t) / sp.sin(t), sp.cot(t))
    True
    >>> check(sp.sin(sp.Symbol("theta1")), sp.sin(t))  # a plain symbol of the same name is the same quantity
    True
    """
    if answer is Ellipsis or answer is None:
        raise AssertionError("no answer yet: replace the ... with your answer and run the cell again")
    right = _as_matrix(expected)
    names = _symbols_by_name(robot, right)
    right = _renamed(right, names)
    left = _renamed(_as_matrix(answer), names)
    if left.shape != right.shape:
        raise AssertionError(f"the answer has shape {left.shape}, the expected result {right.shape}")
    basis = _basis(robot, [*left, *right])
    for index, (a, b) in enumerate(zip(left, right, strict=True)):
        if a.free_symbols or b.free_symbols:
            same = _same_function(a, b, basis)
        else:
            same = abs(complex(a) - complex(b)) <= tolerance * max(1.0, abs(complex(b)))
        if not same:
            where = f"entry {divmod(index, left.cols)}" if left.shape != (1, 1) else "the answer"
            raise AssertionError(f"{where} is {a}, expected {b}")
    return True


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
    return sp.Matrix([[sp.sympify(value)]])


def _basis(robot: Robot | None, exprs: list[sp.Expr]) -> AngleBasis:
    if robot is not None:
        return AngleBasis.of(joint.variable for joint in robot.joints if joint.is_revolute)
    symbols = set().union(*(sp.sympify(e).free_symbols for e in exprs)) if exprs else set()
    angles = sorted((s for s in symbols if s.name.startswith("theta")), key=lambda s: s.name)
    return AngleBasis.of(angles)

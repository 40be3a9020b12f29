"""Checking students' answers: symbolic answers exactly (any equivalent form is accepted), numbers to a tolerance.

Used by the teaching notebooks; a student writes an answer in any algebraically equivalent form (``-s1*L1 - ...``,
with or without the angle-sum identities applied) and :func:`check` decides whether it is right.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import sympy as sp

from symjac.model import Robot
from symjac.simplify import AngleBasis, is_identity

__all__ = ["check"]


def check(answer: Any, expected: Any, robot: Robot | None = None, *, tolerance: float = 1e-9) -> bool:
    """``True`` if ``answer`` equals ``expected``; otherwise an ``AssertionError`` saying which entry differs.

    Symbolic answers (expressions or matrices) are compared exactly as functions of the robot's joint angles (or of
    every symbol named ``theta<i>`` if no robot is given); numeric answers entry by entry to ``tolerance``.

    Examples
    --------
    >>> t = sp.Symbol("theta1", real=True)
    >>> check(2 * sp.sin(t) * sp.cos(t), sp.sin(2 * t))
    True
    """
    left, right = _as_matrix(answer), _as_matrix(expected)
    if left.shape != right.shape:
        raise AssertionError(f"the answer has shape {left.shape}, the expected result {right.shape}")
    basis = _basis(robot, [*left, *right])
    for index, (a, b) in enumerate(zip(left, right, strict=True)):
        if a.free_symbols or b.free_symbols:
            same = is_identity(a, b, basis)
        else:
            same = abs(complex(a) - complex(b)) <= tolerance * max(1.0, abs(complex(b)))
        if not same:
            where = f"entry {divmod(index, left.cols)}" if left.shape != (1, 1) else "the answer"
            raise AssertionError(f"{where} is {a}, expected {b}")
    return True


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

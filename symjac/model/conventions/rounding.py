r"""What a robot file's rounded decimals may be off by: unit screw axes and zero pitch, to the file's precision.

A calibrated product-of-exponentials file writes each screw :math:`(\omega, v)` to a few decimals. Rounding each
entry by at most :math:`\epsilon/2` moves :math:`|\omega|` from 1 by at most :math:`\tfrac{\epsilon}{2}\sqrt{3}` and
the pitch :math:`\omega \cdot v` of a revolute screw (zero exactly) by at most

.. math:: |\delta\omega \cdot v| + |\omega \cdot \delta v| \le \tfrac{\epsilon}{2}\sqrt{3}\,(1 + |v|)

so with :data:`ROUNDING` :math:`= 10^{-5}` every file written with 5 decimals or more passes (6 decimals:
:math:`8.7 \cdot 10^{-7} (1 + |v|)`), while a mistaken axis ([1, 1, 0]) or a real pitch (a helical joint's
millimetres per radian) is refused. A numeric axis within that tolerance is normalised: exactly when the result
is short (``[0, 0.707107, 0.707107]`` is :math:`(0, \sqrt{2}/2, \sqrt{2}/2)`), else to double precision, since
long radicals such as :math:`\sqrt{1000000972549}` only make every later product cost more.
"""

from __future__ import annotations

import math
import random
from collections.abc import Sequence
from typing import TypeAlias

import sympy as sp

from symjac.model.conventions.base import JointReader
from symjac.model.expressions import exact_number, expression_text
from symjac.model.robot import unit_vector

__all__ = ["ROUNDING", "is_zero", "short", "unit", "zero_pitch"]

Vector: TypeAlias = tuple[sp.Expr, sp.Expr, sp.Expr]

ROUNDING = 1e-5
r"""Relative error a file's numbers may carry: a unit length within it of 1, a pitch within it times :math:`1 + |v|`."""
_SIMPLIFY_OPS = 40
"""The longest expression of parameters (in operations) that validation simplifies exactly."""
_SHORT_EXACT = 40
"""The longest text of an exactly normalised entry that is kept (``sqrt(2)/2``); longer ones go to floats."""


def short(values: Sequence[sp.Expr] | sp.Expr) -> str:
    """Numbers as short decimals (``-0.000749``), never as radicals; expressions of parameters as they are."""
    if isinstance(values, Sequence):
        return "[" + ", ".join(short(e) for e in values) + "]"
    expr = sp.sympify(values)
    return f"{float(expr):.6g}" if not expr.free_symbols else str(expr)


def is_zero(expr: sp.Expr, tolerance: float = ROUNDING) -> bool:
    """Whether ``expr`` is zero: identically when it holds parameters, to ``tolerance`` when it is a number.

    An expression of parameters is simplified when it is short; a longer one (which simplification could take
    minutes over) is taken to be zero when it vanishes to 1e-12 at five random values of its parameters.
    """
    if not expr.free_symbols:
        return abs(float(expr)) <= tolerance
    if sp.count_ops(expr) <= _SIMPLIFY_OPS:
        return bool(sp.simplify(expr) == 0)
    symbols = sorted(expr.free_symbols, key=str)
    function = sp.lambdify(symbols, expr, modules="math")
    draw = random.Random(0)
    samples = [[draw.uniform(-2.0, 2.0) for _ in symbols] for _ in range(5)]
    try:
        return all(abs(complex(function(*sample))) < 1e-12 for sample in samples)
    except (ArithmeticError, ValueError):
        return False


def unit(vector: Vector, what: str, field: str, reader: JointReader) -> Vector:
    r"""``vector`` checked to have unit length (identically when it holds parameters, to :data:`ROUNDING` else).

    Returned as given when exactly unit; else normalised exactly when that stays short, or to double precision.
    """
    square = sum(e**2 for e in vector)
    if any(e.free_symbols for e in vector):
        if not is_zero(square - 1):
            raise reader.fail(f"{what} must have unit length, and |{list(vector)}|^2 = {sp.simplify(square)} is not "
                              f"identically 1", field)
        return vector
    length = math.sqrt(float(square))
    if abs(length - 1) > ROUNDING:
        raise reader.fail(f"{what} must have unit length, got {short(vector)} of length {length:.6g}", field)
    if square == 1:
        return vector
    rational = all(e.is_Rational for e in vector)
    if abs(length - 1) < 1e-14 and (not rational or max(abs(e.q) for e in vector) > 10**12):
        return vector  # a unit vector written to double precision (a conversion's): exact normalising only bloats it
    exact = unit_vector(vector)
    if any(len(str(expression_text(e))) > _SHORT_EXACT for e in exact):
        return _float_unit(vector, length) if rational else vector
    return exact


def _float_unit(vector: Vector, length: float) -> Vector:
    x, y, z = (exact_number(float(e) / length) for e in vector)
    return x, y, z


def zero_pitch(omega: Vector, v: Vector, reader: JointReader) -> Vector:
    r"""``v`` of a revolute screw checked to be perpendicular to the unit ``omega``, its part along ``omega`` dropped.

    A number's pitch :math:`\omega \cdot v` may be :data:`ROUNDING` :math:`(1 + |v|)` (the file's rounding); one of
    parameters must vanish identically.
    """
    pitch = sum(a * b for a, b in zip(omega, v, strict=True))
    pitch = sp.radsimp(sp.expand(pitch)) if not pitch.has(sp.sin, sp.cos) else pitch
    symbolic = bool(pitch.free_symbols) or any(b.free_symbols for b in v)
    if symbolic:
        zero = is_zero(pitch)
    else:
        size = math.sqrt(sum(float(b) ** 2 for b in v))
        zero = abs(float(pitch)) <= ROUNDING * (1 + size)
    if not zero:
        bound = "" if pitch.free_symbols else f" (more than the rounding {ROUNDING:g} * (1 + |v|) allows)"
        raise reader.fail(f"a revolute screw has v perpendicular to w (zero pitch), got w.v = {short(pitch)}{bound}",
                          "screw")
    if pitch == 0:
        return v
    if symbolic:
        x, y, z = (b - pitch * a for a, b in zip(omega, v, strict=True))  # dropped, as the chain drops it
        return x, y, z
    x, y, z = (exact_number(float(b) - float(pitch) * float(a)) for a, b in zip(omega, v, strict=True))
    return x, y, z  # a file's rounding, dropped in floats: exact, it would only lengthen every later number

r"""Generic geometry: which chains have no textbook form, and their link motions in floating point.

Textbook arms turn their joint axes by multiples of :math:`\pi/2` (or by a symbolic twist): their rotation matrices
are full of zeros and ones, sums of parallel joints become :math:`\theta_{23}`, and the exact normal forms of
:mod:`symjac.symbolic.simplify` are short. A chain whose constant rotations are *generic numbers* (calibrated twists
such as 1.5702 rad, screw axes identified by a calibration, CAD exports) has none of that: written out, its
Jacobian grows exponentially with the joints, and exact arithmetic on its numbers (rationals with long numerators,
square roots from normalised axes) is slower still. Such a chain is derived *nested*
(:class:`~symjac.kinematics.chain.Chain` with ``nested=True``): constants in floating point, every entry of every
partial product named as an :class:`~symjac.symbolic.nested.Intermediate`, no simplification.

A number counts as textbook (:func:`is_textbook_number`) when it is exact, free of trigonometric functions and
small: 0, 1, 1/2, :math:`\sqrt{2}/2`, :math:`\sqrt{3}/2`. The base and tool transforms, used once each, do not make
a chain generic.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from symjac.model.conventions.base import JointForm
from symjac.symbolic.transforms import Motion, homogeneous, rotation

__all__ = ["FLOAT_DIGITS", "is_generic", "is_textbook_number", "numeric_steps"]

FLOAT_DIGITS = 17
"""Significant digits of the floats a nested chain computes with (enough to round-trip a double)."""

_LARGEST_INTEGER = 100
"""The largest integer (numerator, denominator, radicand) a textbook number may hold."""


def is_textbook_number(value: sp.Expr) -> bool:
    """Whether a constant entry of a rotation is exact and small (``sqrt(3)/2``), not generic (``cos(7851/5000)``).

    Examples
    --------
    >>> is_textbook_number(sp.sqrt(2) / 2), is_textbook_number(sp.cos(sp.Rational(7851, 5000)))
    (True, False)
    """
    value = sp.sympify(value)
    if value.has(sp.Float) or any(not isinstance(node, sp.Pow | sp.Mul | sp.Add | sp.Rational | sp.NumberSymbol)
                                  and not node.is_Atom for node in sp.preorder_traversal(value)):
        return False
    integers = [abs(int(n)) for r in value.atoms(sp.Rational) for n in (r.p, r.q)]
    return all(n <= _LARGEST_INTEGER for n in integers) and sp.count_ops(value) <= 6


def _motion_is_textbook(step: Motion | sp.MatrixBase) -> bool:
    if isinstance(step, sp.MatrixBase):
        return all(not entry.is_number or is_textbook_number(entry) for entry in step[:3, :3])
    if step.kind != "R" or step.value.free_symbols:  # a translation, a joint's motion, or a symbolic twist
        return True
    turns = step.value / (sp.pi / 2)
    return bool(turns.is_Integer) or (is_textbook_number(sp.cos(step.value)) and is_textbook_number(sp.sin(step.value)))


def is_generic(forms: Sequence[JointForm]) -> bool:
    """Whether a constant rotation of some link is a generic number (the chain is then derived nested)."""
    return not all(_motion_is_textbook(step) for form in forms for step in (*form.before, *form.after))


def _floats(matrix: sp.MatrixBase) -> sp.Matrix:
    return sp.Matrix(matrix).applyfunc(lambda e: e.evalf(FLOAT_DIGITS) if e.is_number and not e.is_Integer else e)


def numeric_steps(steps: Sequence[Motion | sp.MatrixBase]) -> tuple[Motion | sp.Matrix, ...]:
    """``steps`` with their constants in floating point: constant rotations as 4 x 4 float matrices.

    A joint's own motion (its angle may hold an offset, kept exact inside its sine and cosine) is left as it is; a
    constant translation's length becomes a float, a symbolic one stays a symbol.
    """
    result: list[Motion | sp.Matrix] = []
    for step in steps:
        if isinstance(step, sp.MatrixBase):
            result.append(_floats(step))
        elif step.kind == "R" and not step.value.free_symbols and not _textbook_turn(step.value):
            result.append(_floats(homogeneous(rotation(step.axis, step.value), sp.zeros(3, 1))))
        elif step.kind == "T" and step.value.is_number and not step.value.is_Integer:
            result.append(Motion("T", step.axis, step.value.evalf(FLOAT_DIGITS)))
        else:
            result.append(step)
    return tuple(result)


def _textbook_turn(angle: sp.Expr) -> bool:
    return bool((angle / (sp.pi / 2)).is_Integer)

r"""Textbook shorthand, shared by the LaTeX and pretty printers: which sines and cosines abbreviate, factor order.

A sine or cosine is abbreviated when its argument is a sum of revolute joint variables ``theta{i}`` (all with
coefficient +1): :math:`s_1 = \sin\theta_1`, :math:`c_{23} = \cos(\theta_2 + \theta_3)`; anything else prints in
full. The math keeps ordinary ``sin``/``cos``; only the printers abbreviate.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from decimal import Decimal
from typing import Any

import sympy as sp

__all__ = ["FLOAT_DIGITS", "GREEK", "SUBSCRIPTS", "file_decimal", "readable_float", "shorthand_indices",
           "textbook_factors"]

_JOINT_ANGLE = re.compile(r"theta(\d+)\Z")
_RATE = re.compile(r"(theta|d)d?dot\d+\Z")  # rates and accelerations
GREEK = frozenset({"alpha", "beta", "gamma", "phi", "psi", "vartheta", "eta"})
"""Representation angles that get the shorthand too (:math:`s_{\beta}`)."""
FLOAT_DIGITS = 6
"""Significant digits of a full-precision float printed for people (LaTeX, pretty text, MathML); JSON keeps all."""
SUBSCRIPTS = str.maketrans("0123456789,", "₀₁₂₃₄₅₆₇₈₉\u201a")  # U+201A, a low comma: c₈‚₉‚₁₀


def shorthand_indices(argument: sp.Expr) -> str | None:
    """The subscript of a trig shorthand: ``theta1 + theta2 -> "12"`` (``"8,9,10"`` past 9); ``None`` if none.

    Examples
    --------
    >>> t2, t3 = sp.symbols("theta2 theta3", real=True)
    >>> shorthand_indices(t2 + t3)
    '23'
    >>> shorthand_indices(t2 - t3) is None
    True
    """
    terms = sp.Add.make_args(argument)
    indices = []
    for term in terms:
        match = _JOINT_ANGLE.match(term.name) if isinstance(term, sp.Symbol) else None
        if match is None:
            return None
        indices.append(int(match.group(1)))
    indices.sort()
    separator = "," if any(i > 9 for i in indices) else ""
    return separator.join(str(i) for i in indices)


def _factor_key(factor: sp.Expr, sort_key: Callable[[sp.Basic], Any]) -> tuple[Any, ...]:
    """Textbook order of a product's factors: parameters, cosines, sines (each by joint index), then sums."""
    base = factor.base if isinstance(factor, sp.Pow) else factor
    if isinstance(base, sp.cos | sp.sin):
        indices = shorthand_indices(base.args[0])
        if indices is not None:
            digits = indices.split(",") if "," in indices else list(indices)
            return (1 if isinstance(base, sp.cos) else 2, [int(i) for i in digits], sort_key(factor))
    if isinstance(base, sp.Add):
        return (4, [], sort_key(factor))
    if isinstance(base, sp.Symbol) and _RATE.match(base.name):  # rates last, as in L_1 s_2 \dot\theta_1
        return (3, [], sort_key(factor))
    if isinstance(base, sp.Function):
        return (3, [], sort_key(factor))
    return (0, [], sort_key(factor))


def textbook_factors(product: sp.Expr, sort_key: Callable[[sp.Basic], Any] = sp.default_sort_key
                     ) -> tuple[int, list[sp.Expr]] | None:
    """An integer coefficient and the other factors in textbook order (``c_1 s_{23}``, ``a_2 c_2 (...)``).

    ``None`` for products this ordering does not cover (fractions, negative powers, non-commutative factors),
    which print as SymPy prints them. ``sort_key`` breaks ties as SymPy's ``default_sort_key`` does (a printer
    passes its remembered :class:`symjac.printing.latex.SortKeys`).

    Examples
    --------
    >>> t1, t2, L = sp.symbols("theta1 theta2 L", real=True)
    >>> textbook_factors(-2 * sp.sin(t1 + t2) * sp.cos(t1) * L)
    (-2, [L, cos(theta1), sin(theta1 + theta2)])
    """
    if not isinstance(product, sp.Mul) or not product.is_commutative:
        return None
    coefficient, rest = product.as_coeff_Mul()
    factors = sp.Mul.make_args(rest)
    if not coefficient.is_Integer or any(f.is_Pow and f.exp.is_negative for f in factors):
        return None
    return int(coefficient), sorted(factors, key=lambda factor: _factor_key(factor, sort_key))


def file_decimal(number: sp.Expr) -> str | None:
    """A number read from a decimal in a file, as that decimal: ``89159/1000000 -> "0.089159"``; else ``None``.

    Exact fractions whose denominator divides a power of ten print as decimals (``1/10 -> 0.1``, the math stays
    exact), except halves, quarters, eighths and sixteenths; ``1/2``, ``1/3`` and ``3/16`` stay fractions.

    Examples
    --------
    >>> file_decimal(sp.Rational(89159, 1000000)), file_decimal(sp.Rational(1, 10)), file_decimal(sp.Rational(1, 2))
    ('0.089159', '0.1', None)
    """
    if not isinstance(number, sp.Rational) or number.is_Integer or (number.q <= 16 and number.q % 5):
        return None
    rest = int(number.q)
    for prime in (2, 5):
        while rest % prime == 0:
            rest //= prime
    if rest != 1:
        return None
    return format(Decimal(int(number.p)) / Decimal(int(number.q)), "f")


def readable_float(number: sp.Float) -> sp.Float:
    """``number`` rounded to :data:`FLOAT_DIGITS` significant digits if it carries a double's precision or more.

    Generic geometry (a twist of 1.5702 rad, a calibrated screw axis) gives floats of 15 to 18 digits that nobody
    reads; a number rounded on purpose to fewer digits (``--numeric --digits N``, N < 15) prints as it was rounded.

    Examples
    --------
    >>> readable_float(sp.Float(0.64421768723769105, 18))
    0.644218
    >>> readable_float(sp.Float("0.12345678", 8))
    0.12345678

    A number that would round to a whole number without being one keeps the digits that tell it apart
    (a calibrated cosine, 0.99999982, is not 1):

    >>> readable_float(sp.Float(0.99999982, 18))
    0.9999998
    """
    if number._prec < 53:
        return number
    value, digits = float(number), FLOAT_DIGITS
    while float(f"{value:.{digits}g}").is_integer() and not value.is_integer() and digits < 15:
        digits += 1  # 0.99999982 is not 1: as many digits as tell it apart
    return sp.Float(f"{value:.{digits}g}", digits)

r"""Textbook shorthand, shared by the LaTeX and pretty printers: which sines and cosines abbreviate, factor order.

A sine or cosine is abbreviated when its argument is a sum of revolute joint variables ``theta{i}`` with
coefficients +1 or -1: :math:`s_1 = \sin\theta_1`, :math:`c_{23} = \cos(\theta_2 + \theta_3)`, and for a
difference the subtracted indices follow a minus sign, :math:`c_{2-4} = \cos(\theta_2 - \theta_4)`,
:math:`s_{12-4} = \sin(\theta_1 + \theta_2 - \theta_4)` (a SCARA whose screw points down). The math keeps ordinary
``sin``/``cos``; only the printers abbreviate.

Before printing, :func:`textbook_form` rewrites what the shorthand cannot name into what it can, as a textbook
writes it: the sine or cosine of joint variables plus a numeric constant (a DH offset of :math:`\pi/4`) is expanded by
the angle-sum formulas, :math:`\sin(\theta_2 + \pi/4) = \tfrac{\sqrt{2}}{2}(s_2 + c_2)`, so every trig term of a
joint variable prints as shorthand; and a sum inside a product gives up a common fraction,
:math:`L_2 (c_3/2 - 1/2) = L_2 (c_3 - 1)/2`. Both are identities: the printed result equals the unprinted one.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from decimal import Decimal
from typing import Any

import sympy as sp

__all__ = ["FLOAT_DIGITS", "GREEK", "SUBSCRIPTS", "file_decimal", "readable_float", "shorthand_indices",
           "textbook_factors", "textbook_form"]

_JOINT_ANGLE = re.compile(r"theta(\d+)\Z")
_RATE = re.compile(r"(theta|d)d?dot\d+\Z")  # rates and accelerations
GREEK = frozenset({"alpha", "beta", "gamma", "phi", "psi", "vartheta", "eta"})
"""Representation angles that get the shorthand too (:math:`s_{\beta}`)."""
FLOAT_DIGITS = 6
"""Significant digits of a full-precision float printed for people (LaTeX, pretty text, MathML); JSON keeps all."""
SUBSCRIPTS = str.maketrans("0123456789,-", "₀₁₂₃₄₅₆₇₈₉\u201a\u208b")  # a low comma (c₈‚₉‚₁₀), a low minus (c₂₋₄)


def shorthand_indices(argument: sp.Expr) -> str | None:
    """The subscript of a trig shorthand: ``theta1 + theta2 -> "12"``, ``theta2 - theta4 -> "2-4"``; else ``None``.

    Added indices come first in increasing order, then each subtracted one after a minus sign; past 9 the indices
    are separated by commas (``"8,9,10"``, ``"8,9-10"``). An argument with no added joint variable has none (SymPy
    writes ``cos(-theta1)`` as ``cos(theta1)`` anyway).

    Examples
    --------
    >>> t1, t2, t3 = sp.symbols("theta1 theta2 theta3", real=True)
    >>> shorthand_indices(t2 + t3), shorthand_indices(t1 + t2 - t3), shorthand_indices(2 * t2 + t3) is None
    ('23', '12-3', True)
    """
    added, subtracted = _signed_indices(argument) or ([], [])
    if not added:
        return None
    separator = "," if any(i > 9 for i in added + subtracted) else ""
    return separator.join(str(i) for i in added) + "".join(f"-{i}" for i in subtracted)


def _signed_indices(argument: sp.Expr) -> tuple[list[int], list[int]] | None:
    """The joint indices added and subtracted in ``argument`` (each sorted); ``None`` if it is not such a sum."""
    added: list[int] = []
    subtracted: list[int] = []
    for term in sp.Add.make_args(argument):
        sign, variable = (-1, -term) if term.could_extract_minus_sign() else (1, term)
        match = _JOINT_ANGLE.match(variable.name) if isinstance(variable, sp.Symbol) else None
        if match is None:
            return None
        (added if sign > 0 else subtracted).append(int(match.group(1)))
    return sorted(added), sorted(subtracted)


def _factor_key(factor: sp.Expr, sort_key: Callable[[sp.Basic], Any]) -> tuple[Any, ...]:
    """Textbook order of a product's factors: parameters, cosines, sines (each by joint index), then sums."""
    base = factor.base if isinstance(factor, sp.Pow) else factor
    if isinstance(base, sp.cos | sp.sin):
        signed = _signed_indices(base.args[0])
        if signed is not None and signed[0]:
            return (1 if isinstance(base, sp.cos) else 2, signed[0] + [-i for i in signed[1]], sort_key(factor))
    if isinstance(base, sp.Add):
        return (4, [], sort_key(factor))
    if isinstance(base, sp.Symbol) and _RATE.match(base.name):  # rates last, as in L_1 s_2 \dot\theta_1
        return (3, [], sort_key(factor))
    if isinstance(base, sp.Function):
        return (3, [], sort_key(factor))
    return (0, [], sort_key(factor))


def textbook_form(expr: Any, memo: dict[sp.Basic, sp.Basic] | None = None) -> Any:
    r"""``expr`` (or each entry of a matrix) rewritten so that every sine and cosine of joint variables is shorthand.

    * ``sin(A + k)`` and ``cos(A + k)``, with ``A`` a sum or difference of joint variables and ``k`` a number, are
      expanded, :math:`\sin(A + k) = \cos k \sin A + \sin k \cos A`, their common factor taken out
      (:math:`\sin(\theta_2 + \pi/4) = \tfrac{\sqrt{2}}{2}(s_2 + c_2)`), as a textbook writes an offset that
      SymPy leaves inside the function (:math:`\pi/2` it already turns into :math:`c_2`);
    * a sum that is a factor of a product gives its common fraction to the product's coefficient
      (:math:`\sqrt{2}(s_6/2 + c_6/2) = \tfrac{\sqrt{2}}{2}(s_6 + c_6)`).

    Both are identities: the result equals ``expr``. ``memo`` (a printer's) remembers rewritten subexpressions
    across calls.

    Examples
    --------
    >>> t2, t3, L = sp.symbols("theta2 theta3 L", real=True)
    >>> textbook_form(sp.sin(t2 + sp.pi / 4))
    sqrt(2)*(sin(theta2) + cos(theta2))/2
    >>> textbook_form(L * (sp.cos(t3) / 2 - sp.Rational(1, 2)))
    L*(cos(theta3) - 1)/2
    """
    memo = {} if memo is None else memo
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(lambda entry: textbook_form(entry, memo))
    if not isinstance(expr, sp.Basic) or isinstance(expr, sp.Atom):
        return expr
    result = _rewrite(expr, memo)
    part, rest = _common_fraction(result) if isinstance(result, sp.Add) else (sp.S.One, result)
    return result if part == 1 else sp.Mul(part, rest, evaluate=False)  # (s_6 + c_6)/2, kept from distributing


def _rewrite(expr: sp.Basic, memo: dict[sp.Basic, sp.Basic]) -> sp.Basic:
    """:func:`textbook_form` of one expression, each distinct subexpression rewritten once."""
    if expr.is_Atom or not expr.args:
        return expr
    done = memo.get(expr)
    if done is not None:
        return done
    args = [_rewrite(arg, memo) for arg in expr.args]
    result = expr.func(*args) if args != list(expr.args) else expr
    if isinstance(result, sp.sin | sp.cos):
        result = _expanded_offset(result)
    elif isinstance(result, sp.Mul):
        result = _fraction_out(result)
    memo[expr] = result
    return result


def _expanded_offset(function: sp.Expr) -> sp.Expr:
    """``sin(A + k)``/``cos(A + k)`` by the angle-sum formula when ``A`` is shorthand and ``k`` a nonzero number."""
    numbers, angles = sp.sift(sp.Add.make_args(function.args[0]), lambda term: term.is_number, binary=True)
    angle = sp.Add(*angles)
    if not numbers or not angles or (shorthand_indices(angle) is None and shorthand_indices(-angle) is None):
        return function  # pi/4 - theta2 expands too: sin(-theta2) is -s_2
    offset = sp.Add(*numbers)
    if isinstance(function, sp.sin):
        expanded = sp.cos(offset) * sp.sin(angle) + sp.sin(offset) * sp.cos(angle)
    else:
        expanded = sp.cos(offset) * sp.cos(angle) - sp.sin(offset) * sp.sin(angle)
    return _fraction_out(sp.factor_terms(expanded)) if expanded.is_Add else expanded


def _fraction_out(product: sp.Expr) -> sp.Expr:
    """A product whose sums give up their common fraction: ``L (c/2 - 1/2) -> L (c - 1) / 2``."""
    if not isinstance(product, sp.Mul) or not product.is_commutative:
        return product
    content, factors = sp.S.One, []
    for factor in product.args:
        part, factor = _common_fraction(factor) if factor.is_Add else (sp.S.One, factor)
        content *= part
        factors.append(factor)
    if content == 1:
        return product
    rebuilt = sp.Mul(content, *factors)
    return rebuilt if rebuilt.is_Mul else product  # a number times one sum distributes again: left as it was


def _common_fraction(total: sp.Add) -> tuple[sp.Expr, sp.Expr]:
    """``(1/q, q * total)`` if each term is ``±1/q`` times the rest (``c/2 - 1/2``), else ``(1, total)``."""
    part, rest = total.primitive()
    if part.q == 1 or any(abs(term.as_coeff_Mul()[0]) != 1 for term in sp.Add.make_args(rest)):
        return sp.S.One, total
    return part, rest


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

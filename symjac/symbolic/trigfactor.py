r"""Determinants and factorisations in the polynomial image, in final textbook form.

Three steps turn a matrix of normal forms (:mod:`symjac.symbolic.trigpoly`) into a factored determinant a person can
read:

1. :func:`determinant_image`: the determinant by cofactor expansion along the rows,
   :math:`\det A_{[i:], C} = \sum_{k} (-1)^{k} a_{i, c_k} \det A_{[i+1:], C \setminus c_k}`, every product reduced
   modulo :math:`S_j^2 + C_j^2 - 1` at once. Each sub-determinant of the lower rows is computed once per set of
   columns (at most :math:`2^n` of them rather than :math:`n!` products), and the minors of a redundant arm's
   Jacobian share them. Reducing as it goes keeps the polynomials small; a fraction-free elimination cannot reduce
   (it divides exactly) and spent 26 s on the Panda's seven minors, which this does in 0.05 s.
2. :func:`trig_factor_list`: irreducible factors of the normal form, then of each factor once more after rewriting
   :math:`C_j^2 = 1 - S_j^2` for one angle (the normal form keeps sines of degree one, so
   :math:`s_3 (a c_3 + b s_3)` reads :math:`a s_3 c_3 + b - b c_3^2` there and only splits after that rewriting),
   and the pairs :math:`(c_j - 1)(c_j + 1)` and :math:`(s_j - 1)(s_j + 1)` gathered into :math:`-s_j^2` and
   :math:`-c_j^2`.
3. :func:`compact_expr`: each factor laid out nested with, per angle, sines or cosines of degree at most one,
   whichever prints shorter, and what pairs remain inside the parentheses written out (:math:`-a_6 s_5^2` rather
   than :math:`a_6 (c_5^2 - 1)`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import sympy as sp
from sympy.polys.rings import PolyElement

from symjac.symbolic.layout import nested_expr
from symjac.symbolic.simplify import printed_ops
from symjac.symbolic.trigpoly import TrigImage, reduce_image

__all__ = ["FACTOR_UNREDUCED_TERMS", "SPLIT_TERMS", "compact_expr", "determinant_image", "rewrite_square",
           "trig_factor_list"]

FACTOR_UNREDUCED_TERMS = 150
"""Largest determinant (in terms) factored before reduction, where products such as (c - 1)(c + 1) still show."""
SPLIT_TERMS = 24
"""Largest factor (in terms) tried for a split by grouping terms."""


def determinant_image(matrix: Sequence[Sequence[PolyElement]], image: TrigImage,
                      columns: Sequence[int] | None = None, *, reduced: bool = True) -> PolyElement:
    r"""The determinant of the square submatrix of ``matrix`` on ``columns`` (default all).

    ``reduced=False`` skips the reduction of the products: the result is then the determinant as a polynomial in the
    generators, which keeps products of factors visible (see :func:`trig_factor_list`) but grows faster.

    Examples
    --------
    >>> from symjac.symbolic.angles import AngleBasis
    >>> from symjac.symbolic.layout import expanded_expr
    >>> from symjac.symbolic.trigpoly import image_of
    >>> t = sp.Symbol("theta1", real=True)
    >>> image, p = image_of([sp.cos(t), -sp.sin(t), sp.sin(t), sp.cos(t)], AngleBasis.of([t]))
    >>> expanded_expr(determinant_image([p[:2], p[2:]], image), image)
    1
    """
    rows = len(matrix)
    chosen = tuple(range(len(matrix[0]))) if columns is None else tuple(columns)
    if len(chosen) != rows:
        raise ValueError(f"a determinant needs as many columns as rows ({rows}), got {len(chosen)}")
    polynomial_ring = image.ring_and_gens[0]
    table: dict[tuple[int, ...], PolyElement] = {}

    def minor(cols: tuple[int, ...]) -> PolyElement:
        if not cols:
            return polynomial_ring.one
        if cols not in table:
            row = matrix[rows - len(cols)]
            total = polynomial_ring.zero
            for position, column in enumerate(cols):
                if row[column]:
                    rest = minor(cols[:position] + cols[position + 1:])
                    if rest:
                        term = row[column] * rest
                        term = reduce_image(term, image) if reduced else term
                        total = total - term if position % 2 else total + term
            table[cols] = total
        return table[cols]

    return minor(chosen)


def rewrite_square(poly: PolyElement, square: int, other: int) -> PolyElement:
    r"""``poly`` with every power of generator ``square`` reduced by :math:`x^2 = 1 - y^2` (``y`` the ``other``).

    With ``square`` a cosine :math:`C_j` and ``other`` its sine, this is the normal form that keeps cosines of
    degree one instead of sines.
    """
    terms: dict[tuple[int, ...], Any] = {}
    for monomial, coefficient in poly.iterterms():
        k, rest = divmod(monomial[square], 2)
        for m in range(k + 1):
            exponents = list(monomial)
            exponents[square] = rest
            exponents[other] += 2 * m
            key = tuple(exponents)
            terms[key] = terms.get(key, 0) + coefficient * (-1) ** m * math.comb(k, m)
    return poly.ring.from_dict({m: c for m, c in terms.items() if c})


def _angles_of(poly: PolyElement, image: TrigImage) -> list[int]:
    """The angles whose sine or cosine occurs in ``poly``."""
    degrees = poly.degrees()
    return [j for j in range(image.angle_count) if degrees[2 * j] or degrees[2 * j + 1]]


def _rewritings(poly: PolyElement, image: TrigImage) -> list[PolyElement]:
    """``poly`` with one angle's squares rewritten (cosines, then sines, reduced), each form that differs."""
    forms = []
    degrees = poly.degrees()
    for j in _angles_of(poly, image):
        s, c = 2 * j, 2 * j + 1
        if degrees[c] >= 2:
            forms.append(rewrite_square(poly, c, s))
        if degrees[s] >= 2:
            forms.append(rewrite_square(poly, s, c))
    return forms


def _split(poly: PolyElement, image: TrigImage) -> tuple[Any, list[tuple[PolyElement, int]]]:
    """Irreducible factors of ``poly`` as a function of the angles (one rewriting per level, recursively).

    Factors over :data:`SPLIT_TERMS` terms are left whole: factoring their rewritten forms took from seconds to
    minutes on the Panda's minors (Wang's algorithm), and no factor that large was seen to split.
    """
    if len(poly) > SPLIT_TERMS:
        return poly.ring.domain.one, [(poly, 1)]
    for form in _rewritings(poly, image):
        constant, factors = form.factor_list()
        if sum(multiplicity for _, multiplicity in factors) > 1:
            return _split_each(constant, factors, image)
    return poly.ring.domain.one, [(poly, 1)]


def _split_each(constant: Any, factors: list[tuple[PolyElement, int]],
                image: TrigImage) -> tuple[Any, list[tuple[PolyElement, int]]]:
    """Every factor split by :func:`_split`, multiplicities multiplied and constants gathered into ``constant``."""
    parts: list[tuple[PolyElement, int]] = []
    for factor, multiplicity in factors:
        inner, pieces = _split(factor, image)
        constant *= inner**multiplicity
        parts.extend((piece, m * multiplicity) for piece, m in pieces)
    return constant, parts


def trig_factor_list(poly: PolyElement, image: TrigImage) -> tuple[sp.Rational, list[tuple[PolyElement, int]]]:
    r"""A constant and the factors of ``poly`` as a function of the angles, with their multiplicities.

    ``poly`` need not be reduced. A small one (up to :data:`FACTOR_UNREDUCED_TERMS` terms) is factored as it is
    first: products of factors that mix :math:`c_j^2` and :math:`s_j^2` (:math:`(a (c_4 - 1) + b s_4)(a c_4 + b
    s_4)`) only show there, since no normal form of the product splits. Then every factor is reduced and factored
    again, also after rewriting one angle's squares (see the module docstring), and :math:`(c_j - 1)(c_j + 1)` comes
    back as :math:`-s_j^2`. Equal factors are merged. The product equals ``poly`` modulo :math:`S_j^2 + C_j^2 - 1`.
    A ``poly`` that reduces to zero is the caller's to catch.

    Examples
    --------
    >>> from symjac.symbolic.angles import AngleBasis
    >>> from symjac.symbolic.trigpoly import image_of
    >>> t = sp.Symbol("theta3", real=True)
    >>> a, b = sp.symbols("a b")
    >>> image, (p,) = image_of([sp.sin(t) * (a * sp.cos(t) + b * sp.sin(t))], AngleBasis.of([t]))
    >>> c, factors = trig_factor_list(p, image)
    >>> c, [(nested_expr(f, image), m) for f, m in factors]
    (1, [(sin(theta3), 1), (a*cos(theta3) + b*sin(theta3), 1)])
    """
    # multivariate factoring of a large unreduced polynomial can take minutes (the Panda's minors have up to 406
    # terms, 47 once reduced): there the reduced one is factored instead.
    if len(poly) > FACTOR_UNREDUCED_TERMS:
        poly = reduce_image(poly, image)
    constant, raw = poly.factor_list()
    collected: dict[PolyElement, int] = {}
    for unreduced, multiplicity in raw:
        inner, pieces = _reduced_factors(reduce_image(unreduced, image), image)
        constant *= inner**multiplicity
        for piece, m in pieces:
            piece, sign = _normalised(piece)
            constant *= sign ** (m * multiplicity)
            collected[piece] = collected.get(piece, 0) + m * multiplicity
    constant *= _pair_unit_factors(collected, image)
    return sp.Rational(int(constant.numerator), int(constant.denominator)), sorted(
        collected.items(), key=lambda item: (len(item[0]), item[0].LM))


def _reduced_factors(poly: PolyElement, image: TrigImage) -> tuple[Any, list[tuple[PolyElement, int]]]:
    """The factors of a reduced polynomial, each split further by :func:`_split` (a constant has none)."""
    if poly.is_ground:
        return poly.LC, []
    constant, factors = poly.factor_list()
    return _split_each(constant, factors, image)


def _normalised(poly: PolyElement) -> tuple[PolyElement, int]:
    """``poly`` with a positive leading coefficient, and the sign taken out."""
    return (-poly, -1) if poly.LC < 0 else (poly, 1)


def _pair_unit_factors(collected: dict[PolyElement, int], image: TrigImage) -> int:
    """Merge (x - 1)^m (x + 1)^m into (-1)^m y^{2m} for x, y a cosine and its sine (or the reverse); the sign."""
    sign = 1
    for j in range(image.angle_count):
        for x, y in ((image.cosine(j), image.sine(j)), (image.sine(j), image.cosine(j))):
            low, high = x - 1, x + 1
            m = min(collected.get(low, 0), collected.get(high, 0))
            if m:
                for factor in (low, high):
                    collected[factor] -= m
                    if not collected[factor]:
                        del collected[factor]
                collected[y] = collected.get(y, 0) + 2 * m
                sign *= (-1) ** m
    return sign


def compact_expr(poly: PolyElement, image: TrigImage) -> sp.Expr:
    """``poly`` laid out nested, choosing per angle sines or cosines of degree one, whichever prints shorter."""
    poly = reduce_image(poly, image)
    best = nested_expr(poly, image)
    best_ops = printed_ops(best)
    for j in _angles_of(poly, image):
        if poly.degrees()[2 * j + 1] < 2:
            continue
        candidate = rewrite_square(poly, 2 * j + 1, 2 * j)
        expr = nested_expr(candidate, image)
        ops = printed_ops(expr)
        if ops < best_ops:
            poly, best, best_ops = candidate, expr, ops
    return best.replace(lambda node: isinstance(node, sp.Add), _pythagoras)


def _pythagoras(total: sp.Add) -> sp.Expr:
    r"""One nested sum with the squares of one angle paired off: :math:`a c^2 - a = -a s^2`, and so on.

    Also :math:`a s^2 - a = -a c^2` and :math:`a s^2 + a c^2 = a`. The nesting leaves such pairs inside parentheses
    when no single choice of sines or cosines per angle suits the whole factor.
    """
    terms = dict(total.as_coefficients_dict())
    for term in list(terms):
        if not (isinstance(term, sp.Pow) and term.exp == 2 and isinstance(term.base, sp.sin | sp.cos)):
            continue
        if term not in terms:
            continue
        a, angle = terms[term], term.base.args[0]
        other = (sp.cos if isinstance(term.base, sp.sin) else sp.sin)(angle) ** 2
        if terms.get(other) == a:  # a s^2 + a c^2 = a
            del terms[term], terms[other]
            terms[sp.S.One] = terms.get(sp.S.One, 0) + a
        elif terms.get(sp.S.One) == -a:  # a c^2 - a = -a s^2 (and the same with s and c exchanged)
            del terms[term], terms[sp.S.One]
            terms[other] = terms.get(other, 0) - a
    rewritten = sp.Add(*[coefficient * term for term, coefficient in terms.items() if coefficient != 0])
    return rewritten if rewritten != total else total

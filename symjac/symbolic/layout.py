r"""Normal forms laid out for people: a plain sum of monomials, or nested by greedy multivariate Horner.

:func:`nested_expr` factors out the generator shared by most terms and recurses on both parts, so
:math:`c_1 c_2 x + c_1 s_2 y + z` becomes :math:`c_1 (c_2 x + s_2 y) + z`. A factored sum that SymPy reads with a
leading minus is shown as :math:`-c_1 (x - y)` rather than :math:`c_1 (y - x)`.

Laying out is most of the time of a large derivation (the Coriolis matrix and the Newton-Euler torques of a 7-joint
arm with symbolic inertias: 10 of 15 s each, measured), so the layout keeps SymPy's work to building the result:

- each sum knows whether SymPy reads it as negative without asking SymPy. SymPy's rule
  (``Add.could_extract_minus_sign``) is: more terms with a leading minus than without; on a tie, the first term in
  SymPy's term order has a negative coefficient. SymPy answers the tie by sorting the sum and its negation and
  comparing their sort keys. The sign of the first term in the sum's own term order gives the same answer, as the
  order does not depend on coefficients, except that SymPy puts a positive number first in ``1 - x``: there, and
  where a generator is a number (``sin(pi/7)``, ``sqrt(2)``, which SymPy's order counts as coefficients), SymPy is
  asked;
- sub-sums met again (the same factor of several entries, the same group in several links) are laid out once per
  image (:attr:`TrigImage.layouts`).

Where a generator is itself a negative expression SymPy rewrites (``sin(-x)`` is ``-sin(x)``), the signs are asked
of SymPy, as before. The result is the same expression either way; ``tests/test_layout.py`` compares this with the
plain algorithm on random polynomials.
"""

from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.polys.rings import PolyElement

from symjac.symbolic.trigpoly import TrigImage

__all__ = ["expanded_expr", "nested_expr"]

Sparse = dict[int, int]  # a monomial as {generator index: exponent}, exponents positive
Laid = tuple[sp.Expr, bool]  # an expression and whether SymPy reads it with a leading minus
MEMO_TERMS = 8


def _coefficient_expr(coefficient: Any) -> sp.Rational:
    return sp.Rational(int(coefficient.numerator), int(coefficient.denominator))


def expanded_expr(poly: PolyElement, image: TrigImage) -> sp.Expr:
    """A polynomial of the image as a SymPy sum of monomials."""
    return sp.Add(*[_coefficient_expr(c) * sp.Mul(*[image.back(i) ** e for i, e in enumerate(m) if e])
                    for m, c in poly.terms()])


def nested_expr(poly: PolyElement, image: TrigImage) -> sp.Expr:
    """A polynomial of the image as a nested SymPy sum (greedy Horner, module docstring)."""
    sparse = [({i: e for i, e in enumerate(m) if e}, c) for m, c in poly.terms()]
    exact = not all(_plain(image.back(i)) for i in set().union(*(m for m, _ in sparse)))
    return _Nesting(image, exact).nest(sparse)[0]


def _plain(generator: sp.Expr) -> bool:
    """A generator SymPy multiplies without moving signs: a symbol, a function (sin, cos) or a power of one."""
    base = generator.base if isinstance(generator, sp.Pow) else generator
    return (isinstance(base, sp.Symbol | sp.Function) and not generator.is_number
            and not generator.could_extract_minus_sign())


class _Nesting:
    """One layout: the image, its memo, and whether signs are asked of SymPy (``exact``, unusual generators)."""

    def __init__(self, image: TrigImage, exact: bool):
        self.image = image
        self.exact = exact
        self.memo: dict[Any, Laid] = image.layouts.setdefault("nested exact" if exact else "nested", {})

    def term(self, monomial: Sparse, coefficient: Any) -> Laid:
        expr = sp.Mul(_coefficient_expr(coefficient), *[self.image.back(i) ** e for i, e in sorted(monomial.items())])
        return expr, (expr.could_extract_minus_sign() if self.exact else coefficient < 0)

    def total(self, summands: list[Laid]) -> Laid:
        if len(summands) <= 1:
            return summands[0] if summands else (sp.S.Zero, False)
        expr = sp.Add(*[s for s, _ in summands])
        if self.exact:
            return expr, expr.could_extract_minus_sign()
        negatives = sum(negative for _, negative in summands)
        if 2 * negatives != len(summands):
            return expr, 2 * negatives > len(summands)
        if expr.args[0].is_Number:  # SymPy orders 1 - x and x - 1 by hand: ask it
            return expr, expr.could_extract_minus_sign()
        return expr, bool(expr.as_ordered_terms()[0].as_coeff_Mul()[0] < 0)

    def nest(self, terms: list[tuple[Sparse, Any]]) -> Laid:
        """Factor out the generator shared by most terms, recurse on the terms that have it, loop on the rest.

        The parts outside each factored generator are collected and summed once at the end rather than added to the
        sum of the rest one by one (which re-sorted that growing sum at every step).
        """
        key = frozenset((frozenset(m.items()), c) for m, c in terms) if len(terms) <= MEMO_TERMS else None
        if key in self.memo:
            return self.memo[key]
        summands: list[Laid] = []
        while terms:
            counts: dict[int, int] = {}
            for monomial, _ in terms:
                for i in monomial:
                    counts[i] = counts.get(i, 0) + 1
            best = max(counts, key=lambda i: (counts[i], -i), default=None)
            if len(terms) <= 1 or best is None or counts[best] < 2:
                summands += [self.term(m, c) for m, c in terms]
                break
            inside: list[tuple[Sparse, Any]] = []
            outside: list[tuple[Sparse, Any]] = []
            for monomial, coefficient in terms:
                if best in monomial:
                    reduced = dict(monomial)
                    if reduced[best] > 1:
                        reduced[best] -= 1
                    else:
                        del reduced[best]
                    inside.append((reduced, coefficient))
                else:
                    outside.append((monomial, coefficient))
            summands.append(self.product(self.image.back(best), self.nest(inside)))
            terms = outside
        laid = self.total(summands)
        if key is not None:
            self.memo[key] = laid
        return laid

    def product(self, factor: sp.Expr, inner: Laid) -> Laid:
        """``factor * inner``, a leading minus kept outside the parentheses: -c1*(x + y) rather than c1*(-x - y)."""
        expr, negative = inner
        flipped = isinstance(expr, sp.Add) and negative
        product = sp.Mul(sp.S.NegativeOne, factor, -expr) if flipped else factor * expr
        return product, (product.could_extract_minus_sign() if self.exact else negative)

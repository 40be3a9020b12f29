"""The nested layout equals the plain greedy Horner algorithm that asks SymPy for every sign, expression for expression.

:mod:`symjac.symbolic.layout` decides signs without SymPy and reuses sub-sums; here the algorithm is written the
plain way (each sign from ``could_extract_minus_sign``, nothing reused) and both lay out the same polynomials: random
ones over sines, cosines and parameters (with ties between positive and negative terms, the case SymPy settles by
sorting), one with numeric generators (``sin(pi/7)``), and the Newton-Euler torques of a 4-joint arm.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symjac import load_robot
from symjac.analysis.dynamics.gravity import Gravity
from symjac.analysis.dynamics.polynomial import polynomial_recursion
from symjac.kinematics.chain import Chain
from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.layout import nested_expr
from symjac.symbolic.trigpoly import TrigImage, image_of, reduce_image


def plain_nested(poly: Any, image: TrigImage) -> sp.Expr:
    """Greedy multivariate Horner, every sign asked of SymPy."""

    def nest(terms: list[tuple[dict[int, int], Any]]) -> sp.Expr:
        summands = []
        while terms:
            counts: dict[int, int] = {}
            for monomial, _ in terms:
                for i in monomial:
                    counts[i] = counts.get(i, 0) + 1
            best = max(counts, key=lambda i: (counts[i], -i), default=None)
            if len(terms) <= 1 or best is None or counts[best] < 2:
                summands += [sp.Rational(int(c.numerator), int(c.denominator))
                             * sp.Mul(*[image.back(i) ** e for i, e in sorted(m.items())]) for m, c in terms]
                break
            inside = [({**m, best: m[best] - 1} if m[best] > 1 else {i: e for i, e in m.items() if i != best}, c)
                      for m, c in terms if best in m]
            terms = [(m, c) for m, c in terms if best not in m]
            inner, factor = nest(inside), image.back(best)
            negated = isinstance(inner, sp.Add) and inner.could_extract_minus_sign()
            summands.append(-(factor * (-inner)) if negated else factor * inner)
        return sp.Add(*summands)

    return nest([({i: e for i, e in enumerate(m) if e}, c) for m, c in poly.terms()])


t1, t2, t3 = sp.symbols("theta1:4", real=True)
a, b, d = sp.symbols("a b d", real=True)
PIECES = [sp.sin(t1), sp.cos(t1), sp.sin(t2), sp.cos(t2), sp.sin(t1 + t2), sp.cos(t3), a, b, d, sp.Integer(1)]


@st.composite
def trig_polynomials(draw: st.DrawFn) -> sp.Expr:
    """Sums of up to 12 products of up to 4 pieces, coefficients small integers of either sign (many ties)."""
    products = st.lists(st.sampled_from(PIECES), min_size=1, max_size=4)
    terms = draw(st.lists(st.tuples(st.sampled_from([-3, -2, -1, 1, 2, 5]), products), min_size=1, max_size=12))
    return sp.Add(*[c * sp.Mul(*factors) for c, factors in terms])


@settings(max_examples=400, deadline=None)
@given(st.lists(trig_polynomials(), min_size=1, max_size=3))
def test_random_polynomials_lay_out_as_the_plain_algorithm(exprs: list[sp.Expr]) -> None:
    image, polys = image_of(exprs, AngleBasis.of([t1, t2, t3]))
    for poly in polys:
        poly = reduce_image(poly, image)
        assert nested_expr(poly, image) == plain_nested(poly, image)


def test_numeric_generators_lay_out_as_the_plain_algorithm() -> None:
    """sin(pi/7) and cos(pi/7) are numbers to SymPy's term order: the layout asks SymPy for those signs."""
    expr = sp.sin(t1 + sp.pi / 7) * (a * sp.cos(t1) - b * sp.sin(t2 - sp.pi / 7) + d) - sp.cos(t2) * a + b - d
    image, (poly,) = image_of([expr], AngleBasis.of([t1, t2]))
    assert any(generator.is_number for generator in map(image.back, range(2 * image.angle_count)))
    assert nested_expr(poly, image) == plain_nested(poly, image)


def test_newton_euler_torques_lay_out_as_the_plain_algorithm() -> None:
    whole = load_robot("iiwa7")
    arm = dataclasses.replace(whole, joints=whole.joints[:4], tool=None, inertials=whole.inertials[:4])
    chain = Chain(arm)
    rates = sp.symbols("qd1:5", real=True)
    accelerations = sp.symbols("qdd1:5", real=True)
    steps = polynomial_recursion(chain, rates, accelerations, Gravity().vector)
    for torque in steps.torques:
        assert nested_expr(torque, steps.image) == plain_nested(torque, steps.image)

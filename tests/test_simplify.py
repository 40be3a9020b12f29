"""The simplifier's normal form: unique (equal functions give equal results), exact, and compact."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from symjac.symbolic.angles import AngleBasis
from symjac.symbolic.simplify import is_identity, simplify_expr, trig_normal_form

t1, t2, t3 = sp.symbols("theta1 theta2 theta3", real=True)
L1, L2, beta = sp.symbols("L1 L2 beta", real=True)
BASIS = AngleBasis((t1, t2, t3), (t1, t1 + t2, t1 + t2 + t3))


def test_pythagoras_of_a_constant_angle_reduces_to_one():
    # a regression: a numeric twist (0.3 rad) left sin(3/10)**2 + cos(3/10)**2 in one method's result
    c = sp.Rational(3, 10)
    assert trig_normal_form(sp.sin(c) ** 2 + sp.cos(c) ** 2, BASIS) == 1
    assert is_identity(sp.sin(t1 + c) ** 2, 1 - sp.cos(t1 + c) ** 2, BASIS)


def test_parameter_angles_obey_pythagoras_and_the_addition_formula():
    assert trig_normal_form(sp.sin(beta) ** 2 + sp.cos(beta) ** 2, BASIS) == 1
    expanded = sp.cos(beta) * sp.cos(sp.Rational(1, 5)) - sp.sin(beta) * sp.sin(sp.Rational(1, 5))
    assert is_identity(sp.cos(beta + sp.Rational(1, 5)), expanded, BASIS)
    assert is_identity(sp.sin(t1 - beta), sp.sin(t1) * sp.cos(beta) - sp.cos(t1) * sp.sin(beta), BASIS)


def test_special_angles_become_radicals_with_their_squares_reduced():
    assert trig_normal_form(sp.sin(t1 + sp.pi / 3) ** 2 + sp.cos(t1 + sp.pi / 3) ** 2, BASIS) == 1
    assert is_identity(sp.sin(t1 + sp.pi / 6), sp.sqrt(3) / 2 * sp.sin(t1) + sp.cos(t1) / 2, BASIS)


def test_sums_of_parallel_angles_collapse():
    expr = L1 * sp.cos(t1) + L2 * (sp.cos(t1) * sp.cos(t2) - sp.sin(t1) * sp.sin(t2))
    assert simplify_expr(expr, BASIS) == L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2)


def test_common_factors_are_pulled_out():
    expr = sp.expand(sp.cos(t1) * (L1 * sp.cos(t2) + L2 * sp.cos(t2 + t3)))
    basis = AngleBasis((t1, t2, t3), (t1, t2, t2 + t3))
    assert simplify_expr(expr, basis) == sp.cos(t1) * (L1 * sp.cos(t2) + L2 * sp.cos(t2 + t3))


def test_a_false_identity_is_rejected():
    assert not is_identity(sp.sin(t1) ** 2, sp.cos(t1) ** 2, BASIS)
    assert not is_identity(sp.sin(sp.Rational(3, 10)), sp.Rational(3, 10), BASIS)


# Random trigonometric polynomials in the joint angles, a constant angle and a parameter angle: rewriting each one by
# textbook identities must not change its normal form, and the normal form must keep its numeric value.
ANGLES = [t1, t2, t3, t1 + t2, t2 - t3, t1 + sp.Rational(3, 10), beta, t2 + beta]
FACTORS = st.sampled_from([f(a) for a in ANGLES for f in (sp.sin, sp.cos)] + [L1, L2, sp.Rational(-1, 2)])
MONOMIALS = st.lists(FACTORS, min_size=1, max_size=4).map(lambda fs: sp.Mul(*fs))
POLYNOMIALS = st.lists(MONOMIALS, min_size=1, max_size=5).map(lambda ms: sp.Add(*ms))


@pytest.mark.slow
@settings(deadline=None, max_examples=30)
@given(expr=POLYNOMIALS)
def test_normal_form_is_unique_and_exact(expr):
    rewritten = sp.expand_trig(expr) + sp.sin(t3) ** 2 + sp.cos(t3) ** 2 - 1
    assert trig_normal_form(expr, BASIS) == trig_normal_form(rewritten, BASIS)
    compact = simplify_expr(expr, BASIS)
    values = {t1: 0.3, t2: -1.2, t3: 2.1, L1: 0.7, L2: -0.4, beta: 0.9}
    np.testing.assert_allclose(float(compact.evalf(subs=values)), float(expr.evalf(subs=values)), atol=1e-12)

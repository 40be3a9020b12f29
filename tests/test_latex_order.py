"""The LaTeX printer orders the terms of every sum exactly as SymPy does, by its own faster route."""

from __future__ import annotations

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from marks import marked

from symjac import jacobian, load_robot
from symjac.printing.latex import SortKeys, ordered_terms

x, y, z = sp.symbols("x y z", real=True)
A, B = sp.symbols("A B", commutative=False)

ATOMS = [x, y, z, sp.sin(x), sp.cos(x + y), sp.sqrt(2), sp.pi, sp.Rational(3, 7), sp.Float(0.25), sp.I,
         sp.Integer(10) ** 400, sp.Rational(1, 10**400)]


def _sums(expr: sp.Basic) -> list[sp.Add]:
    return [node for node in sp.preorder_traversal(expr) if isinstance(node, sp.Add)]


@pytest.mark.parametrize("expr", [1 - x, 2 - 3 * x, sp.pi - 2 * y, x**2 + 3 * x * y + 1, A * B + B * A + x,
                                  sp.sqrt(2) * x - sp.Rational(1, 3) * y * z + sp.I * x])
def test_special_and_mixed_sums(expr):
    assert ordered_terms(expr) == expr.as_ordered_terms()


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(ATOMS), st.sampled_from(ATOMS), st.integers(-3, 3)), min_size=2,
                max_size=6))
def test_random_sums(parts):
    expr = sp.Add(*(c * a * b**e for a, b, e in parts for c in [1]))
    if isinstance(expr, sp.Add):
        assert ordered_terms(expr) == expr.as_ordered_terms()


@pytest.mark.parametrize("name", marked(["puma560", "stanford", "ur5"]))
def test_every_sum_of_a_jacobian(name):
    for add in _sums(jacobian(load_robot(name), frame=0)):
        assert ordered_terms(add) == add.as_ordered_terms()


@pytest.mark.parametrize("name", marked(["puma560", "stanford", "ur5"]))
def test_remembered_sort_keys_equal_sympys(name):
    keys = SortKeys()
    J = jacobian(load_robot(name), frame=0)
    nodes = {node for entry in J for node in sp.preorder_traversal(entry)}
    assert all(keys(node) == sp.default_sort_key(node) for node in nodes)
    assert all(keys(node) == sp.default_sort_key(node) for node in (sp.exp(x) * y, sp.Dummy("u") ** 2, A * B * x))

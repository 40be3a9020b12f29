r"""Nested results lowered: their intermediates become the first temporaries, instead of a graph to CSE again.

A chain with generic geometry is derived nested (:mod:`symjac.symbolic.nested`): its results hold
:class:`~symjac.symbolic.nested.Intermediate` symbols, each defined once in terms of the joint variables and earlier
intermediates. That is already a common subexpression elimination, and a linear one; written out, the same results
are graphs whose trees grow exponentially with the chain. So the definitions go to the generated code as they are:

1. **Angles** (:func:`expanded_nested`). Each definition gets the angle expansion of every other expression
   (:class:`~symjac.symbolic.angles.AngleExpansion`: :math:`\cos\theta_i \to c_i`), once per intermediate, kept
   with the expansion so that every function of a module shares it. The expanded definition is an intermediate
   again (:func:`~symjac.symbolic.nested.named`), or written in place when it became small.
2. **Temporaries** (:func:`placeheld`). Every intermediate is replaced by a plain placeholder symbol, numbered in
   evaluation order (:math:`w_k \to h_k`, :math:`h_k = \text{definition}_k`), so nothing later sees an
   intermediate: no name, no index of one reaches the generated text, and the code is the same for the same input.
3. **CSE of what remains** (:func:`symjac.codegen.cse.eliminate_common` with ``definitions``): the definitions and
   the outputs go through ``sympy.cse`` together (each is small), and everything is numbered ``x0, x1, ...`` in
   evaluation order.
4. **Numbers grouped** (:func:`grouped`): SymPy distributes a number over a sum, so a generic rotation's
   :math:`c_\alpha (c_\theta y - s_\theta x)` arrives as two products; the terms that share a number are grouped
   under it again, each group one temporary (a calibrated 6R arm's Jacobian: 348 operations before, 308 after).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from weakref import WeakKeyDictionary

import sympy as sp

from symjac.symbolic.angles import AngleExpansion
from symjac.symbolic.dag import distinct_nodes
from symjac.symbolic.nested import Intermediate, definitions, named

__all__ = ["expanded_nested", "grouped", "has_nested", "placeheld"]

Temporaries = list[tuple[sp.Symbol, sp.Expr]]

_EXPANDED: WeakKeyDictionary[AngleExpansion, dict[sp.Basic, sp.Expr]] = WeakKeyDictionary()
"""Per angle expansion (one per chain), each intermediate's expanded counterpart (an expanded one maps to itself)."""


def has_nested(exprs: Sequence[sp.Basic]) -> bool:
    """Whether ``exprs`` hold an :class:`~symjac.symbolic.nested.Intermediate` (each shared node visited once)."""
    return any(isinstance(node, Intermediate) for node in distinct_nodes(exprs))


def _direct(expr: sp.Basic) -> list[Intermediate]:
    """The intermediates ``expr`` names itself (not those inside their definitions)."""
    return [node for node in distinct_nodes([expr]) if isinstance(node, Intermediate)]


def expanded_nested(angles: AngleExpansion, exprs: Sequence[sp.Expr]) -> list[sp.Expr]:
    r"""``exprs`` with every intermediate replaced by one whose definition is angle-expanded (``angles``).

    ``exprs`` themselves must already be expanded (:meth:`AngleExpansion.expand_all
    <symjac.symbolic.angles.AngleExpansion.expand_all>` leaves intermediates alone, as symbols). Each intermediate
    is expanded once per ``angles``; an intermediate that is already the expanded one stays.
    """
    cache = _EXPANDED.setdefault(angles, {})
    pending = [w for w, _ in definitions(list(exprs)) if w not in cache]
    if pending:
        for w, expanded in zip(pending, angles.expand_all([w.definition for w in pending]), strict=True):
            value = named(sp.Basic.xreplace(expanded, {u: cache[u] for u in _direct(expanded)}))
            cache[w] = value
            if isinstance(value, Intermediate):
                cache[value] = value
    return [sp.Basic.xreplace(e, {u: cache[u] for u in _direct(e)}) for e in exprs]


def placeheld(exprs: Sequence[sp.Expr], symbols: Iterator[sp.Symbol] | None = None
              ) -> tuple[Temporaries, list[sp.Expr]]:
    """The definitions of the intermediates in ``exprs`` as temporaries, and ``exprs`` in terms of them.

    Each intermediate becomes a placeholder, the next of ``symbols`` (default: :class:`sympy.Dummy` symbols ``_h0,
    _h1, ...``, numbered in evaluation order, so that placeholders sort by their names, never by creation), defined
    by its definition in terms of earlier placeholders. Neither the temporaries nor the expressions hold an
    intermediate.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> w = named(sp.sin(x) * x + 1)
    >>> placeheld([2 * w, w**2], sp.numbered_symbols("h"))
    ([(h0, x*sin(x) + 1)], [2*h0, h0**2])
    """
    holders: dict[sp.Basic, sp.Symbol] = {}
    temporaries: Temporaries = []
    fresh = sp.numbered_symbols("_h", cls=sp.Dummy, real=True) if symbols is None else symbols
    for w, definition in definitions(list(exprs)):
        holders[w] = next(fresh)
        temporaries.append((holders[w], sp.Basic.xreplace(definition, {u: holders[u] for u in _direct(definition)})))
    return temporaries, [sp.Basic.xreplace(sp.sympify(e), {u: holders[u] for u in _direct(e)}) for e in exprs]


def grouped(temporaries: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
            ) -> tuple[Temporaries, list[sp.Expr]]:
    r"""Terms of a sum that share a numeric factor grouped under it, each group a temporary shared by every sum.

    .. math:: a\,s_4 x_{12} - a\,x_{14} - b\,x_9 \;\to\; a\,t - b\,x_9, \qquad
              b\,s_4 x_{12} - b\,x_{14} + a\,x_9 \;\to\; b\,t + a\,x_9, \qquad t = s_4 x_{12} - x_{14}

    SymPy distributes a number over a sum (:math:`c\,(u + v) \to c\,u + c\,v`), so the rotation of a generic link,
    :math:`y' = c_\alpha (c_\theta y - s_\theta x) + s_\alpha z`, reaches code generation as three products in each of
    two rows; grouped, the sum in parentheses is computed once. A group is written with its first term (SymPy's
    sort order) positive, so a group and its negative share one temporary. The temporaries and ``outputs`` come
    renamed ``_x0, _x1, ...`` in evaluation order.

    Examples
    --------
    >>> s4, x9, x12, x14 = sp.symbols("s4 x9 x12 x14")
    >>> grouped([], [0.5*s4*x12 - 0.5*x14 - 0.25*x9, 0.25*s4*x12 - 0.25*x14 + 0.5*x9])
    ([(_x0, -s4*x12 + x14)], [-0.5*_x0 - 0.25*x9, -0.25*_x0 + 0.5*x9])
    """
    names = sp.numbered_symbols("_g", cls=sp.Dummy, real=True)
    shared: dict[sp.Expr, sp.Expr] = {}  # a sum with its first term positive: the temporary holding it (or minus)
    result: Temporaries = []

    def normal(inner: sp.Expr) -> tuple[int, sp.Expr]:
        # the first term in SymPy's structural order of the terms without their signs (Basic.compare: cheap, and
        # independent of hashing); default_sort_key took seconds on a long chain
        terms = [term.as_coeff_Mul() for term in inner.args]
        first = min(terms, key=lambda pair: _Structural(pair[1]))
        return (-1, -inner) if first[0] < 0 else (1, inner)

    def regroup(expr: sp.Expr) -> sp.Expr:
        if not isinstance(expr, sp.Add):
            return expr
        groups: dict[sp.Expr, list[sp.Expr]] = {}
        for term in expr.args:
            coefficient, rest = term.as_coeff_Mul()
            groups.setdefault(abs(coefficient), []).append(sp.sign(coefficient) * rest)
        if all(len(terms) < 2 or factor == 1 for factor, terms in groups.items()):
            return expr
        parts = []
        for factor, terms in groups.items():
            if len(terms) < 2 or factor == 1:
                parts += [factor * term for term in terms]
                continue
            sign, inner = normal(sp.Add(*terms))
            if inner not in shared:
                shared[inner] = next(names)
                result.append((shared[inner], inner))  # type: ignore[arg-type]  # a new symbol
            parts.append(sign * factor * shared[inner])
        return sp.Add(*parts)

    for symbol, value in temporaries:
        value = regroup(value)
        result.append((symbol, value))
        if isinstance(value, sp.Add):
            sign, inner = normal(value)
            shared.setdefault(inner, sign * symbol)
    reduced = [regroup(e) for e in outputs]
    renaming: dict[sp.Symbol, sp.Symbol] = {}
    fresh = sp.numbered_symbols("_x", real=True)
    renamed: Temporaries = []
    for symbol, value in result:
        renaming[symbol] = next(fresh)
        renamed.append((renaming[symbol], value.xreplace(renaming)))
    return renamed, [e.xreplace(renaming) for e in reduced]


class _Structural:
    """An expression ordered by :meth:`sympy.Basic.compare` (a total order on structure, as ``sorted`` wants)."""

    __slots__ = ("expr",)

    def __init__(self, expr: sp.Basic):
        self.expr = expr

    def __lt__(self, other: _Structural) -> bool:
        return bool(self.expr.compare(other.expr) < 0)

r"""Nested forms: results written with named intermediate values, for geometry that has no textbook form.

A product of n generic link transforms (calibrated screw axes, twists such as 1.5702 rad) has no compact closed form:
multiplied out, its entries grow exponentially with n. Built frame by frame, each entry of :math:`{}^0T_k` is a
short expression of the entries of :math:`{}^0T_{k-1}` and of link k's own transform, so the *nested* form grows
linearly. Here each such entry is an :class:`Intermediate`: a symbol that carries its definition,

.. math:: w_{17} = w_{9}\cos\theta_4 - 0.4383\,w_{12}, \qquad \dots

SymPy treats an intermediate as a symbol whose free symbols are those of its definition, so differentiation
(:math:`\partial w / \partial \theta_i` is the intermediate of the differentiated definition) and substitution of
symbols see through it, each intermediate done once. A result that holds intermediates is handed to people
(:func:`presented`) written out when its written-out form stays small (:data:`INLINE_LIMIT`), and otherwise as a
:class:`NestedMatrix`, which prints with its definitions (LaTeX ``where`` lines, JSON definitions).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import sympy as sp

from symjac.symbolic.dag import distinct_nodes

__all__ = [
    "INLINE_LIMIT",
    "Intermediate",
    "NestedMatrix",
    "definitions",
    "has_intermediates",
    "inline",
    "named",
    "presented",
    "presented_matrix",
    "substitute",
    "tree_size",
]

INLINE_LIMIT = 4_000
"""Tree nodes above which a result keeps its intermediates (:func:`presented`); below, it is written out.

A generic 3-joint arm's Jacobian written out has a few hundred nodes and reads well; a 6-joint one has hundreds of
thousands (the nested form: a few hundred short definitions).
"""


class Intermediate(sp.Dummy):  # type: ignore[misc]
    r"""A name for one subexpression of a nested result: a real symbol that carries its ``definition``.

    Its free symbols are those of the definition (joint variables and parameters, never other intermediates), so
    ``expr.diff(theta)`` and ``expr.subs(theta, value)`` work on expressions that hold it; both are done once per
    intermediate (and kept), so their cost grows with the number of intermediates, not with the written-out size.
    """

    __slots__ = ("_derivatives", "_free", "definition")

    definition: sp.Expr
    _free: frozenset[sp.Symbol]
    _derivatives: dict[sp.Symbol, sp.Expr]

    def __new__(cls, definition: sp.Expr) -> Intermediate:
        """A new intermediate for ``definition`` (never shared with an equal one: identity is cheap to compare)."""
        obj = super().__new__(cls, "w", real=True)
        obj.definition = definition
        obj._free = frozenset(definition.free_symbols)
        obj._derivatives = {}
        return obj  # type: ignore[no-any-return]

    def __reduce__(self) -> tuple[Any, tuple[sp.Expr]]:
        return Intermediate, (self.definition,)

    @property
    def free_symbols(self) -> set[sp.Basic]:  # type: ignore[override]
        """The free symbols of the definition."""
        return set(self._free)

    def _eval_derivative_n_times(self, s: sp.Basic, n: int) -> sp.Expr:
        result: sp.Expr = self
        for _ in range(int(n)):
            result = result._eval_derivative(s) if isinstance(result, Intermediate) else result.diff(s)
        return result

    def _eval_derivative(self, s: sp.Basic) -> sp.Expr:
        if s not in self._free:
            return sp.S.Zero
        if s not in self._derivatives:
            self._derivatives[s] = named(self.definition.diff(s))
        return self._derivatives[s]

    def _eval_subs(self, old: sp.Basic, new: sp.Basic) -> sp.Expr | None:
        # the definition's own ``subs`` reaches the intermediates it holds through SymPy's cache of ``_subs``, so a
        # shared intermediate is substituted once per (old, new)
        if not (getattr(old, "free_symbols", set()) & self._free):
            return self
        return named(self.definition.subs(old, new))

    def _xreplace(self, rule: Mapping[sp.Basic, sp.Basic]) -> tuple[sp.Basic, bool]:
        if self in rule:
            return rule[self], True
        if not any(key in self._free for key in rule):
            return self, False
        return substitute([self], rule)[0], True

    def _eval_evalf(self, prec: int) -> sp.Expr | None:
        return None if self._free else inline([self])[0].evalf(prec)


def _is_small(expr: sp.Expr) -> bool:
    """Whether naming ``expr`` saves nothing: an atom, or one operation on atoms (``-w3``, ``sin(theta1)``)."""
    return bool(expr.is_Atom) or (all(arg.is_Atom for arg in expr.args) and len(expr.args) <= 2)


def named(expr: sp.Expr) -> sp.Expr:
    """``expr`` itself when it is small (:func:`_is_small`) or a number, else a new :class:`Intermediate` for it."""
    expr = sp.sympify(expr)
    if _is_small(expr):
        return expr
    if not expr.free_symbols:
        return expr.evalf() if expr.has(sp.Float) else expr
    return Intermediate(expr)


def _intermediates(roots: Iterable[sp.Basic]) -> list[Intermediate]:
    """The intermediates ``roots`` use, directly or through definitions, each after the ones its definition uses."""
    order: list[Intermediate] = []
    placed: set[Intermediate] = set()
    stack: list[tuple[sp.Basic, bool]] = [(root, False) for root in reversed(list(roots))]
    while stack:
        node, ready = stack.pop()
        if ready:
            placed.add(node)  # type: ignore[arg-type]
            order.append(node)  # type: ignore[arg-type]
            continue
        if isinstance(node, Intermediate):
            if node in placed:
                continue
            stack.append((node, True))
            node = node.definition
        inner = [n for n in distinct_nodes([node]) if isinstance(n, Intermediate) and n not in placed]
        stack.extend((n, False) for n in reversed(inner))
    return order


def has_intermediates(value: Any) -> bool:
    """Whether a SymPy expression, matrix or array holds an :class:`Intermediate`."""
    return any(isinstance(node, Intermediate) for node in distinct_nodes(_entries(value)))


def _entries(value: Any) -> list[sp.Basic]:
    if isinstance(value, sp.MatrixBase | sp.NDimArray):
        return list(value)  # type: ignore[arg-type]
    if isinstance(value, Sequence):
        return [e for item in value for e in _entries(item)]
    return [sp.sympify(value)]


def definitions(value: Any) -> tuple[tuple[Intermediate, sp.Expr], ...]:
    """The intermediates ``value`` uses and their definitions, each after those its definition uses."""
    return tuple((w, w.definition) for w in _intermediates(_entries(value)))


def inline(exprs: Sequence[sp.Expr]) -> list[sp.Expr]:
    """``exprs`` with every intermediate replaced by its definition, written out (shared subexpressions stay shared).

    The result is a graph of shared subexpressions: its size as a tree may be exponential in the chain's length
    (:func:`tree_size` says how large before anyone prints it).
    """
    values: dict[sp.Basic, sp.Basic] = {}
    for w in _intermediates(exprs):
        values[w] = sp.Basic.xreplace(w.definition, {u: values[u] for u in _direct(w.definition)})
    return [sp.Basic.xreplace(sp.sympify(e), {u: values[u] for u in _direct(e)}) for e in exprs]


def substitute(exprs: Sequence[sp.Expr], rule: Mapping[sp.Basic, sp.Basic]) -> list[sp.Expr]:
    """``exprs`` with ``rule`` applied (as ``xreplace``) inside every definition, each intermediate once.

    Numbers for every symbol give numbers; otherwise the results hold new intermediates.
    """
    values: dict[sp.Basic, sp.Basic] = {}
    for w in _intermediates(exprs):
        local = {**rule, **{u: values[u] for u in _direct(w.definition)}}
        values[w] = named(sp.Basic.xreplace(w.definition, local))
    return [sp.Basic.xreplace(sp.sympify(e), {**rule, **{u: values[u] for u in _direct(e)}}) for e in exprs]


def _direct(expr: sp.Basic) -> list[Intermediate]:
    return [n for n in distinct_nodes([expr]) if isinstance(n, Intermediate)]


def tree_size(value: Any) -> int:
    """Nodes of ``value`` written out as trees (intermediates by their definitions), counted without writing it."""
    roots = _entries(value)
    sizes: dict[int, int] = {}
    for w in _intermediates(roots):
        sizes[id(w)] = _size(w.definition, sizes)
    return sum(_size(root, sizes) for root in roots)


def _size(expr: sp.Basic, sizes: dict[int, int]) -> int:
    local: dict[int, int] = {}
    for node in distinct_nodes([expr]):
        if isinstance(node, Intermediate):
            local[id(node)] = sizes[id(node)]
        else:
            local[id(node)] = 1 + sum(local[id(arg)] for arg in node.args)
    return local[id(expr)]


class NestedMatrix(sp.ImmutableDenseMatrix):  # type: ignore[misc]
    r"""An immutable matrix whose entries use :class:`Intermediate` values, each defined once (:attr:`definitions`).

    It is what symjac returns where the written-out form would be too large to read or build: the Jacobian of a
    generic 6-joint arm (a few hundred definitions, against hundreds of thousands of terms written out). Entries
    differentiate and substitute as usual (``J.subs(values)`` gives numbers); :meth:`inlined` writes it out.
    """

    @property
    def definitions(self) -> tuple[tuple[Intermediate, sp.Expr], ...]:
        """Each intermediate the entries use and its definition, in evaluation order."""
        return definitions(self)

    def inlined(self) -> sp.ImmutableMatrix:
        """The same matrix written out: entries as shared graphs, which may be exponentially large as trees."""
        return sp.ImmutableMatrix(self.rows, self.cols, inline(list(self)))


def presented(value: Any, limit: int = INLINE_LIMIT) -> Any:
    """A result as people get it: written out if it holds intermediates and stays within ``limit`` tree nodes.

    A larger matrix becomes a :class:`NestedMatrix`; a larger array keeps its intermediates (its
    :func:`definitions` name them). A result without intermediates is returned as it is.
    """
    if not has_intermediates(value):
        return value
    if tree_size(value) <= limit:
        flat = inline(_entries(value))
        if isinstance(value, sp.MatrixBase):
            return type(value)(value.rows, value.cols, flat) if not isinstance(value, NestedMatrix) else \
                sp.ImmutableMatrix(value.rows, value.cols, flat)
        if isinstance(value, sp.NDimArray):
            return type(value)(flat, value.shape)
        return flat[0]
    if isinstance(value, sp.MatrixBase):
        return NestedMatrix(value)
    return value


def presented_matrix(value: sp.MatrixBase) -> sp.Matrix:
    """:func:`presented` for a kept matrix: a fresh mutable copy, or a :class:`NestedMatrix` when it stays nested."""
    return presented(sp.Matrix(value))  # type: ignore[no-any-return]

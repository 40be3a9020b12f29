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

from collections import OrderedDict
from collections.abc import Container, Iterable, Mapping, Sequence
from typing import Any

import sympy as sp

from symjac.symbolic.dag import distinct_nodes

__all__ = [
    "INLINE_LIMIT",
    "Intermediate",
    "NestedMatrix",
    "definitions",
    "derivative",
    "has_intermediates",
    "inline",
    "lambdify_cse",
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


_FACTS = (lambda kb, orig, a0: (kb, orig, tuple(sorted(a0.items()))))(*sp.Symbol._canonical_assumptions(real=True))


class Intermediate(sp.Dummy):  # type: ignore[misc]
    r"""A name for one subexpression of a nested result: a real symbol that carries its ``definition``.

    Its free symbols are those of the definition (joint variables and parameters, never other intermediates), so
    ``expr.diff(theta)`` and ``expr.subs(theta, value)`` work on expressions that hold it; both are done once per
    intermediate (and kept), so their cost grows with the number of intermediates, not with the written-out size.
    """

    __slots__ = ("_derivatives", "_free", "_tree", "_uses", "definition")

    definition: sp.Expr
    _free: frozenset[sp.Symbol]
    _derivatives: dict[sp.Symbol, sp.Expr]
    _uses: tuple[Intermediate, ...]
    """The intermediates the definition holds directly."""
    _tree: int
    """Nodes of the definition written out as a tree."""

    def __new__(cls, definition: sp.Expr) -> Intermediate:
        """A new intermediate for ``definition`` (never shared with an equal one: identity is cheap to compare)."""
        # Symbol's own constructor deduces the assumptions of every new symbol from scratch (and so does copying
        # them). They are the same for every intermediate, and so is every fact SymPy later derives from them, so all
        # intermediates share one deduced set (_FACTS)
        obj = sp.Expr.__new__(cls)
        obj.name = f"w{sp.Dummy._count}"  # told apart when printed as SymPy prints it; symjac's printers renumber
        obj._assumptions = _FACTS[0]
        obj._assumptions_orig, obj._assumptions0 = _FACTS[1], _FACTS[2]
        obj.dummy_index = sp.Dummy._base_dummy_index + sp.Dummy._count
        sp.Dummy._count += 1
        obj.definition = definition
        obj._free = frozenset(definition.free_symbols)
        obj._derivatives = {}
        obj._uses, obj._tree = _uses_and_size(definition)
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
        return derivative(self, s)

    def _eval_subs(self, old: sp.Basic, new: sp.Basic) -> sp.Expr | None:
        if not (getattr(old, "free_symbols", set()) & self._free):
            return self
        if isinstance(old, sp.Symbol):  # bottom-up through the definitions, no recursion however long the chain
            return _substituted(self, old, new)
        return named(self.definition.subs(old, new))

    def _xreplace(self, rule: Mapping[sp.Basic, sp.Basic]) -> tuple[sp.Basic, bool]:
        if self in rule:
            return rule[self], True
        if not isinstance(rule, Mapping) or not any(key in self._free for key in rule):
            return self, False  # (SymPy's own rewrites pass rules that are functions, not mappings)
        return substitute([self], rule)[0], True

    def xreplace(self, rule: Mapping[sp.Basic, sp.Basic], hack2: bool = False) -> sp.Basic:
        """``rule`` applied inside the definition (SymPy's atoms would only look at themselves)."""
        return self._xreplace(rule)[0]

    def _eval_evalf(self, prec: int) -> sp.Expr | None:
        return None if self._free else inline([self])[0].evalf(prec)


def derivative(expr: sp.Expr, variable: sp.Basic) -> sp.Expr:
    r""":math:`\partial e / \partial x` through intermediates: each one's derivative is an intermediate, derived once.

    The intermediates ``expr`` uses are differentiated in evaluation order (so the chain rule never recurses deeper
    than one definition, even for a 40-joint chain), each keeping its derivative; then ``expr`` itself.
    """
    for w in _intermediates([expr]):
        if variable in w._free and variable not in w._derivatives:
            w._derivatives[variable] = named(_local_derivative(w.definition, variable))
    return _local_derivative(sp.sympify(expr), variable)


def _local_derivative(expr: sp.Expr, s: sp.Basic) -> sp.Expr:
    """The derivative of one (small) definition, intermediates in it already differentiated."""
    if isinstance(expr, Intermediate):
        return expr._derivatives[s] if s in expr._free else sp.S.Zero
    if expr == s:
        return sp.S.One
    if expr.is_Atom or s not in expr.free_symbols:
        return sp.S.Zero
    if isinstance(expr, sp.Add):
        return sp.Add(*[d for d in (_local_derivative(arg, s) for arg in expr.args) if d != 0])
    if isinstance(expr, sp.Mul):
        args = list(expr.args)
        terms = [(i, _local_derivative(arg, s)) for i, arg in enumerate(args)]
        return sp.Add(*[sp.Mul(*args[:i], d, *args[i + 1:]) for i, d in terms if d != 0])
    if isinstance(expr, sp.sin):
        return sp.cos(expr.args[0]) * _local_derivative(expr.args[0], s)
    if isinstance(expr, sp.cos):
        return -sp.sin(expr.args[0]) * _local_derivative(expr.args[0], s)
    if isinstance(expr, sp.Pow) and not expr.exp.free_symbols:
        return expr.exp * expr.base ** (expr.exp - 1) * _local_derivative(expr.base, s)
    if not any(isinstance(node, Intermediate) for node in distinct_nodes([expr])):
        return expr.diff(s)
    raise NotImplementedError(f"no derivative rule for {type(expr).__name__} around intermediate values")


def _is_small(expr: sp.Expr) -> bool:
    """Whether naming ``expr`` saves nothing: an atom, or one operation on atoms (``-w3``, ``sin(theta1)``).

    A product such as ``0.43*sin(theta2)`` is named: then every entry of a generic link's transform is an
    intermediate, which is how the simplifier tells nested input (:func:`has_intermediates`) from textbook input.
    """
    return bool(expr.is_Atom) or (all(arg.is_Atom for arg in expr.args) and len(expr.args) <= 2)


def named(expr: sp.Expr) -> sp.Expr:
    """``expr`` itself when it is small (:func:`_is_small`) or a number, else a new :class:`Intermediate` for it."""
    expr = sp.sympify(expr)
    if _is_small(expr):
        return expr
    if not expr.free_symbols:
        return expr.evalf() if expr.has(sp.Float) else expr
    return Intermediate(expr)


def _uses_and_size(expr: sp.Basic) -> tuple[tuple[Intermediate, ...], int]:
    """The intermediates ``expr`` holds directly, and its size written out as a tree."""
    sizes: dict[int, int] = {}
    uses: dict[Intermediate, None] = {}
    for node in distinct_nodes([expr]):
        if isinstance(node, Intermediate):
            uses[node] = None
            sizes[id(node)] = node._tree
        else:
            sizes[id(node)] = 1 + sum(sizes[id(arg)] for arg in node.args)
    return tuple(uses), sizes[id(expr)]


_RECENT_SUBSTITUTIONS: OrderedDict[tuple[sp.Basic, sp.Basic], dict[Intermediate, sp.Expr]] = OrderedDict()
"""Per recent ``(old, new)`` pair, what each intermediate became: ``Matrix.subs`` calls every entry on its own."""
_KEPT_SUBSTITUTIONS = 8


def _substituted(w: Intermediate, old: sp.Basic, new: sp.Basic) -> sp.Expr:
    """``w`` with ``old`` replaced by ``new``, every intermediate below it once per pair (the last few pairs kept)."""
    key = (old, new)
    memo = _RECENT_SUBSTITUTIONS.get(key)
    if memo is None:
        memo = _RECENT_SUBSTITUTIONS[key] = {}
        if len(_RECENT_SUBSTITUTIONS) > _KEPT_SUBSTITUTIONS:
            _RECENT_SUBSTITUTIONS.popitem(last=False)
    else:
        _RECENT_SUBSTITUTIONS.move_to_end(key)
    for u in _intermediates([w], known=memo):
        memo[u] = named(sp.Basic.xreplace(u.definition, {old: new, **{v: memo[v] for v in u._uses}}))
    return memo[w]


def _intermediates(roots: Iterable[sp.Basic], known: Container[Intermediate] = frozenset()) -> list[Intermediate]:
    """The intermediates ``roots`` use, directly or through definitions, each after the ones its definition uses.

    Those in ``known`` are left out, and so is what only they use.
    """
    order: list[Intermediate] = []
    placed: set[Intermediate] = set()
    stack: list[tuple[Intermediate, bool]] = []
    for root in reversed(list(roots)):
        uses = (root,) if isinstance(root, Intermediate) else _uses_and_size(root)[0]
        stack.extend((w, False) for w in reversed(uses))
    while stack:
        w, ready = stack.pop()
        if ready:
            if w not in placed:
                placed.add(w)
                order.append(w)
            continue
        if w in placed or w in known:
            continue
        stack.append((w, True))
        stack.extend((u, False) for u in reversed(w._uses) if u not in placed and u not in known)
    return order


def has_intermediates(value: Any) -> bool:
    """Whether a SymPy expression, matrix or array holds an :class:`Intermediate`."""
    return any(isinstance(node, Intermediate) for node in distinct_nodes(_entries(value)))


def _entries(value: Any) -> list[sp.Basic]:
    if isinstance(value, sp.MatrixBase):
        return list(value)
    if isinstance(value, sp.NDimArray):
        return list(sp.flatten(value.tolist()))
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
        values[w] = sp.Basic.xreplace(w.definition, {u: values[u] for u in w._uses})
    return [sp.Basic.xreplace(sp.sympify(e), {u: values[u] for u in _direct(e)}) for e in exprs]


def substitute(exprs: Sequence[sp.Expr], rule: Mapping[sp.Basic, sp.Basic]) -> list[sp.Expr]:
    """``exprs`` with ``rule`` applied (as ``xreplace``) inside every definition, each intermediate once.

    Numbers for every symbol give numbers; otherwise the results hold new intermediates.
    """
    values: dict[sp.Basic, sp.Basic] = {}
    for w in _intermediates(exprs):
        local = {**rule, **{u: values[u] for u in w._uses}}
        values[w] = named(sp.Basic.xreplace(w.definition, local))
    return [sp.Basic.xreplace(sp.sympify(e), {**rule, **{u: values[u] for u in _direct(e)}}) for e in exprs]


def _direct(expr: sp.Basic) -> tuple[Intermediate, ...]:
    return (expr,) if isinstance(expr, Intermediate) else _uses_and_size(expr)[0]


def tree_size(value: Any) -> int:
    """Nodes of ``value`` written out as trees (intermediates by their definitions), counted without writing it."""
    return sum(_uses_and_size(root)[1] for root in _entries(value))


class NestedMatrix(sp.ImmutableDenseMatrix):  # type: ignore[misc]
    r"""An immutable matrix whose entries use :class:`Intermediate` values, each defined once (its ``definitions``).

    It is what symjac returns where the written-out form would be too large to read or build: the Jacobian of a
    generic 6-joint arm (a few hundred definitions, against hundreds of thousands of terms written out). Entries
    differentiate and substitute as usual (``J.subs(values)`` gives numbers); :meth:`inlined` writes it out.
    """

    @property
    def definitions(self) -> tuple[tuple[Intermediate, sp.Expr], ...]:
        """Each intermediate the entries use and its definition, in evaluation order."""
        return definitions(self)

    def xreplace(self, rule: Mapping[sp.Basic, sp.Basic]) -> sp.MatrixBase:  # type: ignore[override]
        """``rule`` applied inside every definition once (shared by all entries), then :func:`presented`."""
        return presented(sp.ImmutableMatrix(self.rows, self.cols, substitute(list(self), rule)))

    def subs(self, *args: Any, **kwargs: Any) -> sp.MatrixBase:  # type: ignore[override]
        """Symbols replaced as :meth:`xreplace` does (numbers for every symbol give a matrix of numbers)."""
        pairs = dict(args[0]) if len(args) == 1 and isinstance(args[0], Mapping) else \
            dict(args[0]) if len(args) == 1 else {args[0]: args[1]} if len(args) == 2 else None
        if pairs is not None and not kwargs and all(isinstance(sp.sympify(k), sp.Symbol) for k in pairs):
            return self.xreplace({sp.sympify(k): sp.sympify(v) for k, v in pairs.items()})
        return super().subs(*args, **kwargs)  # type: ignore[no-any-return]

    def inlined(self) -> sp.ImmutableMatrix:
        """The same matrix written out: entries as shared graphs, which may be exponentially large as trees."""
        return sp.ImmutableMatrix(self.rows, self.cols, inline(list(self)))


def presented(value: Any, limit: int | None = None) -> Any:
    """A result as people get it: written out if it holds intermediates and stays within ``limit`` tree nodes.

    ``limit`` defaults to :data:`INLINE_LIMIT` (read when called).

    A larger matrix becomes a :class:`NestedMatrix`; a larger array keeps its intermediates (its
    :func:`definitions` name them). A result without intermediates is returned as it is.
    """
    if not has_intermediates(value):
        return value
    if tree_size(value) <= (INLINE_LIMIT if limit is None else limit):
        flat = inline(_entries(value))
        if isinstance(value, sp.MatrixBase):
            return type(value)(value.rows, value.cols, flat) if not isinstance(value, NestedMatrix) else \
                sp.ImmutableMatrix(value.rows, value.cols, flat)
        if isinstance(value, sp.NDimArray):
            return type(value)(flat, value.shape)
        return flat[0]
    if isinstance(value, sp.MatrixBase):
        return NestedMatrix(sp.Matrix(value))  # (given an immutable matrix, the constructor returns it as it is)
    return value


def lambdify_cse(expr: Any) -> tuple[list[tuple[sp.Symbol, sp.Expr]], Any]:
    """A ``cse`` for :func:`sympy.lambdify`: the intermediates ``expr`` uses become its assignments, in order.

    ``sympy.lambdify(q, J, cse=lambdify_cse)`` compiles a nested result in time linear in its definitions (printing
    it written out would take exponential time); an ``expr`` without intermediates gets SymPy's own ``cse``.
    """
    pairs = definitions(expr)
    if not pairs:
        return sp.cse(expr, list=False)  # type: ignore[no-any-return]
    return [(w, d) for w, d in pairs], expr


def presented_matrix(value: sp.MatrixBase) -> sp.Matrix:
    """:func:`presented` for a kept matrix: a fresh mutable copy, or a :class:`NestedMatrix` when it stays nested."""
    return presented(sp.Matrix(value))  # type: ignore[no-any-return]

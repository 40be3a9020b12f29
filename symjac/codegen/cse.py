r"""Common subexpression elimination that stays fast on long chains.

``sympy.cse(order="canonical")`` orders the arguments of every sum and product by their size *as trees*, and compares
expressions as trees. The raw products of a long 3-D chain are graphs whose trees are exponentially larger (a
20-joint snake's Jacobian: a few thousand distinct subexpressions, millions of tree nodes), so SymPy's
CSE alone took most of a minute there. When the trees are that large (more than :data:`TREE_LIMIT` nodes), every
subexpression the graph shares is first given a name of its own, in evaluation order, which leaves only small trees
for ``sympy.cse`` to work on. Smaller inputs (every catalog robot) go to ``sympy.cse`` unchanged.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable, Sequence

import sympy as sp

from symjac.symbolic.dag import distinct_nodes, rebuild, with_args

__all__ = ["TREE_LIMIT", "eliminate_common"]

TREE_LIMIT = 100_000
"""Tree nodes (shared subexpressions counted once per use) above which shared subexpressions are named first."""

SMALL = 4  # a shared subexpression of fewer tree nodes (-s1, L*c2) is left inline: naming it saves nothing

Temporaries = list[tuple[sp.Symbol, sp.Expr]]


def eliminate_common(exprs: Sequence[sp.Expr], definitions: Sequence[tuple[sp.Symbol, sp.Expr]] = ()
                     ) -> tuple[Temporaries, list[sp.Expr]]:
    """Temporaries ``_x0, _x1, ...`` in evaluation order and ``exprs`` in terms of them (deterministic).

    ``definitions`` are named values ``exprs`` use (symbols that are no argument, each defined after those its
    definition uses, as :func:`symjac.codegen.nested.placeheld` gives them): they join the CSE as values of their
    own and become temporaries too, renamed with the rest (one defined as another's value is dropped for it).

    Examples
    --------
    >>> x, y = sp.symbols("x y")
    >>> eliminate_common([sp.sin(x) * y, sp.sin(x) * y + 1])
    ([(_x0, y*sin(x))], [_x0, _x0 + 1])
    >>> h = sp.Dummy("h")
    >>> eliminate_common([h * y, h * y + 1], [(h, sp.sin(x) + 1)])
    ([(_x0, sin(x) + 1), (_x1, _x0*y)], [_x1, _x1 + 1])
    """
    names = sp.numbered_symbols("_x", real=True)
    given = list(definitions)
    roots = [d for _, d in given] + list(exprs)
    sizes = _tree_sizes(roots)
    if not given and sum(sizes[id(e)] for e in exprs) <= TREE_LIMIT:
        found, reduced = sp.cse(list(exprs), symbols=names, order="canonical")
        return list(found), list(reduced)
    if sum(sizes[id(e)] for e in roots) <= TREE_LIMIT:
        shared: Temporaries = []
        named = roots
    else:
        shared, named = _name_shared(roots, sizes)
    definitions = [*shared, *((h, d) for (h, _), d in zip(given, named[:len(given)], strict=True))]
    named = named[len(given):]
    helpers = sp.numbered_symbols("_y", cls=sp.Dummy, real=True)
    replacements, reduced = sp.cse([d for _, d in definitions] + named, symbols=helpers, order="canonical")
    steps = dict(replacements) | {h: d for (h, _), d in zip(definitions, reduced[:len(definitions)], strict=True)}
    order = _evaluation_order([h for h, _ in definitions] + [y for y, _ in replacements], steps)
    renaming: dict[sp.Symbol, sp.Expr] = {}
    temporaries: Temporaries = []
    for symbol in order:
        value = steps[symbol].xreplace(renaming)
        if value.is_Symbol:  # the shared subexpression was CSE'd to another name: use that one
            renaming[symbol] = value
            continue
        renaming[symbol] = next(names)
        temporaries.append((renaming[symbol], value))
    return temporaries, [e.xreplace(renaming) for e in reduced[len(definitions):]]


def _tree_sizes(exprs: Sequence[sp.Expr]) -> dict[int, int]:
    """Each subexpression's size as a tree (by identity), computed once per distinct subexpression."""
    sizes: dict[int, int] = {}
    for node in distinct_nodes(exprs):
        sizes[id(node)] = 1 + sum(sizes[id(arg)] for arg in node.args)
    return sizes


def _name_shared(exprs: Sequence[sp.Expr], sizes: dict[int, int]) -> tuple[Temporaries, list[sp.Expr]]:
    """Every subexpression used more than once (and not small) replaced by a name, definitions in evaluation order.

    Subexpressions are told apart by structure, not identity: whether two equal subtrees are one object depends on
    SymPy's cache, and the generated code must not. Each distinct object gets the index of its structure (its
    function and its arguments' indices), computed once, so equal trees are never compared as trees.
    """
    nodes = distinct_nodes(exprs)
    structure: dict[int, int] = {}  # id(node) -> index of its structure
    indices: dict[Hashable, int] = {}
    first: list[sp.Basic] = []  # the first node of each structure
    for node in nodes:
        key: Hashable = (type(node), node) if not node.args else (node.func, *(structure[id(a)] for a in node.args))
        structure[id(node)] = indices.setdefault(key, len(indices))
        if structure[id(node)] == len(first):
            first.append(node)
    uses = Counter(structure[id(arg)] for node in first for arg in node.args)
    uses.update(structure[id(e)] for e in exprs)  # an output used inside another output too
    shared = {structure[id(node)] for node in first if uses[structure[id(node)]] > 1 and sizes[id(node)] >= SMALL}
    definitions: Temporaries = []
    name_of: dict[int, sp.Symbol] = {}
    names = sp.numbered_symbols("_h", cls=sp.Dummy, real=True)  # no input can hold a Dummy

    def step(node: sp.Basic, args: tuple[sp.Basic, ...]) -> sp.Basic:
        index = structure[id(node)]
        if index not in shared:
            return with_args(node, args)
        if index not in name_of:
            name_of[index] = next(names)
            definitions.append((name_of[index], with_args(node, args)))
        return name_of[index]

    named = rebuild(exprs, step)
    return definitions, named


def _evaluation_order(symbols: list[sp.Symbol], steps: dict[sp.Symbol, sp.Expr]) -> list[sp.Symbol]:
    """``symbols`` ordered so that each comes after the ones its value uses (depth first, in the given order)."""
    order: list[sp.Symbol] = []
    placed: set[sp.Symbol] = set()
    rank = {symbol: k for k, symbol in enumerate(symbols)}
    for root in symbols:
        stack = [(root, False)]
        while stack:
            symbol, ready = stack.pop()
            if symbol in placed:
                continue
            if ready:
                placed.add(symbol)
                order.append(symbol)
                continue
            stack.append((symbol, True))
            needs = sorted((s for s in steps[symbol].free_symbols if s in steps and s not in placed),
                           key=rank.__getitem__)
            stack.extend((s, False) for s in reversed(needs))
    return order

r"""Expressions walked as graphs: every distinct subexpression visited once.

A raw chain product shares its subexpressions: the entries of :math:`{}^0T_n = {}^0T_{n-1}\,{}^{n-1}T_n` hold those
of :math:`{}^0T_{n-1}` as arguments, and so on down the chain. SymPy's own walks (``preorder_traversal``,
``replace``, ``free_symbols``, ``is_number``) visit a shared subexpression once per path to it, which grows
exponentially with the number of links (a 3-D snake: about :math:`1.6^n` paths). The walks here visit it once, and
iterate instead of recursing, so a long chain neither takes exponential time nor exceeds Python's recursion limit.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

import sympy as sp

__all__ = ["distinct_nodes", "free_symbols", "rebuild", "with_args"]


def distinct_nodes(roots: Iterable[sp.Basic]) -> list[sp.Basic]:
    """Every subexpression of ``roots``, each object once, arguments before the expressions that hold them.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> shared = sp.sin(x) + 1
    >>> distinct_nodes([shared * x, shared])
    [x, 1, sin(x), sin(x) + 1, x*(sin(x) + 1)]
    """
    order: list[sp.Basic] = []
    # By identity: equal but distinct trees would be compared node by node, as trees. Safe because every node stays
    # alive in ``order`` and SymPy's ``args`` are the stored argument objects, so an id is never reused meanwhile.
    seen: set[int] = set()
    for root in roots:
        if id(root) in seen:
            continue
        stack: list[tuple[sp.Basic, bool]] = [(root, False)]
        while stack:
            node, expanded = stack.pop()
            if expanded:
                order.append(node)  # keeps the node alive, so its id stays its own
                continue
            if id(node) in seen:
                continue
            seen.add(id(node))
            stack.append((node, True))
            stack.extend((arg, False) for arg in reversed(node.args) if id(arg) not in seen)
    return order


def free_symbols(roots: Iterable[sp.Basic]) -> set[sp.Symbol]:
    """The symbols ``roots`` depend on (``Basic.free_symbols`` of all of them, each subexpression visited once)."""
    return {node for node in distinct_nodes(roots) if isinstance(node, sp.Symbol)}


def rebuild(roots: Iterable[sp.Basic], step: Callable[[sp.Basic, tuple[sp.Basic, ...]], sp.Basic]) -> list[sp.Basic]:
    """``roots`` rebuilt bottom-up: each distinct node becomes ``step(node, new_args)``, computed once.

    ``new_args`` are the node's arguments already rebuilt; ``step`` returns the node's replacement (typically
    ``node.func(*new_args)`` when they changed, or something else entirely).

    Examples
    --------
    >>> x, y = sp.symbols("x y")
    >>> def double_x(node, args):
    ...     return 2 * x if node == x else with_args(node, args)
    >>> rebuild([sp.sin(x) + y], double_x)
    [y + sin(2*x)]
    """
    roots = list(roots)
    done: dict[int, sp.Basic] = {}  # by identity, as in distinct_nodes (which keeps every node alive)
    for node in distinct_nodes(roots):
        done[id(node)] = step(node, tuple(done[id(arg)] for arg in node.args))
    return [done[id(root)] for root in roots]


def with_args(node: sp.Basic, args: tuple[sp.Basic, ...]) -> sp.Basic:
    """``node`` itself when ``args`` are its own arguments, else the same function of ``args`` (re-evaluated)."""
    if all(new is old for new, old in zip(args, node.args, strict=True)):
        return node
    return node.func(*args)

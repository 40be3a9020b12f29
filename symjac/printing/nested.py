r"""Nested results made printable: each intermediate renamed :math:`w_1, w_2, \dots` and listed under "where".

A result of generic geometry (:mod:`symjac.symbolic.nested`) holds :class:`~symjac.symbolic.nested.Intermediate`
symbols, SymPy dummies all named ``w`` that carry their definitions. Before any format prints it, a document is
*named* (:func:`named_document`): the intermediates its equations use are numbered in evaluation order (each after
those its definition uses, the first equation's first), replaced by plain symbols :math:`w_k`, and each equation
gets the definitions it is the first to use (:attr:`~symjac.printing.document.Equation.where`),

.. math:: {}^{0}J = \begin{bmatrix} w_{1} & \dots \end{bmatrix}, \quad
          \text{where } w_{1} = 0.999999\,c_{1},\ \dots

The letter is the first of :data:`LETTERS` that no symbol of the robot or the result is spelled with (``w``, else
``u``, else ``z``, ...). Numbering follows the expressions' own structure, so the same input prints the same bytes.
A document without intermediates is returned as it is (a textbook result prints exactly as before).
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Iterable, Sequence
from typing import Any

import sympy as sp

from symjac.printing.document import Block, Document, Equation
from symjac.symbolic.dag import distinct_nodes
from symjac.symbolic.nested import Intermediate, definitions, has_intermediates

__all__ = ["LETTERS", "Definition", "all_definitions", "named_document", "spare_letter"]

LETTERS = ("w", "u", "z", "v", "g", "h", "k", "m", "n", "y")
"""Letters the intermediates may be named with, in order of preference."""

Definition = tuple[sp.Symbol, sp.Expr]
"""``(w_k, definition)``: one "where" line, the definition in terms of earlier :math:`w_j` only."""


def spare_letter(names: Iterable[str]) -> str:
    """The first of :data:`LETTERS` that no name in ``names`` is spelled with (``w``, ``w3``, ``w_12`` use ``w``).

    Examples
    --------
    >>> spare_letter(["theta1", "w_1", "u"])
    'z'
    """
    taken = set(names)
    for letter in LETTERS:
        pattern = re.compile(rf"{letter}(_?\{{?\d*\}}?)?")
        if not any(pattern.fullmatch(name) for name in taken):
            return letter
    raise ValueError(f"every letter for intermediates ({', '.join(LETTERS)}) is a symbol name already")


def _parts(rhs: Any) -> tuple[Any, ...]:
    return rhs if isinstance(rhs, tuple) else (rhs,)


def _entries(value: Any) -> list[sp.Basic]:
    if isinstance(value, sp.MatrixBase | sp.NDimArray):
        return list(value)  # type: ignore[arg-type]
    return [sp.sympify(value)]


def _renamed(value: Any, rule: dict[sp.Basic, sp.Basic]) -> Any:
    """``value`` (an expression, matrix or array) with each intermediate replaced by its name."""
    if isinstance(value, sp.MatrixBase):
        return sp.ImmutableMatrix(value.rows, value.cols, [sp.Basic.xreplace(e, rule) for e in value])
    if isinstance(value, sp.NDimArray):
        return sp.ImmutableDenseNDimArray([sp.Basic.xreplace(e, rule) for e in value], value.shape)
    return sp.Basic.xreplace(sp.sympify(value), rule)


def _symbol_names(document: Document, values: Sequence[Any]) -> set[str]:
    """The names of the robot's symbols and of every symbol ``values`` hold, through the intermediates' definitions."""
    roots = [e for value in values for e in _entries(value)]
    roots += [definition for _, definition in definitions(roots)]
    names = {node.name for node in distinct_nodes(roots)
             if isinstance(node, sp.Symbol) and not isinstance(node, Intermediate)}
    if document.model is not None:
        names |= {str(s) for s in (*document.model.q, *document.model.joint_variables,
                                   *document.model.parameter_symbols)}
    return names


def named_document(document: Document) -> Document:
    r"""``document`` with its intermediates named :math:`w_1, w_2, \dots` and defined under the equations that use them.

    Every equation of the blocks, then of ``extra``, is visited in order; an equation's
    :attr:`~symjac.printing.document.Equation.where` holds the definitions it is the first to use, in evaluation
    order. A document without intermediates comes back unchanged (the same object).
    """
    equations = [m for block in document.blocks for m in block.math if isinstance(m, Equation)]
    equations += list(document.extra)
    values = [part for equation in equations for part in _parts(equation.rhs)]
    if not any(has_intermediates(value) for value in values if isinstance(value, sp.Basic | sp.MatrixBase
                                                                          | sp.NDimArray)):
        return document
    letter = spare_letter(_symbol_names(document, values))
    rule: dict[sp.Basic, sp.Basic] = {}
    renamed: dict[int, Equation] = {}
    for equation in equations:
        if id(equation) in renamed:  # the same equation twice: named once
            continue
        where: list[Definition] = []
        for w, definition in definitions([e for part in _parts(equation.rhs) for e in _entries(part)]):
            if w in rule:
                continue
            symbol = sp.Symbol(f"{letter}_{len(rule) + 1}", real=True)
            where.append((symbol, sp.Basic.xreplace(definition, rule)))  # its own intermediates are named already
            rule[w] = symbol
        rhs = tuple(_renamed(part, rule) for part in _parts(equation.rhs))
        renamed[id(equation)] = dataclasses.replace(equation, rhs=rhs if isinstance(equation.rhs, tuple) else rhs[0],
                                                    where=(*equation.where, *where))
    blocks = tuple(Block(block.caption, tuple(renamed.get(id(m), m) for m in block.math)) for block in document.blocks)
    return dataclasses.replace(document, blocks=blocks, extra=tuple(renamed[id(e)] for e in document.extra))


def all_definitions(document: Document) -> list[Definition]:
    """Every "where" line of a named document (:func:`named_document`), in order: what its JSON lists."""
    equations = [m for block in document.blocks for m in block.math if isinstance(m, Equation)]
    return [pair for equation in (*equations, *document.extra) for pair in equation.where]

r"""Fitting equations into the page width: matrices split into column blocks, long sums broken over lines.

MathML Core has no automatic line breaking, and a browser page must not grow wider than the window. The width of
each printed entry is estimated from its MathML tree (in em, from the characters of its tokens, scripts at 70 %),
and an equation that would exceed the budget is laid out as:

* a matrix: consecutive column blocks, each within the budget (the caller labels them ``columns 1-3`` and lets the
  page wrap them);
* an entry or a scalar wider than the budget: a sum written over several left-aligned lines, ``+``/``-`` first.

The estimate is deliberately generous; the browser test measures the real page.
"""

from __future__ import annotations

from dataclasses import dataclass
from xml.dom.minidom import Element

import sympy as sp

from symjac.printing.mathml import TextbookMathMLPrinter, math_element, mathml_node
from symjac.printing.shorthand import textbook_factors

__all__ = ["BUDGET_EM", "Display", "Piece", "displays", "estimated_width"]

BUDGET_EM = 40.0
"""Widest display (estimated em) laid out on one line; the page's column is wider than this by a margin."""

_OPERATOR_WIDTH = {"+": 1.3, "-": 1.3, "=": 1.5, "\u2062": 0.1, "(": 0.45, ")": 0.45, ",": 0.5}


def estimated_width(node: Element) -> float:
    """The estimated rendered width of a MathML element, in em (generous: token characters, operator spacing)."""
    tag = node.tagName
    children = [child for child in node.childNodes if isinstance(child, Element)]
    if tag in ("mi", "mn", "mo", "mtext"):
        text = "".join(child.data for child in node.childNodes if hasattr(child, "data"))
        if tag == "mo":
            return _OPERATOR_WIDTH.get(text, 0.8 * len(text) + 0.4)
        return (0.62 if tag == "mi" and len(text) == 1 else 0.55) * len(text)
    widths = [estimated_width(child) for child in children]
    if tag in ("msub", "msup"):
        return widths[0] + 0.75 * sum(widths[1:]) + 0.1
    if tag == "msubsup":
        return widths[0] + 0.75 * max(widths[1:]) + 0.1
    if tag == "mfrac":
        return max(widths) + 0.4
    if tag in ("msqrt", "mroot"):
        return widths[0] + 1.1
    if tag == "mtable":
        columns: list[float] = []
        for row in children:
            cells = [estimated_width(cell) for cell in row.childNodes if isinstance(cell, Element)]
            columns = [max(a, b) for a, b in zip(columns + [0.0] * len(cells), cells, strict=False)] \
                if columns else cells
        return sum(columns) + 1.0 * len(columns)
    return sum(widths)


@dataclass(frozen=True)
class Display:
    """One ``<math display="block">`` of an equation, with the columns it shows (``None``: the whole matrix)."""

    markup: str
    columns: tuple[int, int] | None = None


def _element(printer: TextbookMathMLPrinter, tag: str, text: str | None = None) -> Element:
    element = printer.dom.createElement(tag)
    if text is not None:
        element.appendChild(printer.dom.createTextNode(text))
    return element


Piece = list[Element]
"""Nodes that stay together on one line; a line may break between two pieces."""


def _pieces(printer: TextbookMathMLPrinter, expr: sp.Expr, budget: float) -> list[Piece]:
    """``expr`` cut where a line may break: between the terms of a sum, and inside a long sum within a product."""
    node = mathml_node(expr, printer)
    if estimated_width(node) <= budget:
        return [[node]]
    if isinstance(expr, sp.Add):
        pieces: list[Piece] = []
        for number, term in enumerate(expr.as_ordered_terms()):
            negative = term.could_extract_minus_sign()
            inner = _pieces(printer, -term if negative else term, budget)
            if number or negative:
                inner[0].insert(0, _element(printer, "mo", "\u2212" if negative else "+"))
            pieces += inner
        return pieces
    ordered = textbook_factors(expr) if isinstance(expr, sp.Mul) else None
    if ordered is None:
        return [[node]]
    coefficient, factors = ordered
    pieces = []
    prefix = [_element(printer, "mo", "\u2212")] if coefficient < 0 else []
    if abs(coefficient) != 1:
        prefix.append(_element(printer, "mn", str(abs(coefficient))))
    for factor in factors:
        if factor.is_Add:
            inner = _pieces(printer, factor, budget)
            inner[0].insert(0, _element(printer, "mo", "("))
            inner[-1].append(_element(printer, "mo", ")"))
        else:
            inner = [[mathml_node(factor, printer)]]
        pieces += inner
    pieces[0][:0] = prefix
    return pieces


def _lines(printer: TextbookMathMLPrinter, expr: sp.Expr, budget: float) -> Element:
    """``expr`` printed within ``budget``: as it is, or over left-aligned lines broken between pieces."""
    pieces = _pieces(printer, expr, budget)
    if len(pieces) == 1:
        return pieces[0][0] if len(pieces[0]) == 1 else _row(printer, pieces[0])
    table = _element(printer, "mtable")
    table.setAttribute("class", "lines")
    lines: list[list[Element]] = [[]]
    width = 0.0
    for piece in pieces:
        piece_width = sum(estimated_width(node) for node in piece)
        if lines[-1] and width + piece_width > budget:
            lines.append([])
            width = 0.0
        lines[-1] += piece
        width += piece_width
    for line in lines:
        row, cell = _element(printer, "mtr"), _element(printer, "mtd")
        cell.appendChild(_row(printer, line))
        row.appendChild(cell)
        table.appendChild(row)
    return table


def _row(printer: TextbookMathMLPrinter, nodes: list[Element]) -> Element:
    row = _element(printer, "mrow")
    for node in nodes:
        row.appendChild(node)
    return row


def _matrix(printer: TextbookMathMLPrinter, cells: list[list[Element]]) -> Element:
    table = _element(printer, "mtable")
    for cell_row in cells:
        row = _element(printer, "mtr")
        for cell in cell_row:
            entry = _element(printer, "mtd")
            entry.appendChild(cell)
            row.appendChild(entry)
        table.appendChild(row)
    fenced = _element(printer, "mrow")
    fenced.appendChild(_element(printer, "mo", "("))
    fenced.appendChild(table)
    fenced.appendChild(_element(printer, "mo", ")"))
    return fenced


def _equation(printer: TextbookMathMLPrinter, lhs: Element | None, rhs: Element) -> str:
    row = _element(printer, "mrow")
    if lhs is not None:
        row.appendChild(lhs)
        row.appendChild(_element(printer, "mo", "="))
    row.appendChild(rhs)
    return math_element(row, display=True)


def displays(rhs: sp.Basic, lhs: Element | None = None, budget: float = BUDGET_EM) -> list[Display]:
    """``lhs = rhs`` as one display when it fits the budget, else as column blocks (matrices) or broken lines.

    Examples
    --------
    >>> t1 = sp.Symbol("theta1", real=True)
    >>> [d.columns for d in displays(sp.Matrix([[sp.cos(t1)] * 30]))]
    [(0, 18), (18, 30)]
    """
    printer = TextbookMathMLPrinter()
    lhs_width = 0.0 if lhs is None else estimated_width(lhs) + 1.5
    if not isinstance(rhs, sp.MatrixBase):
        return [Display(_equation(printer, lhs, _lines(printer, rhs, budget - lhs_width)))]
    entries = [[mathml_node(rhs[i, j], printer) for j in range(rhs.cols)] for i in range(rhs.rows)]
    widths = [max((estimated_width(entries[i][j]) for i in range(rhs.rows)), default=0.0) + 1.0
              for j in range(rhs.cols)]
    if lhs_width + sum(widths) + 1.0 <= budget:
        return [Display(_equation(printer, lhs, _matrix(printer, entries)))]
    blocks: list[tuple[int, int]] = []
    start, width = 0, 1.0
    for j, column_width in enumerate(widths):
        if j > start and width + column_width > budget:
            blocks.append((start, j))
            start, width = j, 1.0
        width += column_width
    blocks.append((start, rhs.cols))
    shown, alone = [], len(blocks) == 1  # one block (a column vector of long entries) keeps its name
    for first, last in blocks:
        cell_budget = (budget - 2.0 if last - first == 1 else budget) - (lhs_width if alone else 0.0)
        cells = [[_lines(printer, rhs[i, j], cell_budget) if widths[j] > cell_budget else entries[i][j]
                  for j in range(first, last)] for i in range(rhs.rows)]
        shown.append(Display(_equation(printer, lhs if alone else None, _matrix(printer, cells)), (first, last)))
    return shown

r"""A robot's table (DH rows, or a general chain's origins and axes) as text, LaTeX and rows of strings (for JSON).

The columns and the entries come from the robot's convention plug-in (:mod:`symjac.model.conventions`); this module
only formats them: a column is a symbol with a subscript (:math:`\alpha_{i-1}`) or a word (``xyz``), an entry an
expression or a vector (printed in brackets). The report's HTML table uses the same data
(:func:`table_headings`, :func:`table_cells`).
"""

from __future__ import annotations

import unicodedata

import sympy as sp

from symjac.deprecation import renamed
from symjac.model.conventions import plugin
from symjac.model.conventions.base import Cell, Column
from symjac.model.robot import Robot
from symjac.printing.latex import latex

__all__ = ["VARIABLE", "column_html", "column_latex", "column_text", "parameter_headers", "parameter_rows",
           "parameter_table_latex", "parameter_table_text", "table_cells", "table_headings", "text_table"]

# The names these had before they were convention-neutral (a DH table is one convention's parameter table).
__getattr__ = renamed("symjac.printing.tables", {
    "dh_headers": "parameter_headers",
    "dh_rows": "parameter_rows",
    "dh_table_text": "parameter_table_text",
    "dh_table_latex": "parameter_table_latex",
})


VARIABLE = Column("variable")
"""The last column of a coupled robot's table: each joint variable, and for a coupled joint what it equals."""


def table_headings(robot: Robot) -> tuple[Column, ...]:
    """The columns of ``robot``'s table after the joint number and type (and ``variable`` if joints are coupled)."""
    columns = plugin(robot.convention).columns
    return columns if robot.coupling is None else (*columns, VARIABLE)


def table_cells(robot: Robot) -> list[tuple[Cell, ...]]:
    """The entries of ``robot``'s table, one row per joint, under :func:`table_headings`.

    A coupled robot's rows end with the joint variable (``theta2``) or, for a coupled joint, the equation that
    drives it (``theta4 = -theta2 - theta3``, a :class:`sympy.Eq`).
    """
    spec = plugin(robot.convention)
    rows = [spec.cells(joint) for joint in robot.joints]
    if robot.coupling is None:
        return rows
    return [(*cells, variable if value == variable else sp.Eq(variable, value, evaluate=False))
            for cells, variable, value in zip(rows, robot.joint_variables, robot.joint_values, strict=True)]


def _cell_text(cell: Cell) -> str:
    if isinstance(cell, sp.Equality):
        return f"{sp.sstr(cell.lhs)} = {sp.sstr(cell.rhs)}"
    return sp.sstr(list(cell) if isinstance(cell, tuple) else cell)


def _greek(symbol: str) -> str | None:
    """The Greek letter named ``symbol`` (``"alpha"`` gives α), or ``None``."""
    try:
        return unicodedata.lookup(f"GREEK SMALL LETTER {symbol.upper()}")
    except KeyError:
        return None


def column_text(column: Column) -> str:
    """``alpha_{i-1}``, ``d_i`` or the word."""
    if not column.subscript:
        return column.symbol
    return f"{column.symbol}_{column.subscript}" if len(column.subscript) == 1 else (
        f"{column.symbol}_{{{column.subscript}}}")


def column_latex(column: Column) -> str:
    r"""``\alpha_{i-1}``, ``d_i`` or ``\text{word}``."""
    if not column.subscript:
        return rf"\text{{{column.symbol}}}"
    symbol = f"\\{column.symbol}" if _greek(column.symbol) else column.symbol
    return column_text(Column(symbol, column.subscript))


def column_html(column: Column) -> str:
    """``&#945;<sub>i-1</sub>``, ``d<sub>i</sub>`` or the word."""
    letter = _greek(column.symbol)
    symbol = f"&#{ord(letter)};" if letter else column.symbol
    return f"{symbol}<sub>{column.subscript}</sub>" if column.subscript else symbol


def parameter_headers(robot: Robot) -> list[str]:
    """Plain-text column names after ``joint`` and ``type``."""
    return [column_text(column) for column in table_headings(robot)]


def parameter_rows(robot: Robot) -> list[list[str]]:
    """One row of strings per joint: index, type, then the columns of :func:`parameter_headers` (SymPy strings)."""
    return [[str(joint.index), joint.type.value, *map(_cell_text, cells)]
            for joint, cells in zip(robot.joints, table_cells(robot), strict=True)]


def text_table(headers: list[str], rows: list[list[str]]) -> str:
    """Left-aligned columns two spaces apart, header first."""
    widths = [max(len(row[i]) for row in [headers, *rows]) for i in range(len(headers))]
    lines = ["  ".join(cell.ljust(width) for cell, width in zip(row, widths, strict=True)).rstrip()
             for row in [headers, *rows]]
    return "\n".join(lines) + "\n"


def parameter_table_text(robot: Robot) -> str:
    """The DH table as aligned plain text."""
    return text_table(["joint", "type", *parameter_headers(robot)], parameter_rows(robot))


def _cell_latex(cell: Cell) -> str:
    if isinstance(cell, tuple):
        return r"\left[" + ",\\ ".join(latex(v) for v in cell) + r"\right]"
    return latex(cell)


def parameter_table_latex(robot: Robot) -> str:
    r"""The table as a LaTeX ``array``: the joint number, then the columns (entries in textbook shorthand).

    Examples
    --------
    >>> from symjac import load_robot
    >>> print(parameter_table_latex(load_robot("planar2r"))[:46])
    \begin{array}{c|cccc} i & \alpha_i & a_i & d_i
    """
    headings = table_headings(robot)
    body = r" \\ ".join(" & ".join([str(joint.index), *(_cell_latex(cell) for cell in cells)])
                        for joint, cells in zip(robot.joints, table_cells(robot), strict=True))
    return (r"\begin{array}{c|" + "c" * len(headings) + "} i & " + " & ".join(map(column_latex, headings))
            + r" \\ \hline " + body + r" \end{array}")

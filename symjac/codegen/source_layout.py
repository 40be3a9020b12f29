"""Source layout shared by the backends: statements wrapped to the line width, unpacking, sines, temporaries.

Printed expressions contain spaces only around binary ``+``/``-`` and after commas, so every function here breaks
lines at spaces only and never splits a token; every generated line stays within :data:`LINE_WIDTH` (what ruff
checks in the generated modules).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Literal, Protocol

import sympy as sp

from symjac.codegen.lower import LoweredFunction, SymbolNames
from symjac.errors import CodegenError

__all__ = [
    "LINE_WIDTH",
    "angle_lines",
    "check_layout",
    "comment_lines",
    "entry_names",
    "indices",
    "input_lines",
    "temporary_lines",
    "tuple_lines",
    "tuple_literal",
    "unpack",
    "wrap_statement",
]

LINE_WIDTH = 120
"""Longest line of generated source, in characters (the project's ruff setting)."""


class _Printer(Protocol):
    def doprint(self, expr: sp.Expr) -> str: ...


def wrap_statement(head: str, code: str, tail: str = "", *, width: int = LINE_WIDTH,
                   language: Literal["python", "c"] = "python") -> list[str]:
    """Lines of the statement ``head + code + tail``, broken at spaces so that none is longer than ``width``.

    A long Python statement is wrapped in parentheses (implicit continuation); C needs nothing. Continuation lines
    are indented by four more spaces than ``head``'s own indentation.

    Examples
    --------
    >>> wrap_statement("    x0 = ", "a + b + c", width=16)
    ['    x0 = (a + b', '        + c)']
    """
    line = f"{head}{code}{tail}"
    if len(line) <= width:
        return [line]
    indent = " " * (len(head) - len(head.lstrip()) + 4)
    if language == "python":
        head, tail = f"{head}(", f"){tail}"
    pieces = code.split(" ")
    lines: list[str] = []
    current = head
    for index, piece in enumerate(pieces):
        last = index == len(pieces) - 1
        addition = piece if current in (head, indent) else f" {piece}"
        if len(current) + len(addition) + (len(tail) if last else 0) > width and current not in (head, indent):
            lines.append(current)  # the closing tail counts on the last line too
            current, addition = indent, piece
        current += addition
        if last:
            current += tail
    lines.append(current)
    return lines


def comment_lines(text: str, *, continuation: str = "", width: int = LINE_WIDTH) -> tuple[str, ...]:
    r"""``text`` as the body of ``#   `` comment lines, broken at spaces; ``continuation`` ends every broken line.

    A shell command keeps working when copied if ``continuation`` is ``" \\"``; a Python call needs nothing.

    Examples
    --------
    >>> comment_lines("symjac codegen planar2r --target numpy", continuation=" \\", width=30)
    ('symjac codegen planar2r \\', '    --target numpy')
    """
    room = width - len("#   ")
    lines: list[str] = []
    current = ""
    words = [piece for word in text.split() for piece in _pieces(word, room - 4 - len(continuation))]
    for word in words:  # any whitespace: a line break in the text must not end the comment
        candidate = f"{current} {word}" if current.strip() else f"{current}{word}"
        if len(candidate) + len(continuation) > room and current.strip():
            lines.append(current + continuation)
            current = f"    {word}"
        else:
            current = candidate
    lines.append(current)
    return tuple(lines)


def _pieces(word: str, room: int) -> list[str]:
    """``word`` cut to fit ``room``.

    First after an opening parenthesis (a Python call stays valid across the lines), then, for a path longer than a
    line, every ``room`` characters (join those lines to use it).
    """
    if len(word) <= room:
        return [word]
    pieces = [part + "(" for part in word.split("(")[:-1]] + [word.split("(")[-1]]
    merged: list[str] = []
    for part in pieces:
        if merged and len(merged[-1]) + len(part) <= room:
            merged[-1] += part
        else:
            merged.append(part)
    return [chunk for part in merged for chunk in (part[i:i + room] for i in range(0, len(part), room))]


def tuple_literal(items: Iterable[str]) -> str:
    """Python source of a tuple of already printed items: ``(a,)`` for one, ``(a, b)`` for more."""
    entries = list(items)
    return f"({entries[0]},)" if len(entries) == 1 else f"({', '.join(entries)})"


def tuple_lines(head: str, items: Iterable[str], *, width: int = LINE_WIDTH) -> list[str]:
    """``head`` followed by the tuple of ``items``: one line if it fits, else one item group per line (black style).

    Examples
    --------
    >>> tuple_lines("X = ", ["1", "2"])
    ['X = (1, 2)']
    >>> tuple_lines("X = ", ["10", "20", "30"], width=12)
    ['X = (', '    10, 20,', '    30,', ')']
    """
    entries = list(items)
    line = head + tuple_literal(entries)
    if len(line) <= width:
        return [line]
    indent = " " * (len(head) - len(head.lstrip()) + 4)
    lines = [f"{head}("]
    current = indent
    for entry in entries:
        addition = f"{entry}," if current == indent else f" {entry},"
        if len(current) + len(addition) > width and current != indent:
            lines.append(current)
            current, addition = indent, f"{entry},"
        current += addition
    lines += [current, f"{indent[:-4]})"]
    return lines


def indices(shape: tuple[int, ...]) -> list[str]:
    """Subscripts of every entry in row-major order: ``...`` for a scalar, ``3`` for a vector, ``1, 2``, ``1, 2, 0``."""
    if not shape:
        return ["..."]
    subscripts = [""]
    for extent in shape:
        subscripts = [f"{head}, {i}" if head else str(i) for head in subscripts for i in range(extent)]
    return subscripts


def entry_names(lowered: LoweredFunction, names: SymbolNames, symbols: Sequence[sp.Symbol]) -> list[str]:
    """Names to unpack an argument into; entries the function never reads get a leading underscore (ruff RUF059)."""
    used = lowered.used_symbols
    return [names.mapping[s] if s in used else f"_{names.mapping[s]}" for s in symbols]


def unpack(names: Sequence[str], value: str, indent: str) -> list[str]:
    """``a, b, c = value``, or a parenthesised target list over several lines if that is too long."""
    line = f"{indent}{', '.join(names)}{',' if len(names) == 1 else ''} = {value}"
    if len(line) <= LINE_WIDTH:
        return [line]
    tail = f" = {value}"
    lines = tuple_lines(indent, names, width=LINE_WIDTH - len(tail))  # "(", the names a group per line, ")"
    lines[-1] += tail
    return lines


def input_lines(parameters: Sequence[sp.Symbol], lowered: LoweredFunction, names: SymbolNames, indent: str
                ) -> list[str]:
    """Unpack the argument rows (and the ``parameters``, the module's parameter symbols) into the local names."""
    lines: list[str] = []
    for argument, symbols in lowered.inputs:
        lines += unpack(entry_names(lowered, names, symbols), argument, indent)
    if parameters:
        lines += unpack(entry_names(lowered, names, parameters), "parameters", indent)
    return lines


def angle_lines(lowered: LoweredFunction, names: SymbolNames, printer: _Printer, indent: str, module: str,
                pair: str | None = None) -> list[str]:
    """One sine and one cosine per joint angle the expressions use (``pair(a)`` gives both at once if set)."""
    lines: list[str] = []
    used = lowered.used_symbols
    for sine, cosine, angle in lowered.angles:
        text = printer.doprint(angle)
        if pair is not None and sine in used and cosine in used:
            lines.append(f"{indent}{names.mapping[sine]}, {names.mapping[cosine]} = {pair}({text})")
            continue
        if sine in used:
            lines.append(f"{indent}{names.mapping[sine]} = {module}sin({text})")
        if cosine in used:
            lines.append(f"{indent}{names.mapping[cosine]} = {module}cos({text})")
    return lines


def temporary_lines(lowered: LoweredFunction, names: SymbolNames, printer: _Printer, indent: str) -> list[str]:
    """The common subexpressions, one assignment each, in CSE order."""
    lines: list[str] = []
    for symbol, expr in lowered.temporaries:
        lines += wrap_statement(f"{indent}{names.mapping[symbol]} = ", printer.doprint(expr))
    return lines


def check_layout(files: Mapping[str, str], width: int = LINE_WIDTH) -> Mapping[str, str]:
    """``files`` as they are, once no line is wider than ``width`` or ends in spaces.

    Anything else is an internal error of a template: generated files must be lint-clean in their language.
    """
    for name, text in files.items():
        for number, line in enumerate(text.splitlines(), start=1):
            if len(line) > width or line != line.rstrip():
                raise CodegenError(f"internal error: {name} line {number} is too long or has trailing spaces")
    return files

r"""Long results broken to fit a page, the way a textbook breaks them: short matrices, named entries, "where" lines.

A matrix wider than the page keeps its shape: its widest entries are replaced by names (:math:`r_{11}`, :math:`J_{23}`,
:math:`\tau_1`) and listed below it, each ``name = value`` on its own line of an ``align*``, a value too long for one
line continued on the next ones, broken before a ``+`` or ``-`` (inside parentheses if it has to). A column vector
whose entries are all too long is listed component by component. Widths are estimated from the LaTeX (in points,
10 pt Computer Modern), on the safe side, against :data:`TEXT_WIDTH`.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import sympy as sp

from symjac.printing.latex import TextbookLatexPrinter
from symjac.printing.shorthand import file_decimal, textbook_factors

__all__ = ["TEXT_WIDTH", "Display", "break_tex", "entry_namer", "fit_equation", "fit_side_by_side", "tex_width",
           "with_definitions"]

TEXT_WIDTH = 680.0
"""Points available for a display: a landscape US-letter page with 1.5 cm margins is 709 pt wide."""

_LINE = TEXT_WIDTH - 30.0  # continuation lines start after a \quad and the alignment point
_COLUMN_GAP = 10.0  # 2 \arraycolsep
_BRACKETS = 16.0

_GLYPH = {"+": 12.5, "-": 12.5, "=": 14.0, ",": 4.5, ";": 4.5, "(": 4.0, ")": 4.0, "[": 3.0, "]": 3.0,
          "|": 3.0, " ": 0.0, "&": 0.0, "'": 3.0, ".": 3.0, "<": 14.0, ">": 14.0, "/": 5.0}
_COMMANDS = {"left": 0.0, "right": 0.0, "bigl": 0.0, "bigr": 0.0, ",": 1.7, ";": 2.8, "quad": 10.0, "qquad": 20.0,
             "cdot": 8.0, "geq": 14.0, "leq": 14.0, "neq": 14.0, "to": 14.0, "times": 12.5, "pi": 6.0,
             "omega": 6.5, "mathrm": 0.0, "operatorname": 0.0, "text": 0.0, "dot": 0.0, "ddot": 0.0, "hat": 0.0,
             "partial": 6.0, "det": 16.0, "sin": 15.0, "cos": 17.0, "tan": 17.0, "operatorname*": 0.0}
_PREFIX = 2000  # characters of a long expression measured first (a line holds about a hundred)
_TOKEN = re.compile(r"\\[A-Za-z]+\*?|\\.|[{}^_]|[^\\{}^_]")


def _group(tokens: list[str], start: int) -> tuple[list[str], int]:
    """The tokens of the argument starting at ``start`` (a braced group or one token) and the index after it."""
    if start >= len(tokens):
        return [], start
    if tokens[start] != "{":
        return [tokens[start]], start + 1
    depth, index = 0, start
    while index < len(tokens):
        depth += {"{": 1, "}": -1}.get(tokens[index], 0)
        if depth == 0:
            return tokens[start + 1:index], index + 1
        index += 1
    return tokens[start + 1:], len(tokens)


def _width(tokens: list[str], scale: float, cap: float = math.inf) -> float:
    """The width of ``tokens``; past ``cap`` it stops early and returns a width above ``cap``, not the whole one."""
    total, index = 0.0, 0
    while index < len(tokens):
        token = tokens[index]
        index += 1
        if token in ("^", "_"):
            argument, index = _group(tokens, index)
            total += _width(argument, scale * 0.72, cap)
        elif token == "\\frac":
            numerator, index = _group(tokens, index)
            denominator, index = _group(tokens, index)
            total += max(_width(numerator, scale * 0.8, cap), _width(denominator, scale * 0.8, cap)) + 3.0 * scale
        elif token == "\\sqrt":
            argument, index = _group(tokens, index)
            total += _width(argument, scale, cap) + 9.0 * scale
        elif token in ("\\text", "\\mathrm", "\\operatorname"):
            argument, index = _group(tokens, index)
            total += 5.0 * scale * sum(1 for t in argument if t not in "{}")
        elif token in ("{", "}"):
            continue
        elif token.startswith("\\"):
            total += _COMMANDS.get(token[1:], 6.5) * scale
        else:
            total += _GLYPH.get(token, 6.2) * scale
        if total > cap:
            break
    return total


def _wider_than(tex: str, limit: float) -> bool:
    """Whether ``tex_width(tex) > limit``, without measuring all of a long expression.

    A prefix cut at a space is never wider than the whole (every token adds a width of at least zero), so a prefix
    already too wide settles it; the measuring stops as soon as it passes ``limit``.
    """
    if len(tex) > _PREFIX:
        cut = tex.rfind(" ", 0, _PREFIX)
        if cut > 0 and _width(_TOKEN.findall(tex[:cut]), 1.0, limit) > limit:
            return True
    return _width(_TOKEN.findall(tex), 1.0, limit) > limit


def tex_width(tex: str, scale: float = 1.0) -> float:
    r"""Estimated width in points of LaTeX math ``tex`` (slightly more than TeX gives; ``\frac`` in text style).

    Examples
    --------
    >>> 20 < tex_width("a_{2} c_{2} + a_{3} c_{23}") < 60
    True
    """
    return _width(_TOKEN.findall(tex), scale)


@dataclass(frozen=True)
class Display:
    r"""One equation laid out: the display (``\[...\]`` body, or ``align*`` lines) and the "where" lines after it."""

    main: str
    lines: tuple[str, ...] = ()
    where: tuple[str, ...] = ()

    def body(self) -> str:
        """The LaTeX of the whole layout: the equation, then ``where`` and its aligned definitions."""
        text = rf"\[ {self.main} \]" if self.main else ""
        if self.lines:
            text += "\\begin{align*}\n" + " \\\\\n".join(self.lines) + "\n\\end{align*}"
        if self.where:
            text += "\n\\noindent where\n\\begin{align*}\n" + " \\\\\n".join(self.where) + "\n\\end{align*}"
        return text.strip()


class _BreakingPrinter(TextbookLatexPrinter):
    """The textbook printer, plus pieces of a long expression with the places it may break between them.

    One printer lays out a whole matrix: its entries share subexpressions, each printed (and measured) once.
    """

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__(settings)
        self._widths: dict[str, float] = {}

    def width(self, tex: str) -> float:
        """:func:`tex_width`, remembered: a long sum is measured at every level it is broken at."""
        found = self._widths.get(tex)
        if found is None:
            found = self._widths[tex] = tex_width(tex)
        return found

    def pieces(self, expr: sp.Expr, limit: float) -> list[str]:
        """LaTeX chunks; a line may break before any chunk that starts with a sign (``"+ ..."``, ``"- ..."``)."""
        tex = self.doprint(expr)
        if not _wider_than(tex, limit):
            return [tex]
        if isinstance(expr, sp.Add):
            chunks: list[str] = []
            for number, term in enumerate(self._as_ordered_terms(expr)):
                negative = term.could_extract_minus_sign()
                parts = self.pieces(-term if negative else term, limit)
                sign = "- " if negative else ("+ " if number else "")
                chunks += [sign + parts[0], *parts[1:]] if number or negative else parts
            return chunks
        if isinstance(expr, sp.Mul):
            numerator, denominator = sp.fraction(expr)
            if denominator != 1:
                return [rf"\frac{{1}}{{{self.doprint(denominator)}}}", *self._grouped(numerator, limit)]
            coefficient, rest = expr.as_coeff_Mul()
            if coefficient.is_Float or file_decimal(abs(coefficient)) is not None:  # 0.4318 (...), --numeric
                head = ("- " if coefficient < 0 else "") + self.doprint(abs(coefficient))
                return _glue([head, *(self._grouped(rest, limit) if rest.is_Add else self.pieces(rest, limit))])
            ordered = textbook_factors(expr)
            if ordered is not None:
                coefficient, factors = ordered
                head = ("- " if coefficient < 0 else "") + (str(abs(coefficient)) if abs(coefficient) != 1 else "")
                chunks = [head.strip()] if head.strip() else []
                for factor in factors:
                    chunks += self._grouped(factor, limit) if factor.is_Add else self.pieces(factor, limit)
                return _glue(chunks)
        if isinstance(expr, sp.Function) and len(expr.args) == 1 and r"{\left(" in tex and tex.endswith(r"\right)}"):
            return self._applied(expr, tex[:tex.index(r"{\left(")], limit)
        return [tex]

    def _applied(self, expr: sp.Function, head: str, limit: float) -> list[str]:
        r"""A function of one argument too long for a line, as pieces that break at the argument's signs.

        ``asin(N / D)`` becomes ``\operatorname{asin}\Bigl(\bigl(N\bigr) \big/ \bigl(D\bigr)\Bigr)``: unpaired
        delimiters may end one line and open the next, where ``\left``/``\right`` must close on the line they open.
        """
        numerator, denominator = sp.fraction(expr.args[0])
        chunks = self.pieces(numerator, limit)
        if denominator != 1:
            chunks = [*_wrapped(chunks, r"\bigl(", r"\bigr)"),
                      *_wrapped(self.pieces(denominator, limit), r"\big/ \bigl(", r"\bigr)")]
        return _glue(_wrapped(chunks, head + r"\Bigl(", r"\Bigr)"))

    def _grouped(self, expr: sp.Expr, limit: float) -> list[str]:
        inner = self.pieces(expr, limit)
        if len(inner) == 1:
            return [rf"\left({inner[0]}\right)" if expr.is_Add else inner[0]]
        return _glue([r"\bigl(" + inner[0], *inner[1:-1], inner[-1] + r"\bigr)"])


def _wrapped(chunks: list[str], left: str, right: str) -> list[str]:
    """``chunks`` with ``left`` before the first and ``right`` after the last."""
    if len(chunks) == 1:
        return [left + chunks[0] + right]
    return [left + chunks[0], *chunks[1:-1], chunks[-1] + right]


def _glue(chunks: list[str]) -> list[str]:
    """Join chunks that do not start with a sign to the chunk before (a line breaks only before + or -)."""
    glued: list[str] = []
    for chunk in chunks:
        if glued and not chunk.startswith(("+ ", "- ")):
            glued[-1] = f"{glued[-1]} {chunk}"
        else:
            glued.append(chunk)
    return glued


def _lines(expr: sp.Expr, first: float, printer: _BreakingPrinter) -> list[str]:
    """``expr`` as lines: the first at most ``first`` points wide, the others :data:`_LINE` (else :func:`break_tex`)."""
    lines: list[str] = []
    current, room = "", first
    for chunk in printer.pieces(expr, _LINE * 0.9):
        if current and tex_width(current) + printer.width(chunk) > room:
            lines.append(current)
            current, room = "", _LINE
        current = f"{current} {chunk}".strip()
    fitted: list[str] = []  # a piece the structure gave no break in is broken as text: the page never overflows
    for line in [*lines, current]:
        room = first if not fitted else _LINE
        fitted += break_tex(line, room, _LINE) if _wider_than(line, room) else [line]
    return fitted


def break_tex(tex: str, first: float = TEXT_WIDTH, rest: float = _LINE) -> list[str]:
    r"""LaTeX math ``tex`` as lines at most ``first`` (then ``rest``) points wide, broken before a ``+`` or ``-``.

    The fallback of the layout, on text alone: ``\left( ... \right)`` pairs become ``\bigl( ... \bigr)`` (which may
    end one line and open the next), a fraction wider than half a line ``\bigl(N\bigr) \big/ \bigl(D\bigr)``, the
    braces around a function's argument (``\operatorname{asin}{\left(...\right)}``) are dropped, and the text is
    broken before any binary sign outside braces and outside any other ``\left``/``\right`` pair.

    Examples
    --------
    >>> lines = break_tex(r"a \left(" + " + ".join(f"x_{{{i}}}" for i in range(60)) + r"\right)", 300.0, 300.0)
    >>> lines[0][:12], lines[1][:2], len(lines) > 2 and all(tex_width(line) <= 300.0 for line in lines)
    ('a \\bigl(x_{0', '+ ', True)
    """
    tokens = _unbracketed(_TOKEN.findall(tex))
    breaks, depth, previous = [0], 0, "="
    for index, token in enumerate(tokens):
        if token in ("+", "-") and depth == 0 and previous not in _NO_BREAK_AFTER:
            breaks.append(index)
        depth += {"{": 1, "}": -1, "\\left": 1, "\\right": -1}.get(token, 0)
        previous = token if token.strip() else previous
    lines: list[str] = []
    start, room = 0, first
    for before, after in itertools.pairwise([*breaks, len(tokens)]):
        if before > start and _width(tokens[start:after], 1.0, room) > room:
            lines.append("".join(tokens[start:before]).strip())
            start, room = before, rest
    return [line for line in [*lines, "".join(tokens[start:]).strip()] if line]


_NO_BREAK_AFTER = frozenset({"(", "[", "{", "+", "-", "=", "&", "^", "_", ",", "\\bigl", "\\Bigl", "\\left"})
_FUNCTIONS = frozenset(rf"\{name}" for name in ("sin", "cos", "tan", "cot", "sec", "csc", "log", "ln", "exp", "arcsin",
                                                  "arccos", "arctan"))


def _slashed(tokens: list[str], wide: float) -> list[str]:
    r"""Tokens with each ``\frac{N}{D}`` wider than ``wide`` written ``\bigl(N\bigr) \big/ \bigl(D\bigr)``."""
    out: list[str] = []
    index = 0
    while index < len(tokens):
        numerator, after = _group(tokens, index + 1) if tokens[index] == "\\frac" else ([], index)
        denominator, end = _group(tokens, after) if numerator else ([], index)
        if numerator and max(_width(numerator, 1.0), _width(denominator, 1.0)) > wide:
            out += [r"\bigl", "(", *_slashed(numerator, wide), r"\bigr", ")", " ", r"\big/", " ", r"\bigl", "(",
                    *_slashed(denominator, wide), r"\bigr", ")"]
            index = end
        else:
            out.append(tokens[index])
            index += 1
    return out


def _unbracketed(tokens: list[str]) -> list[str]:
    r"""``\left(``/``\right)`` as ``\bigl(``/``\bigr)``, wide fractions slashed, ``\sin{\bigl(x\bigr)}`` unbraced."""
    big = {("\\left", "("): "\\bigl", ("\\right", ")"): "\\bigr"}
    out = _slashed([big.get((t, n), t) for t, n in zip(tokens, [*tokens[1:], ""], strict=True)], _LINE / 2)
    opened: list[int] = []
    matching: dict[int, int] = {}
    for index, token in enumerate(out):
        if token == "{":
            opened.append(index)
        elif token == "}" and opened:
            start = matching[index] = opened.pop()
            name = out[start - 1] if start else ""
            if name == "}" and start - 1 in matching and out[matching[start - 1] - 1] == "\\operatorname":
                name = "\\operatorname"
            if name in _FUNCTIONS | {"\\operatorname"} and out[start + 1:start + 3] == ["\\bigl", "("] \
                    and out[index - 2:index] == ["\\bigr", ")"]:
                out[start] = out[index] = ""
    return [token for token in out if token]


def _aligned(name: str, expr: sp.Expr, printer: _BreakingPrinter) -> str:
    r"""``name &= value``, continued on ``&\quad`` lines when too long."""
    lines = _lines(expr, TEXT_WIDTH - tex_width(name) - 20.0, printer)
    return " \\\\\n".join([f"{name} &= {lines[0]}", *(rf"&\quad {line}" for line in lines[1:])])


def entry_namer(lhs: str, matrix: sp.MatrixBase) -> Callable[[int, int], str]:
    r"""Names for the entries of ``lhs``: a pose's :math:`r_{11}..p_z`, a matrix's :math:`J_{23}` or :math:`(J_x)_{23}`.

    A 3-vector's components are :math:`{}^{3}f_{3x}`, other vectors' :math:`\tau_{1}`.

    Examples
    --------
    >>> entry_namer("{}^{0}J", sp.zeros(6, 2))(1, 0)
    'J_{21}'
    """
    rows, cols = matrix.shape
    name = lhs.split("=")[0].strip()
    if name.startswith(r"\frac"):
        name = "h"
    if cols == 1:
        if rows == 3 and (match := re.fullmatch(r"(.*)_\{([^{}]*)\}", name)):
            return lambda i, j: f"{match.group(1)}_{{{match.group(2)}{'xyz'[i]}}}"
        return lambda i, j: f"{_letter(name)}_{{{i + 1}}}"
    letter = _letter(name)
    if (rows, cols) == (4, 4) and letter == "T":
        return lambda i, j: f"p_{{{'xyz'[i]}}}" if j == 3 else f"r_{{{i + 1}{j + 1}}}"
    comma = "," if max(rows, cols) > 9 else ""
    return lambda i, j: f"{letter}_{{{i + 1}{comma}{j + 1}}}"


def _letter(name: str) -> str:
    """``{}^{0}_{6}T -> T``, ``J_x -> (J_x)`` (a name with a subscript is wrapped before it gets another)."""
    letter = re.sub(r"^\{\}\^\{[^{}]*\}(_\{[^{}]*\})?", "", name).strip() or "m"
    return f"({letter})" if "_" in letter else letter


def _matrix_width(widths: Sequence[Sequence[float]]) -> float:
    columns = [max(column) for column in zip(*widths, strict=True)]
    return sum(columns) + _COLUMN_GAP * (len(columns) - 1) + _BRACKETS


def fit_equation(lhs: str, rhs: sp.Basic) -> Display:
    r"""``lhs = rhs`` laid out to fit :data:`TEXT_WIDTH` (the entries it names: :func:`entry_namer`).

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> fit_equation("y", x).main
    'y = x'
    """
    printer = _BreakingPrinter()
    head = f"{lhs} = " if lhs else ""
    room = TEXT_WIDTH - tex_width(head)
    if not isinstance(rhs, sp.MatrixBase):
        tex = printer.doprint(rhs)
        if tex_width(tex) <= room:
            return Display(head + tex)
        return Display("", (_aligned(lhs, rhs, printer),))
    entries = [[printer.doprint(rhs[i, j]) for j in range(rhs.cols)] for i in range(rhs.rows)]
    widths = [[printer.width(e) for e in row] for row in entries]
    if _matrix_width(widths) <= room:
        return Display(head + printer.doprint(rhs))
    namer = entry_namer(lhs, rhs)
    for limit in sorted({w for row in widths for w in row}, reverse=True):
        named = {(i, j) for i in range(rhs.rows) for j in range(rhs.cols) if widths[i][j] >= limit}
        shown = [[tex_width(namer(i, j)) if (i, j) in named else widths[i][j] for j in range(rhs.cols)]
                 for i in range(rhs.rows)]
        if _matrix_width(shown) <= room:
            break
    where = tuple(_aligned(namer(i, j), rhs[i, j], printer) for i in range(rhs.rows) for j in range(rhs.cols)
                  if (i, j) in named)
    if rhs.cols == 1 and len(named) == rhs.rows:  # a vector: its components are the equations
        return Display("", where)
    cells = r" \\ ".join(" & ".join(namer(i, j) if (i, j) in named else entries[i][j] for j in range(rhs.cols))
                         for i in range(rhs.rows))
    return Display(head + r"\begin{bmatrix}" + cells + r"\end{bmatrix}", (), where)


def with_definitions(display: Display, definitions: Sequence[tuple[sp.Symbol, sp.Expr]]) -> Display:
    r"""``display`` with ``name = value`` lines for ``definitions`` after its own "where" lines (a nested result's).

    Each definition is broken over lines like a named entry (:func:`fit_equation`), so a long one fits the page.

    Examples
    --------
    >>> w1, x = sp.Symbol("w_1"), sp.Symbol("x")
    >>> with_definitions(Display("y = w_{1}"), [(w1, 2 * x)]).where
    ('w_{1} &= 2 x',)
    """
    if not definitions:
        return display
    printer = _BreakingPrinter()
    lines = tuple(_aligned(printer.doprint(symbol), value, printer) for symbol, value in definitions)
    return Display(display.main, display.lines, (*display.where, *lines))


def fit_side_by_side(texts: Sequence[str]) -> str:
    r"""Short equations on one line joined by ``,\quad``, or one per line of a ``gather*`` when they do not fit.

    An equation wider than the page is a ``split`` of lines broken by :func:`break_tex`.
    """
    if sum(tex_width(t) for t in texts) + 25.0 * (len(texts) - 1) <= TEXT_WIDTH:
        joined = r",\quad ".join(texts)
        return rf"\[ {joined} \]"
    rows = [text if not _wider_than(text, TEXT_WIDTH) else "\\begin{split}" + " \\\\\n&\\quad ".join(
        break_tex(text.replace(" = ", " &= ", 1) if " = " in text else "&" + text, TEXT_WIDTH - 20.0)) + "\\end{split}"
        for text in texts]
    return "\\begin{gather*}\n" + " \\\\\n".join(rows) + "\n\\end{gather*}"

r"""One renderer for every result: a :class:`Document` of captioned equations, as LaTeX, pretty text or JSON.

A CLI command (or a notebook) builds a :class:`Document` (a title, blocks of caption + math, and the JSON data) and
:func:`render` lays it out:

* ``latex``: one line per equation (captions as ``%`` comments when the document asks for them), or with
  ``standalone`` a complete document through the ``documents/latex_document.tex.j2`` template;
* ``pretty``: each block's caption, then its equations in Unicode (``name =`` above a matrix);
* ``json``: the document's data, indented, built only then (so a LaTeX or pretty result never pays for it) and from
  the document itself: the robot's metadata, the document's :attr:`~Document.facts`, then every equation that names
  its :class:`JsonKey` (:func:`symjac.printing.json.document_data`). A result is described once; no format has a
  builder of its own.

A LaTeX result longer than :data:`LATEX_LIMIT` is more than anyone reads on a terminal: :func:`check_latex_size`
refuses it unless it goes to a file.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import sympy as sp

from symjac._version import __version__
from symjac.deprecation import renamed
from symjac.errors import ArgumentError
from symjac.kinematics.chain import Frame
from symjac.model.robot import Robot
from symjac.printing.latex import LatexTooLargeError, TextbookLatexPrinter, escape_text, latex, latex_size_limit
from symjac.printing.tables import parameter_table_latex, parameter_table_text

# Each format imports its own printer when used: a LaTeX result loads no pretty printer, page layout or jinja2.

__all__ = [
    "FORMATS",
    "LATEX_LIMIT",
    "Block",
    "Document",
    "Equation",
    "Inline",
    "JsonKey",
    "LatexTooLargeError",
    "ParameterTable",
    "Prescripted",
    "Style",
    "blocks_as_pairs",
    "caption_text",
    "check_latex_size",
    "equation_latex",
    "equation_text",
    "math_text",
    "render",
    "render_for_terminal",
]

# The names these had before they were convention-neutral (a DH table is one convention's parameter table).
__getattr__ = renamed("symjac.printing.document", {
    "DHTable": "ParameterTable",
})

FORMATS = ("latex", "pretty", "json")
"""Output formats of a document: LaTeX, Unicode text, JSON."""
Style = Literal["latex", "pretty"]
LATEX_LIMIT = 200_000
"""Bytes of LaTeX written to a terminal at most; a longer result is written only to a file (``-o FILE``)."""


@dataclass(frozen=True)
class Prescripted:
    r"""A name with prescripts, :math:`{}^{sup}_{sub}X`: a transform :math:`{}^{0}_{6}T`, a Jacobian :math:`{}^{3}J`.

    Outputs that typeset names themselves (MathML) use it; LaTeX and text use :class:`Equation`'s own spellings.
    """

    letter: str
    sup: Frame
    sub: Frame | None = None


@dataclass(frozen=True)
class JsonKey:
    """Where an equation's right side goes in the JSON form of its document (:func:`.json.document_data`).

    ``name`` is the key of the right side as SymPy strings: rows of strings (a matrix), or with ``flat`` one list
    (a vector's entries). ``latex``, when given, is the key of the equation as one LaTeX line beside it.
    ``item``: the equation is one of several under ``name`` (and ``latex``), a mapping ``item -> value``;
    ``stacked`` then also writes every item's matrix, stacked along a last axis, under that key
    (``data[stacked][i][j][k]`` is item k's entry ``[i, j]``). ``record``: the equation is one of a list under
    ``name``, each ``{"name": text, "latex": ..., "entries": [...]}`` (propagation steps).
    """

    name: str
    latex: str | None = None
    item: str | None = None
    flat: bool = False
    record: bool = False
    stacked: str | None = None


@dataclass(frozen=True)
class Equation:
    r"""``lhs = rhs``: the left side spelled for LaTeX (``{}^{0}J``) and for text (``J_0``), the right side SymPy.

    ``rhs`` is one SymPy object, or a tuple of them printed side by side (a product :math:`E(x)\,J_0`). With empty
    names the right side prints alone (a solution ``theta2 = 0`` is already an equation). ``key`` says where it goes
    in the JSON form (none: it is printed only). ``where``: the ``(w_k, definition)`` pairs of the intermediates the
    right side is the first to use, printed after it (``where w_1 = ...``); :func:`.nested.named_document` fills it.
    """

    tex: str
    text: str
    rhs: Any
    name: Prescripted | None = None
    key: JsonKey | None = None
    where: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()


@dataclass(frozen=True)
class ParameterTable:
    """The parameter table of ``robot`` in its convention: DH parameters, screw axes, or origins and axes."""

    robot: Robot


Math = Equation | ParameterTable


@dataclass(frozen=True)
class Inline:
    r"""Math written by hand for a caption: ``tex`` inside ``$...$`` in LaTeX, ``text`` in pretty output.

    ``expr``, when given, is the same math as a SymPy object, for outputs that typeset SymPy themselves (MathML).
    """

    tex: str
    text: str
    expr: sp.Basic | None = None


@dataclass(frozen=True)
class Block:
    """A caption and the math under it (several equations print side by side in LaTeX, one per line in text).

    ``caption`` is words with inline math: strings are text (escaped for LaTeX), SymPy objects and :class:`Inline`
    math in the output's notation (``$...$`` in LaTeX).
    """

    caption: tuple[str | sp.Basic | Inline, ...] = ()
    math: tuple[Math, ...] = ()


@dataclass(frozen=True)
class Document:
    """A result ready to render: ``title`` and ``robot`` (its name) head a standalone document.

    Its JSON form is built from the document itself (:func:`symjac.printing.json.document_data`): ``model``'s
    metadata (the robot), ``facts`` (JSON-ready values beside the math: frame, point, shape, row names), then each
    equation of the blocks and of ``extra`` (equations only the JSON form carries) that has a :class:`JsonKey`.
    ``data``, when given, replaces that form: the JSON-ready mapping, or a function that builds it (called only for
    ``json``), for a result whose data is no equation (a singularity report). ``comments`` keeps the captions in
    bare LaTeX output as ``%`` lines (for results whose captions explain, such as singularities); otherwise bare
    LaTeX is the equations alone, one per line.
    """

    title: str
    robot: str
    blocks: tuple[Block, ...]
    data: Mapping[str, Any] | Callable[[], Mapping[str, Any]] | None = None
    comments: bool = False
    facts: Mapping[str, Any] = field(default_factory=dict)
    model: Robot | None = None
    extra: tuple[Equation, ...] = ()

    def json_data(self) -> Mapping[str, Any]:
        """The JSON-ready data, built now: ``data`` (called if a function), else the document's own form."""
        if self.data is None:
            from symjac.printing import json as json_form  # looked up when called: the JSON code loads only here

            return json_form.document_data(self)
        return self.data() if callable(self.data) else self.data


def check_latex_size(text: str, hint: str, limit: int | None = None) -> None:
    """Refuse ``text`` longer than ``limit`` bytes (default :data:`LATEX_LIMIT`), in one line ending with ``hint``."""
    limit = LATEX_LIMIT if limit is None else limit
    size = len(text.encode("utf-8"))
    if size > limit:
        raise LatexTooLargeError(_too_large(f"{size / 1000:,.0f} KB, more than", limit, hint))


def render_for_terminal(document: Document, fmt: str, standalone: bool, hint: str) -> str:
    """:func:`render`, refusing LaTeX longer than :data:`LATEX_LIMIT` (:func:`check_latex_size`).

    A matrix stops printing as soon as its entries pass the limit (:func:`~.latex.latex_size_limit`), so a result
    too long to show is refused for a fraction of the cost of printing it.
    """
    if fmt != "latex":
        return render(document, fmt, standalone)
    try:
        with latex_size_limit(LATEX_LIMIT):
            text = render(document, fmt, standalone)
    except LatexTooLargeError:
        raise LatexTooLargeError(_too_large("more than", LATEX_LIMIT, hint)) from None
    check_latex_size(text, hint)
    return text


def _too_large(size: str, limit: int, hint: str) -> str:
    return (f"the LaTeX is {size} {limit / 1000:,.0f} KB: nobody reads that on a terminal; write it to a file with "
            f"-o FILE, or {hint}")


def _check(style: str) -> None:
    if style not in ("latex", "pretty"):
        raise ArgumentError(f"style must be 'latex' or 'pretty', got {style!r}")


def caption_text(block: Block, style: Style) -> str:
    """The caption in ``style``: LaTeX text (words escaped, math in ``$...$``) or plain Unicode text."""
    _check(style)

    def show(part: str | sp.Basic | Inline) -> str:
        if isinstance(part, str):
            return escape_text(part) if style == "latex" else part
        if isinstance(part, Inline):
            return f"${part.tex}$" if style == "latex" else part.text
        if style == "latex":
            return f"${latex(part)}$"
        return _one_line(part)

    return "".join(show(part) for part in block.caption)


def _one_line(expr: sp.Basic) -> str:
    """Unicode text of ``expr`` on one line.

    A caption shows √2/2, not a 2-D fraction, and θ = -π/2 (each side of an equation printed on its own), not
    Eq(theta, -pi/2): the pretty form when it fits one line, else mathematics written linearly
    (:func:`~symjac.printing.pretty.one_line`), never Python syntax.
    """
    from symjac.printing.pretty import one_line, pretty

    if isinstance(expr, sp.Equality):
        return f"{_one_line(expr.lhs)} = {_one_line(expr.rhs)}"
    text = pretty(expr)
    return text if "\n" not in text else one_line(expr)


def equation_latex(equation: Equation) -> str:
    r"""One equation as a LaTeX line: ``{}^{0}J = \begin{bmatrix}...``.

    An equation with "where" lines (:attr:`Equation.where`) is one ``gathered`` block: the equation, then
    ``\text{where }`` and an ``aligned`` block of definitions, one per line.
    """
    parts = equation.rhs if isinstance(equation.rhs, tuple) else (equation.rhs,)
    rhs = " ".join(latex(part) for part in parts)
    text = f"{equation.tex} = {rhs}" if equation.tex else rhs
    if not equation.where:
        return text
    printer = TextbookLatexPrinter()  # one printer: the definitions share their subexpressions
    lines = (r", \\" + "\n").join(f"{printer.doprint(symbol)} &= {printer.doprint(value)}"
                                   for symbol, value in equation.where)
    return "\n".join([r"\begin{gathered}", rf"{text}, \\", r"\text{where } \begin{aligned}[t]", lines,
                      r"\end{aligned}", r"\end{gathered}"])


def equation_text(equation: Equation) -> str:
    """One equation in Unicode: ``name =`` above a matrix, ``name = value`` on one line for a scalar."""
    from symjac.printing.pretty import pretty, pretty_side_by_side

    if isinstance(equation.rhs, tuple):
        text = f"{equation.text} =\n{pretty_side_by_side(*equation.rhs)}"
    elif not equation.text:
        text = pretty(equation.rhs)
    elif isinstance(equation.rhs, sp.MatrixBase):
        text = f"{equation.text} =\n{pretty(equation.rhs)}"
    else:
        text = pretty(sp.Eq(sp.Symbol(equation.text), equation.rhs, evaluate=False))
    if not equation.where:
        return text
    lines = [pretty(sp.Eq(symbol, value, evaluate=False)) for symbol, value in equation.where]
    return "\n".join([text, "where", *lines])


def math_text(block: Block, style: Style) -> str:
    r"""The block's math in ``style`` (``""`` when it has none); LaTeX equations joined by ``,\quad``."""
    _check(style)
    if style == "latex":
        return r",\quad ".join(
            parameter_table_latex(m.robot) if isinstance(m, ParameterTable) else equation_latex(m) for m in block.math)
    return "\n".join(parameter_table_text(m.robot).rstrip("\n") if isinstance(m, ParameterTable) else equation_text(m)
                     for m in block.math)


def render(document: Document, fmt: str, standalone: bool = False) -> str:
    """``document`` as text in ``fmt`` (one of :data:`FORMATS`); ``standalone`` makes LaTeX a whole document.

    Intermediates of a nested result are named first (:func:`.nested.named_document`): ``w_1, w_2, ...`` in the
    math, each defined once in "where" lines (in JSON, the ``definitions`` list).
    """
    if fmt == "json":
        return json.dumps(document.json_data(), indent=2) + "\n"
    from symjac.printing.nested import named_document

    document = named_document(document)
    if fmt == "pretty":
        shown = []
        for block in document.blocks:
            lines = [text for text in (caption_text(block, "pretty"), math_text(block, "pretty")) if text]
            shown.append("\n".join(lines))
        return "\n\n".join(shown) + "\n"
    if fmt != "latex":
        raise ArgumentError(f"unknown format {fmt!r}; choose one of {', '.join(FORMATS)}")
    if standalone:
        from symjac.resources import render_template

        blocks = [{"caption": caption_text(block, "latex"), "latex": _fitted(block)} for block in document.blocks]
        return render_template("documents/latex_document.tex.j2", version=__version__, robot=document.robot,
                               title=escape_text(document.title), blocks=blocks)
    return "".join(_bare_latex(block, document.comments) for block in document.blocks)


def _fitted(block: Block) -> str:
    """The block's math laid out to fit the page (:mod:`.latex_layout`), ``""`` when it has none."""
    from symjac.printing.latex_layout import TEXT_WIDTH, fit_equation, fit_side_by_side, tex_width, with_definitions

    def fitted(m: Equation) -> str:
        return with_definitions(fit_equation(m.tex, m.rhs), m.where).body()

    equations = [m for m in block.math if isinstance(m, Equation)]
    if len(block.math) == 1 and equations and not isinstance(equations[0].rhs, tuple):
        return fitted(equations[0])
    texts = [parameter_table_latex(m.robot) if isinstance(m, ParameterTable) else equation_latex(m) for m in block.math]
    if not any(m.where for m in equations) and all(tex_width(text) <= TEXT_WIDTH for text in texts):
        return fit_side_by_side(texts) if texts else ""
    return "\n".join(fitted(m) if isinstance(m, Equation) else rf"\[ {text} \]"
                     for m, text in zip(block.math, texts, strict=True))


def _bare_latex(block: Block, comments: bool) -> str:
    caption = caption_text(block, "latex") if comments else ""
    body = math_text(block, "latex")
    return (f"% {caption}\n" if caption else "") + (f"{body}\n" if body else "")


def blocks_as_pairs(blocks: Sequence[Block], style: Style) -> list[tuple[str, str]]:
    """Blocks as (caption, math) string pairs in ``style``, for notebooks that lay them out themselves.

    A nested result's intermediates are named and defined first (:func:`.nested.named_document`).
    """
    from symjac.printing.nested import named_document

    blocks = named_document(Document("", "", tuple(blocks))).blocks
    return [(caption_text(block, style), math_text(block, style)) for block in blocks]

r"""The derivation a report shows, as HTML fragments: DH table, link transforms, forward kinematics, Jacobians.

Each function returns escaped HTML holding MathML (:mod:`symjac.printing.mathml_layout` keeps every display within the
page width). :func:`method_agreement` derives the Jacobian by all four methods and compares the results exactly.
"""

from __future__ import annotations

import html
from collections.abc import Sequence
from dataclasses import dataclass
from xml.dom.minidom import Element

import sympy as sp

from symjac.deprecation import renamed
from symjac.kinematics.chain import Frame, chain_of
from symjac.kinematics.jacobian import METHODS, Method, jacobian
from symjac.model.robot import Robot
from symjac.printing.document import Block, Equation, Inline, ParameterTable, Prescripted
from symjac.printing.mathml import TextbookMathMLPrinter, math_element, mathml_node
from symjac.printing.mathml_layout import displays
from symjac.printing.tables import column_html, table_cells, table_headings

__all__ = [
    "Agreement",
    "block_html",
    "caption_html",
    "equation_html",
    "frame_symbol",
    "inline_math",
    "jacobian_symbol",
    "method_agreement",
    "parameter_table_html",
    "transform_symbol",
]

# The names these had before they were convention-neutral (a DH table is one convention's parameter table).
__getattr__ = renamed("symjac.report.content", {
    "dh_table_html": "parameter_table_html",
})


def inline_math(expr: sp.Basic) -> str:
    """``expr`` as an inline ``<math>`` element."""
    return math_element(mathml_node(expr))


def _token(printer: TextbookMathMLPrinter, frame: Frame | str) -> Element:
    element = printer.dom.createElement("mn" if isinstance(frame, int) else "mi")
    element.appendChild(printer.dom.createTextNode(str(frame)))
    return element


def _prescripted(base: str, sub: Frame | None, sup: Frame) -> Element:
    printer = TextbookMathMLPrinter()
    dom = printer.dom
    node = dom.createElement("mmultiscripts")
    letter = dom.createElement("mi")
    letter.appendChild(dom.createTextNode(base))
    node.appendChild(letter)
    node.appendChild(dom.createElement("mprescripts"))
    node.appendChild(dom.createElement("none") if sub is None else _token(printer, sub))
    node.appendChild(_token(printer, sup))
    return node


def transform_symbol(source: Frame, target: Frame) -> Element:
    r""":math:`{}^{source}_{target}T` (Craig: the pose of ``target`` relative to ``source``)."""
    return _prescripted("T", target, source)


def jacobian_symbol(frame: Frame) -> Element:
    r""":math:`{}^{k}J`, the Jacobian expressed in frame {k}."""
    return _prescripted("J", None, frame)


def frame_symbol(text: str) -> Element:
    """A plain left-hand side such as ``det J`` (each word an identifier)."""
    printer = TextbookMathMLPrinter()
    row = printer.dom.createElement("mrow")
    for number, word in enumerate(text.split()):
        if number:
            space = printer.dom.createElement("mspace")
            space.setAttribute("width", "0.3em")
            row.appendChild(space)
        identifier = printer.dom.createElement("mi")
        identifier.appendChild(printer.dom.createTextNode(word))
        row.appendChild(identifier)
    return row


def equation_html(rhs: sp.Basic, lhs: Element | None = None) -> str:
    """``lhs = rhs`` as display math; a matrix too wide for the page becomes labelled column blocks side by side."""
    shown = displays(rhs, lhs)
    if len(shown) == 1:
        return f'<div class="display">{shown[0].markup}</div>\n'
    name = "" if lhs is None else f"{math_element(lhs)} "
    parts = [f'<figure class="block"><figcaption>columns {first + 1}&#8211;{last}</figcaption>{d.markup}</figure>'
             if last - first > 1 else
             f'<figure class="block"><figcaption>column {first + 1}</figcaption>{d.markup}</figure>'
             for d in shown if d.columns is not None for first, last in [d.columns]]
    return f'<p class="note">{name}by columns (too wide for one line):</p><div class="blocks">{"".join(parts)}</div>\n'


def _caption_part_html(part: str | sp.Basic | Inline) -> str:
    """Words escaped; SymPy objects as MathML; math written by hand (:class:`Inline`) as its expression or its text."""
    if isinstance(part, str):
        return html.escape(part)
    if isinstance(part, Inline) and part.expr is None:
        return f'<span class="math-text">{html.escape(part.text)}</span>'
    if isinstance(part, Inline):
        return inline_math(part.expr)
    return inline_math(part)


def caption_html(parts: Sequence[str | sp.Basic | Inline]) -> str:
    """Caption parts (:mod:`symjac.printing.prose`) as HTML: words escaped, math as inline MathML."""
    return "".join(_caption_part_html(part) for part in parts)


def _name(name: Prescripted) -> Element:
    return _prescripted(name.letter, name.sub, name.sup)


def block_html(block: Block) -> str:
    """A :class:`~symjac.printing.document.Block` (caption with inline math, then its equations) as HTML.

    An equation's left side is its prescripted name (:math:`{}^{0}_{1}T`) when it has one, else its text. The
    "where" lines of a named nested result (:attr:`~symjac.printing.document.Equation.where`) follow it.
    """
    caption = f"<p>{caption_html(block.caption)}</p>\n" if block.caption else ""
    math = []
    for item in block.math:
        if isinstance(item, ParameterTable):
            math.append(parameter_table_html(item.robot))
        elif isinstance(item, Equation):
            lhs = _name(item.name) if item.name else frame_symbol(item.text) if item.text else None
            rhs = item.rhs if not isinstance(item.rhs, tuple) else item.rhs[-1]
            math.append(equation_html(rhs, lhs))
            if item.where:  # a nested result's intermediates (named by symjac.printing.nested.named_document)
                math.append('<p class="note">where</p>')
                math += [equation_html(value, mathml_node(symbol)) for symbol, value in item.where]
    return caption + "".join(math)


def parameter_table_html(robot: Robot) -> str:
    """The robot's table (DH rows, or a general chain's origins and axes) as HTML with MathML entries.

    The same columns and entries as the LaTeX table (:func:`symjac.printing.tables.table_cells`).
    """
    head = "".join(f"<th>{h}</th>" for h in ["i", "type", *map(column_html, table_headings(robot))])
    body = "".join(
        f"<tr><td>{joint.index}</td><td>{html.escape(joint.type.value)}</td>"
        + "".join(f"<td>{inline_math(sp.Tuple(*cell) if isinstance(cell, tuple) else cell)}</td>" for cell in cells)
        + "</tr>"
        for joint, cells in zip(robot.joints, table_cells(robot), strict=True))
    return f'<table class="dh"><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>\n'


@dataclass(frozen=True)
class Agreement:
    """The Jacobian by every method in ``frame``, compared with differentiation: ``verdicts[method]``."""

    frame: Frame
    verdicts: dict[str, str]  # "identical", "equal after simplification" or "different"

    @property
    def agree(self) -> bool:
        """Whether every method gave the same matrix."""
        return all(verdict != "different" for verdict in self.verdicts.values())


def method_agreement(robot: Robot, frame: Frame, point: object) -> Agreement:
    """Derive the Jacobian in ``frame`` by all four methods and compare each with differentiation, exactly."""
    chain = chain_of(robot)
    methods: Sequence[Method] = METHODS  # type: ignore[assignment]
    results = {method: jacobian(chain, frame=frame, point=point, method=method) for method in methods}  # type: ignore[arg-type]
    reference = results["differentiation"]
    verdicts: dict[str, str] = {}
    for method, J in results.items():
        if reference == J:
            verdicts[method] = "identical"
        elif (J - reference).applyfunc(lambda e: sp.simplify(sp.expand_trig(e))).is_zero_matrix:
            verdicts[method] = "equal after simplification"
        else:
            verdicts[method] = "different"
    return Agreement(frame, verdicts)

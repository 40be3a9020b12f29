r"""MathML Core in textbook shorthand, for the browser report: :math:`s_1`, :math:`c_{23}`, matrices in parentheses.

SymPy's presentation printer is the base; this subclass abbreviates sines and cosines of joint-angle sums exactly
as the LaTeX printer does (:mod:`symjac.printing.shorthand`), orders products the textbook way, prints matrices as
an ``mtable`` between stretchy ``(`` ``)`` operators, ``atan2`` by its name, and the invisible times as a numeric
character reference. Anything that would still come out as the deprecated ``mfenced`` (not part of MathML Core,
which Chromium renders natively) is rewritten to an ``mrow`` with explicit fences by :func:`core_elements`.
"""

from __future__ import annotations

import re
from typing import Any
from xml.dom.minidom import Element, Text

import sympy as sp
from sympy.printing.mathml import MathMLPresentationPrinter
from sympy.printing.precedence import PRECEDENCE

from symjac.printing.shorthand import GREEK, readable_float, shorthand_indices, textbook_factors

__all__ = ["TextbookMathMLPrinter", "core_elements", "math_element", "mathml_node"]

_INVISIBLE_TIMES = "\u2062"
_DOTTED = re.compile(r"^(.+?)(ddot|dot)(\d*)$")  # rates and accelerations: thetadot1, thetaddot1, ddot3 (d3's rate)
_DOTS = {"dot": "\u02d9", "ddot": "\u00a8"}


class TextbookMathMLPrinter(MathMLPresentationPrinter):
    """Presentation MathML with :math:`s_{ij}, c_{ij}` shorthand and parenthesised ``mtable`` matrices."""

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"mat_delim": "(", **(settings or {})})

    def mathml_tag(self, e: Any) -> str:
        """The operator text of ``e``: the invisible times as a character, not a named entity."""
        tag = super().mathml_tag(e)
        return _INVISIBLE_TIMES if tag == "&InvisibleTimes;" else tag

    def _element(self, tag: str, text: str | None = None) -> Element:
        element = self.dom.createElement(tag)
        if text is not None:
            element.appendChild(self.dom.createTextNode(text))
        return element

    def _shorthand(self, letter: str, expr: sp.Function) -> Element | None:
        indices = shorthand_indices(expr.args[0])
        argument = expr.args[0]
        if indices is None:
            if not (isinstance(argument, sp.Symbol) and argument.name in GREEK):
                return None
            return self._script(letter, self._print(argument))
        return self._script(letter, self._element("mn", indices))

    def _script(self, letter: str, subscript: Element) -> Element:
        node = self._element("msub")
        node.appendChild(self._element("mi", letter))
        node.appendChild(subscript)
        return node

    def _print_Symbol(self, sym: sp.Symbol, style: str = "plain") -> Element:
        """A rate or acceleration (``thetadot1``, ``thetaddot1``) as its coordinate with dots over it, as in LaTeX."""
        match = _DOTTED.match(sym.name)
        if match is None:
            return super()._print_Symbol(sym, style)  # type: ignore[no-any-return]
        prefix, dots, digits = match.groups()
        over = self._element("mover")
        over.setAttribute("accent", "true")
        over.appendChild(super()._print_Symbol(sp.Symbol(prefix), style))
        over.appendChild(self._element("mo", _DOTS[dots]))
        if not digits:
            return over
        node = self._element("msub")
        node.appendChild(over)
        node.appendChild(self._element("mn", digits))
        return node

    def _print_sin(self, expr: sp.Function) -> Element:
        return self._shorthand("s", expr) or self._print_Function(expr)

    def _print_cos(self, expr: sp.Function) -> Element:
        return self._shorthand("c", expr) or self._print_Function(expr)

    def _print_Float(self, expr: sp.Float) -> Element:
        return super()._print_Float(readable_float(expr))

    def _print_Pi(self, expr: sp.Expr) -> Element:
        return self._element("mi", "\u03c0")

    def _print_atan2(self, expr: sp.Function) -> Element:
        row = self._element("mrow")
        row.appendChild(self._element("mi", "atan2"))
        row.appendChild(self._paren_comma_separated(*expr.args))
        return row

    def _print_Mul(self, expr: sp.Mul) -> Element:
        ordered = textbook_factors(expr)
        if ordered is None:
            return super()._print_Mul(expr)
        coefficient, factors = ordered
        row = self._element("mrow")
        if coefficient < 0:
            row.appendChild(self._element("mo", "-"))
        parts = [self._print(abs(coefficient))] if abs(coefficient) != 1 else []
        for factor in factors:
            if factor.is_Add:
                fenced = self._element("mrow")
                fenced.appendChild(self._element("mo", "("))
                fenced.appendChild(self._print(factor))
                fenced.appendChild(self._element("mo", ")"))
                parts.append(fenced)
            else:
                parts.append(self.parenthesize(factor, PRECEDENCE["Mul"]))
        for number, part in enumerate(parts):
            if number:
                row.appendChild(self._element("mo", _INVISIBLE_TIMES))
            row.appendChild(part)
        return row


def core_elements(node: Element) -> Element:
    """Rewrite every ``mfenced`` below ``node`` (deprecated, not MathML Core) as ``mrow`` with ``mo`` fences.

    Hyphens printed as operators become minus signs on the way.
    """
    for child in list(node.childNodes):
        if isinstance(child, Element):
            core_elements(child)
    text = node.firstChild
    if node.tagName in ("mo", "mn") and isinstance(text, Text) and text.data.startswith("-"):
        text.data = "\u2212" + text.data[1:]  # the minus sign, not the hyphen
    document, parent = node.ownerDocument, node.parentNode
    if node.tagName != "mfenced" or document is None or parent is None:
        return node

    def fence(symbol: str) -> Element:
        element = document.createElement("mo")
        element.appendChild(document.createTextNode(symbol))
        return element

    row = document.createElement("mrow")
    separators = (node.getAttribute("separators") or ",").replace(" ", "") or ","
    row.appendChild(fence(node.getAttribute("open") or "("))
    for number, child in enumerate([child for child in node.childNodes if isinstance(child, Element)]):
        if number:
            row.appendChild(fence(separators[min(number - 1, len(separators) - 1)]))
        row.appendChild(child)
    row.appendChild(fence(node.getAttribute("close") or ")"))
    parent.replaceChild(row, node)
    return row


def mathml_node(expr: Any, printer: TextbookMathMLPrinter | None = None) -> Element:
    """The MathML Core element tree of ``expr`` (inside a wrapper ``mrow``, so fences can be rewritten)."""
    printer = printer or TextbookMathMLPrinter()
    wrapper = printer.dom.createElement("mrow")
    wrapper.appendChild(printer._print(expr))
    return core_elements(wrapper)


def math_element(content: Element | str, display: bool = False) -> str:
    r"""A complete ``<math>`` element around ``content`` (a node or its markup), ASCII with character references.

    Examples
    --------
    >>> t2, t3 = sp.symbols("theta2 theta3", real=True)
    >>> math_element(mathml_node(sp.cos(t2 + t3)))
    '<math><mrow><msub><mi>c</mi><mn>23</mn></msub></mrow></math>'
    """
    markup = content if isinstance(content, str) else content.toxml()
    markup = markup.encode("ascii", "xmlcharrefreplace").decode()
    return f'<math display="block">{markup}</math>' if display else f"<math>{markup}</math>"

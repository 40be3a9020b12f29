"""Unicode pretty printing in textbook shorthand (``s₁``, ``c₂₃``), the plain-text twin of :mod:`.latex`."""

from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.printing.pretty.pretty import PrettyPrinter
from sympy.printing.pretty.stringpict import prettyForm, stringPict

from symjac.printing.shorthand import SUBSCRIPTS, file_decimal, readable_float, shorthand_indices, textbook_factors

__all__ = ["TextbookPrettyPrinter", "pretty", "pretty_side_by_side"]


class TextbookPrettyPrinter(PrettyPrinter):
    """Unicode pretty printing with ``s₁, c₂₃`` shorthand."""

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"use_unicode": True, "wrap_line": False, **(settings or {})})

    def _shorthand(self, letter: str, expr: sp.Function) -> prettyForm | None:
        indices = shorthand_indices(expr.args[0])
        if indices is None:
            return None
        return prettyForm(letter + indices.translate(SUBSCRIPTS))

    def _print_sin(self, expr: sp.Function) -> prettyForm:
        return self._shorthand("s", expr) or self._print_Function(expr)

    def _print_cos(self, expr: sp.Function) -> prettyForm:
        return self._shorthand("c", expr) or self._print_Function(expr)

    def _print_Rational(self, expr: sp.Rational) -> prettyForm:
        decimal = file_decimal(expr)
        return prettyForm(decimal) if decimal is not None else super()._print_Rational(expr)

    def _print_Float(self, number: sp.Float) -> prettyForm:
        return super()._print_Float(readable_float(number))

    def _print_Mul(self, product: sp.Mul) -> prettyForm:
        coefficient, rest = product.as_coeff_Mul()
        decimal = file_decimal(abs(coefficient))
        if decimal is not None:  # 0.089159⋅s₁, as the robot file wrote it
            body = self._print(rest)
            form = prettyForm.__mul__(prettyForm(decimal), prettyForm(*body.parens()) if rest.is_Add else body)
            return prettyForm(*form.left("-")) if coefficient < 0 else form
        ordered = textbook_factors(product)
        if ordered is None:
            return super()._print_Mul(product)
        coefficient, factors = ordered
        forms = [self._print(f) for f in factors]
        if coefficient != 1:
            forms.insert(0, self._print(sp.Integer(coefficient)))  # prettyForm.__mul__ turns -1 into a sign
        return prettyForm.__mul__(*forms)


def pretty(expr: Any, **settings: Any) -> str:
    """Unicode pretty print of an expression or matrix in textbook shorthand (``c₁₂``)."""
    return TextbookPrettyPrinter(settings).doprint(expr)


def pretty_side_by_side(*exprs: Any) -> str:
    r"""Several expressions or matrices printed next to each other (a product such as :math:`E(x)\,J_0`)."""
    printer = TextbookPrettyPrinter()
    forms = [printer._print(expr) for expr in exprs]
    joined = forms[0]
    for form in forms[1:]:
        joined = prettyForm(*stringPict.next(joined, " ", form))
    return "\n".join(line.rstrip() for line in str(joined.render(wrap_line=False)).split("\n"))

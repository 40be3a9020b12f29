"""Unicode pretty printing in textbook shorthand (``s₁``, ``c₂₃``), the plain-text twin of :mod:`.latex`."""

from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.printing.precedence import PRECEDENCE
from sympy.printing.pretty.pretty import PrettyPrinter
from sympy.printing.pretty.pretty_symbology import pretty_symbol
from sympy.printing.pretty.stringpict import prettyForm, stringPict
from sympy.printing.str import StrPrinter

from symjac.printing.shorthand import (
    GREEK,
    SUBSCRIPTS,
    file_decimal,
    readable_float,
    shorthand_indices,
    textbook_factors,
    textbook_form,
)

__all__ = ["TextbookPrettyPrinter", "one_line", "pretty", "pretty_side_by_side"]


class TextbookPrettyPrinter(PrettyPrinter):
    """Unicode pretty printing with ``s₁, c₂₃, c₂₋₄`` shorthand (of :func:`.textbook_form`, as the LaTeX printer)."""

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"use_unicode": True, "wrap_line": False, **(settings or {})})
        self._forms: dict[sp.Basic, sp.Basic] = {}

    def doprint(self, expr: Any) -> str:
        """The text of ``expr`` in :func:`.textbook_form`."""
        return str(super().doprint(textbook_form(expr, self._forms)))

    def textbook(self, expr: Any) -> prettyForm:
        """The form of ``expr`` in :func:`.textbook_form` (to place beside others)."""
        return self._print(textbook_form(expr, self._forms))

    def _shorthand(self, letter: str, expr: sp.Function) -> prettyForm | None:
        indices = shorthand_indices(expr.args[0])
        if indices is None:
            argument = expr.args[0]
            if not (isinstance(argument, sp.Symbol) and argument.name in GREEK):
                return None
            return prettyForm(f"{letter}_{pretty_symbol(argument.name)}")  # s_β, as LaTeX's s_{\beta}
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
        if ordered is None and isinstance(coefficient, sp.Rational) and not coefficient.is_Integer \
                and textbook_factors(product * coefficient.q) is not None:  # c₂⋅(c₃ - 1) over 2
            numerator = self._print((-product if coefficient < 0 else product) * coefficient.q)
            form = prettyForm.__truediv__(numerator, self._print(sp.Integer(coefficient.q)))
            return prettyForm(*form.left("-"), binding=prettyForm.NEG) if coefficient < 0 else form
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
    forms = [printer.textbook(expr) for expr in exprs]
    joined = forms[0]
    for form in forms[1:]:
        joined = prettyForm(*stringPict.next(joined, " ", form))
    return "\n".join(line.rstrip() for line in str(joined.render(wrap_line=False)).split("\n"))


_SUPERSCRIPTS = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")
_RELATIONS = {">=": "≥", "<=": "≤", "!=": "≠", "==": "="}


class _OneLinePrinter(StrPrinter):
    """Mathematics on one line of Unicode: ``a₂ + √(a₃² + d₄²) ≥ a₁``, ``-√2/2``, never Python's ``**`` or ``*``."""

    def doprint(self, expr: Any) -> str:
        return str(super().doprint(textbook_form(expr)))

    def _print_Symbol(self, expr: sp.Symbol) -> str:
        return pretty(expr)

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        if expr.exp == sp.S.Half:
            base = self._print(expr.base)
            return "√" + (base if expr.base.is_Atom else f"({base})")
        if expr.exp.is_Integer and 2 <= expr.exp <= 9:
            return self.parenthesize(expr.base, PRECEDENCE["Pow"]) + str(expr.exp).translate(_SUPERSCRIPTS)
        return str(super()._print_Pow(expr, rational))

    def _print_Mul(self, expr: sp.Mul) -> str:
        text = str(super()._print_Mul(expr))
        return text.replace("**", "\0").replace("*", "⋅").replace("\0", "**")

    def _print_Relational(self, expr: sp.core.relational.Relational) -> str:
        return f"{self._print(expr.lhs)} {_RELATIONS.get(expr.rel_op, expr.rel_op)} {self._print(expr.rhs)}"

    def _print_Float(self, expr: sp.Float) -> str:
        return str(super()._print_Float(readable_float(expr)))

    def _print_Pi(self, expr: sp.Expr) -> str:
        return "π"

    def _print_sin(self, expr: sp.Function) -> str:
        argument = expr.args[0]
        greek = isinstance(argument, sp.Symbol) and argument.name in GREEK
        return pretty(expr) if greek or shorthand_indices(argument) is not None else str(self._print_Function(expr))

    _print_cos = _print_sin


def one_line(expr: Any) -> str:
    """``expr`` as mathematics on one line of Unicode (for sentences), where :func:`pretty` would stack it.

    Examples
    --------
    >>> a1, a2, a3, d4 = sp.symbols("a1 a2 a3 d4", positive=True)
    >>> one_line(sp.Ge(a2 + sp.sqrt(a3**2 + d4**2), a1, evaluate=False))
    'a₂ + √(a₃² + d₄²) ≥ a₁'
    >>> one_line(-sp.sqrt(2) / 2), one_line(-sp.pi / 2)
    ('-√2/2', '-π/2')
    """
    return str(_OneLinePrinter().doprint(sp.sympify(expr)))


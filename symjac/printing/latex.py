r"""LaTeX in textbook shorthand: :math:`s_1 = \sin\theta_1`, :math:`c_{23} = \cos(\theta_2 + \theta_3)`.

The shorthand lives only in the printers (a subclass of SymPy's LaTeX printer here, :mod:`.pretty` for Unicode):
the math keeps ordinary ``sin``/``cos`` of joint variables.
"""

from __future__ import annotations

from typing import Any

import sympy as sp
from sympy.printing.latex import LatexPrinter

from symjac.printing.shorthand import GREEK, file_decimal, shorthand_indices, textbook_factors

__all__ = ["DIGITS", "TextbookLatexPrinter", "escape_text", "latex", "rounded"]

DIGITS = 4
"""Significant digits of the numbers in ``--numeric`` results unless ``--digits`` says otherwise."""

_TEXT_ESCAPES = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "_": r"\_", "#": r"\#", "%": r"\%", "&": r"\&",
                 "$": r"\$", "^": r"\^{}", "~": r"\~{}", "<": r"\textless{}", ">": r"\textgreater{}"}


class _DecimalLatexPrinter(LatexPrinter):
    """SymPy's LaTeX with numbers from files as the decimals they were written as (:func:`.file_decimal`).

    Each distinct subexpression is printed once per printer: the entries of a Jacobian share most of their terms
    (a 7-joint chain with generic twists has about 100,000 nodes in its Jacobian but 5,500 distinct ones), and
    SymPy orders the terms of every sum again each time it meets it.
    """

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__(settings)
        self._memo: dict[sp.Basic, str] = {}

    def _print(self, expr: Any, **kwargs: Any) -> str:
        # Only whole expressions printed without options are remembered: ``exp=`` (a power of a function) and the
        # like change the text. Equal SymPy objects print alike (Floats of different precision are not equal).
        if kwargs or not isinstance(expr, sp.Basic):
            return super()._print(expr, **kwargs)
        text = self._memo.get(expr)
        if text is None:
            text = self._memo[expr] = super()._print(expr)
        return text

    def _print_Rational(self, expr: sp.Rational) -> str:
        return file_decimal(expr) or super()._print_Rational(expr)

    def _print_Mul(self, expr: sp.Mul) -> str:
        coefficient, rest = expr.as_coeff_Mul()
        decimal = file_decimal(abs(coefficient))
        if decimal is None:
            return super()._print_Mul(expr)
        body = self._print(rest)  # 0.089159 s_{1}, as the robot file wrote it
        body = rf"\left({body}\right)" if rest.is_Add else body
        return ("- " if coefficient < 0 else "") + f"{decimal} {body}"


class TextbookLatexPrinter(_DecimalLatexPrinter):
    """LaTeX with :math:`s_{ij}, c_{ij}` shorthand and ``bmatrix`` matrices."""

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"mat_str": "bmatrix", "mat_delim": "", **(settings or {})})
        self._plain: _DecimalLatexPrinter | None = None

    def _shorthand(self, letter: str, expr: sp.Function, exp: str | None) -> str | None:
        indices = shorthand_indices(expr.args[0])
        if indices is None:
            argument = expr.args[0]
            if not (isinstance(argument, sp.Symbol) and argument.name in GREEK):
                return None
            indices = "\\" + argument.name  # s_{\beta}: representation angles get the shorthand too
        text = f"{letter}_{{{indices}}}"
        return f"{text}^{{{exp}}}" if exp else text

    def _print_sin(self, expr: sp.Function, exp: str | None = None) -> str:
        return self._shorthand("s", expr, exp) or self._plain_function(expr, exp)

    def _print_cos(self, expr: sp.Function, exp: str | None = None) -> str:
        return self._shorthand("c", expr, exp) or self._plain_function(expr, exp)

    def _plain_function(self, expr: sp.Function, exp: str | None) -> str:
        r"""``\cos^{2}{\left(\beta \right)}`` as SymPy prints it (its own dispatch would come back here)."""
        if self._plain is None:
            self._plain = _DecimalLatexPrinter({"mat_str": "bmatrix", "mat_delim": ""})
        return LatexPrinter._print_Function(self._plain, expr, exp)

    def _print_atan2(self, expr: sp.Function, exp: str | None = None) -> str:
        text = r"\operatorname{atan2}\left(" + ", ".join(self._print(a) for a in expr.args) + r"\right)"
        return f"{text}^{{{exp}}}" if exp else text

    def _print_Mul(self, expr: sp.Mul) -> str:
        if file_decimal(abs(expr.as_coeff_Mul()[0])) is not None:
            return super()._print_Mul(expr)
        ordered = textbook_factors(expr)
        if ordered is None:
            return super()._print_Mul(expr)
        coefficient, factors = ordered
        parts = [r"\left(" + self._print(f) + r"\right)" if f.is_Add else self._print(f) for f in factors]
        if abs(coefficient) != 1:
            parts.insert(0, str(abs(coefficient)))
        return ("- " if coefficient < 0 else "") + " ".join(parts)


def latex(expr: Any, **settings: Any) -> str:
    r"""LaTeX of an expression or matrix in textbook shorthand.

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> latex(sp.Matrix([[sp.cos(t1) * sp.sin(t1 + t2)]]))
    '\\begin{bmatrix}c_{1} s_{12}\\end{bmatrix}'
    """
    return TextbookLatexPrinter(settings).doprint(expr)


def escape_text(text: str) -> str:
    r"""Words for LaTeX text mode: ``_ # % & $ { } ^ ~ \ < >`` made printable.

    Examples
    --------
    >>> escape_text("my_arm: 50% of {3}")
    'my\\_arm: 50\\% of \\{3\\}'
    """
    return "".join(_TEXT_ESCAPES.get(character, character) for character in text)


def rounded(expr: Any, digits: int = DIGITS) -> Any:
    """``expr`` (or a matrix) with every number a decimal of ``digits`` significant digits; integers stay integers.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> rounded(sp.Rational(2159, 5000) * x + sp.Rational(1, 3) + 2 * sp.sin(x), 3)
    0.432*x + 2*sin(x) + 0.333
    """
    value = sp.sympify(expr).evalf(digits)
    return value.xreplace({f: sp.Integer(int(f)) for f in value.atoms(sp.Float) if float(f).is_integer()})

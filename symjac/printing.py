r"""Printing in textbook shorthand: :math:`s_1 = \sin\theta_1`, :math:`c_{23} = \cos(\theta_2 + \theta_3)`.

The shorthand lives only here, in subclasses of SymPy's LaTeX and pretty printers: the math keeps ordinary
``sin``/``cos`` of joint variables. A sine or cosine is abbreviated when its argument is a sum of revolute joint
variables ``theta{i}`` (all with coefficient +1); anything else prints in full.
"""

from __future__ import annotations

import re
from typing import Any

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.pretty.pretty import PrettyPrinter
from sympy.printing.pretty.stringpict import prettyForm

__all__ = ["latex", "pretty", "shorthand_indices"]

_JOINT_ANGLE = re.compile(r"theta(\d+)\Z")
_SUBSCRIPTS = str.maketrans("0123456789,", "₀₁₂₃₄₅₆₇₈₉‚")


def shorthand_indices(argument: sp.Expr) -> str | None:
    """The subscript of a trig shorthand: ``theta1 + theta2 -> "12"`` (``"8,9,10"`` past 9); ``None`` if none.

    Examples
    --------
    >>> t2, t3 = sp.symbols("theta2 theta3", real=True)
    >>> shorthand_indices(t2 + t3)
    '23'
    >>> shorthand_indices(t2 - t3) is None
    True
    """
    terms = sp.Add.make_args(argument)
    indices = []
    for term in terms:
        match = _JOINT_ANGLE.match(term.name) if isinstance(term, sp.Symbol) else None
        if match is None:
            return None
        indices.append(int(match.group(1)))
    indices.sort()
    separator = "," if any(i > 9 for i in indices) else ""
    return separator.join(str(i) for i in indices)


class TextbookLatexPrinter(LatexPrinter):
    """LaTeX with :math:`s_{ij}, c_{ij}` shorthand and ``bmatrix`` matrices."""

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"mat_str": "bmatrix", "mat_delim": "", **(settings or {})})

    def _shorthand(self, letter: str, expr: sp.Function, exp: str | None) -> str | None:
        indices = shorthand_indices(expr.args[0])
        if indices is None:
            return None
        text = f"{letter}_{{{indices}}}"
        return f"{text}^{{{exp}}}" if exp else text

    def _print_sin(self, expr: sp.Function, exp: str | None = None) -> str:
        return self._shorthand("s", expr, exp) or self._print_Function(expr, exp)

    def _print_cos(self, expr: sp.Function, exp: str | None = None) -> str:
        return self._shorthand("c", expr, exp) or self._print_Function(expr, exp)


class TextbookPrettyPrinter(PrettyPrinter):
    """Unicode pretty printing with ``s₁, c₂₃`` shorthand."""

    def __init__(self, settings: dict[str, Any] | None = None):
        super().__init__({"use_unicode": True, "wrap_line": False, **(settings or {})})

    def _shorthand(self, letter: str, expr: sp.Function) -> prettyForm | None:
        indices = shorthand_indices(expr.args[0])
        if indices is None:
            return None
        return prettyForm(letter + indices.translate(_SUBSCRIPTS))

    def _print_sin(self, expr: sp.Function) -> prettyForm:
        return self._shorthand("s", expr) or self._print_Function(expr)

    def _print_cos(self, expr: sp.Function) -> prettyForm:
        return self._shorthand("c", expr) or self._print_Function(expr)


def latex(expr: Any, **settings: Any) -> str:
    r"""LaTeX of an expression or matrix in textbook shorthand.

    Examples
    --------
    >>> t1, t2 = sp.symbols("theta1 theta2", real=True)
    >>> latex(sp.Matrix([[sp.cos(t1) * sp.sin(t1 + t2)]]))
    '\\begin{bmatrix}c_{1} s_{12}\\end{bmatrix}'
    """
    return TextbookLatexPrinter(settings).doprint(expr)


def pretty(expr: Any, **settings: Any) -> str:
    """Unicode pretty print of an expression or matrix in textbook shorthand (``c₁₂``)."""
    return TextbookPrettyPrinter(settings).doprint(expr)

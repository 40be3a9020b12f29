"""The lambdify target's printer: Python source that rebuilds the SymPy expressions."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp
from sympy.printing.str import StrPrinter

from symjac.codegen.printers import ALLOWED_FUNCTIONS, SymbolPrinting, float_literal
from symjac.errors import CodegenError

__all__ = ["SymPyPrinter"]


class SymPyPrinter(StrPrinter):
    """Python source that *rebuilds* the SymPy expression (``sympy.sin(theta1)``), exact numbers kept exact.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> SymPyPrinter({x: "theta1"}).doprint(sp.Rational(1, 3) * sp.sin(x) + sp.sqrt(x) + sp.pi)
    'sympy.sqrt(theta1) + sympy.Rational(1, 3)*sympy.sin(theta1) + sympy.pi'
    """

    def __init__(self, names: Mapping[sp.Symbol, str]):
        super().__init__()
        self.names = names

    def _print_Symbol(self, expr: sp.Symbol) -> str:
        return SymbolPrinting._print_Symbol(self, expr)  # type: ignore[arg-type]

    def _print_Integer(self, expr: sp.Integer) -> str:
        return str(int(expr))

    def _print_Rational(self, expr: sp.Rational) -> str:
        return f"sympy.Rational({int(expr.p)}, {int(expr.q)})"

    def _print_Float(self, expr: sp.Float) -> str:
        return f"sympy.Float({float_literal(expr)!r})"

    def _print_Pi(self, expr: sp.Expr) -> str:
        return "sympy.pi"

    def _print_NumberSymbol(self, expr: sp.NumberSymbol) -> str:
        raise CodegenError(f"constant {expr} is not supported in generated code")

    def _print_Function(self, expr: sp.Function) -> str:
        constant = isinstance(expr, sp.atan | sp.atan2) and expr.is_number  # a robot file's offset: atan(16/3)
        if not (isinstance(expr, (*ALLOWED_FUNCTIONS, sp.sign)) or constant):
            raise CodegenError(f"function {type(expr).__name__} is not supported in generated code")
        return f"sympy.{type(expr).__name__}({', '.join(self._print(argument) for argument in expr.args)})"

    _print_sin = _print_Function
    _print_cos = _print_Function
    _print_sign = _print_Function  # Coulomb friction
    _print_atan = _print_Function
    _print_atan2 = _print_Function

    def _print_Mul(self, expr: sp.Mul) -> str:
        coefficient, rest = expr.as_coeff_Mul()
        if coefficient.is_Rational and not coefficient.is_Integer:  # keep 1/3 exact: never "x/3" on an int
            sign = "-" if coefficient < 0 else ""
            return f"{sign}{self._print_Rational(abs(coefficient))}*{self.parenthesize(rest, 50)}"
        return super()._print_Mul(expr)

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exponent = expr.args
        if exponent == sp.Rational(1, 2):
            return f"sympy.sqrt({self._print(base)})"
        if exponent.is_Integer:
            return f"{self.parenthesize(base, 60)}**{int(exponent)}"
        if exponent.is_Rational:
            return f"{self.parenthesize(base, 60)}**{self._print_Rational(exponent)}"
        raise CodegenError(f"power {expr} with a non-numeric exponent is not supported in generated code")

    def emptyPrinter(self, expr: Any) -> str:
        """Refuse whatever has no printing method of its own."""
        raise CodegenError(f"{type(expr).__name__} ({expr}) is not supported in generated code")

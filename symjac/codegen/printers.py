r"""What the code printers of every target share; each target's own printer is ``backends/<target>/printer.py``.

Each printer is a subclass of a SymPy code printer that maps every symbol to a *validated* name through
``_print_Symbol`` (never a regex over printed text), prints every number as a finite float literal (or an exact
SymPy constructor), writes small integer powers as products (``x*x`` is faster than ``x**2`` in every target) and
refuses anything it does not know (an unknown function, a symbol without a name, an infinite number) with a
:class:`~symjac.errors.SymjacError` before any text is produced. :func:`symjac.codegen.source_layout.wrap_statement`
then breaks long statements at operator spaces so that generated files stay within the line length ruff checks.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import sympy as sp
from sympy.printing.precedence import PRECEDENCE

from symjac.codegen.names import PYTHON_IDENTIFIERS
from symjac.errors import CodegenError
from symjac.symbolic.dag import distinct_nodes

__all__ = [
    "ALLOWED_FUNCTIONS",
    "SymbolPrinting",
    "check_expression",
    "check_identifier",
    "float_literal",
]

ALLOWED_FUNCTIONS = (sp.sin, sp.cos)


def check_identifier(name: Any, what: str, reserved: Mapping[str, str] | None = None) -> str:
    """Return ``name`` if it may be an identifier of a generated Python module, else raise :class:`CodegenError`.

    It must be an ASCII identifier, not a Python keyword or soft keyword, not a builtin (a parameter called ``len``
    or ``min`` would shadow it) and not in ``reserved`` (names the generated module uses itself, with the reason).
    Each target checks with its own rule (:attr:`Backend.identifiers <symjac.codegen.description.Backend>`).

    Examples
    --------
    >>> check_identifier("a2", "parameter name")
    'a2'
    >>> check_identifier("lambda", "parameter name")
    Traceback (most recent call last):
    ...
    symjac.errors.CodegenError: parameter name 'lambda' is a Python keyword
    """
    return PYTHON_IDENTIFIERS.check(name, what, reserved)


def float_literal(value: Any) -> str:
    """The shortest round-tripping literal of a finite real number (``repr`` of the float).

    Examples
    --------
    >>> float_literal(sp.Rational(2159, 5000)), float_literal(sp.pi), float_literal(2)
    ('0.4318', '3.141592653589793', '2.0')
    """
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise CodegenError(f"{value!r} is not a real number") from None
    if not math.isfinite(number):
        raise CodegenError(f"{value!r} is not a finite number")
    return repr(number)


class SymbolPrinting:
    """What every numeric printer shares: names from a mapping, float literals, powers as products, a whitelist.

    A target's printer (``backends/<target>/printer.py``) mixes it into a SymPy printer.
    """

    names: Mapping[sp.Symbol, str]
    used: set[str]  # functions the printed code calls (the module imports exactly these)
    _function_prefix = ""

    def _print_Symbol(self, expr: sp.Symbol) -> str:
        try:
            return self.names[expr]
        except KeyError:
            raise CodegenError(f"symbol {expr} has no name in the generated code") from None

    def _print_Dummy(self, expr: sp.Dummy) -> str:
        return self._print_Symbol(expr)

    def _number(self, value: Any) -> str:
        """A number as this target writes it (a float literal; the c99 target casts it to its real type)."""
        return float_literal(value)

    def _print_Integer(self, expr: sp.Integer) -> str:
        return self._number(expr)

    def _print_Rational(self, expr: sp.Rational) -> str:
        return self._number(expr)

    def _print_Float(self, expr: sp.Float) -> str:
        return self._number(expr)

    def _print_NumberSymbol(self, expr: sp.NumberSymbol) -> str:
        return self._number(expr)

    _print_Pi = _print_NumberSymbol
    _print_Exp1 = _print_NumberSymbol

    def _print_Infinity(self, expr: sp.Expr) -> str:
        raise CodegenError(f"{expr} is not a finite number")

    _print_NegativeInfinity = _print_Infinity
    _print_ComplexInfinity = _print_Infinity
    _print_NaN = _print_Infinity

    def _print_Function(self, expr: sp.Function) -> str:
        if not isinstance(expr, ALLOWED_FUNCTIONS):
            if expr.is_number:  # a constant such as a robot file's offset atan(16/3): its value, computed once here
                return self._number(expr)
            raise CodegenError(f"function {type(expr).__name__} is not supported in generated code")
        argument = self._print(expr.args[0])  # type: ignore[attr-defined]
        self.used.add(type(expr).__name__)
        return f"{self._function_prefix}{type(expr).__name__}({argument})"

    def _print_sign(self, expr: sp.sign) -> str:
        """``(1.0*(x > 0.0) - 1.0*(x < 0.0))``: comparisons every target has (0 at 0, as Coulomb friction at rest)."""
        argument = self._print(expr.args[0])  # type: ignore[attr-defined]
        one, zero = self._number(1), self._number(0)
        return f"({one}*({argument} > {zero}) - {one}*({argument} < {zero}))"

    _print_sin = _print_Function
    _print_cos = _print_Function
    _print_atan = _print_Function  # SymPy's code printers would write atan(...) without importing it
    _print_atan2 = _print_Function

    def _print_Mul(self, expr: sp.Mul) -> str:
        """``-0.5*x*y/(z*z)``: float coefficient first, then factors, then one parenthesised denominator."""
        coefficient, rest = expr.as_coeff_Mul()
        sign = "-" if coefficient.is_negative else ""
        coefficient = abs(coefficient)
        numerator: list[sp.Expr] = []
        denominator: list[sp.Expr] = []
        for factor in rest.as_ordered_factors() if rest.is_Mul else [rest]:
            if factor.is_Pow and factor.exp.is_Rational and factor.exp.is_negative:
                denominator.append(sp.Pow(factor.base, -factor.exp))
            elif factor != 1:
                numerator.append(factor)
        level = PRECEDENCE["Mul"]
        parts = [] if coefficient == 1 else [self._number(coefficient)]
        parts += [self.parenthesize(factor, level, strict=True) for factor in numerator]  # type: ignore[attr-defined]
        text = "*".join(parts) or self._number(1)
        if denominator:
            below = "*".join(self.parenthesize(f, level, strict=True) for f in denominator)  # type: ignore[attr-defined]
            single = denominator[0]
            if len(denominator) > 1 or (single.is_Pow and single.exp.is_Integer and single.exp > 1):
                below = f"({below})"
            text = f"{text}/{below}"
        return sign + text

    def _sqrt(self, text: str) -> str:
        self.used.add("sqrt")
        return f"{self._function_prefix}sqrt({text})"

    def _power(self, base: str, exponent: str) -> str:
        return f"{base}**{exponent}"

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exponent = expr.args
        if not exponent.is_Rational:
            raise CodegenError(f"power {expr} with a non-numeric exponent is not supported in generated code")
        tight = self.parenthesize(base, PRECEDENCE["Mul"] + 1)  # type: ignore[attr-defined]
        whole = self._print(base)  # type: ignore[attr-defined]
        if exponent.is_Integer:
            k = int(exponent)
            if 1 <= abs(k) <= 3:
                product = "*".join([tight] * abs(k))
                if k > 0:
                    return product
                return f"{self._number(1)}/{product}" if abs(k) == 1 else f"{self._number(1)}/({product})"
            if k > 0:
                return self._power(tight, str(k))
            return f"{self._number(1)}/{self._power(tight, str(-k))}"
        if exponent == sp.Rational(1, 2):
            return self._sqrt(whole)
        if exponent == sp.Rational(-1, 2):
            return f"{self._number(1)}/{self._sqrt(whole)}"
        return self._power(tight, f"({self._number(exponent)})")


def check_expression(*exprs: sp.Basic) -> None:
    """Refuse, before anything is printed, every node of ``exprs`` a generated module cannot evaluate.

    Allowed: symbols, finite numbers, ``pi``, ``+``, ``*``, powers with rational exponents, ``sin`` and ``cos``, and
    ``sign`` (Coulomb friction).

    Examples
    --------
    >>> check_expression(sp.sin(sp.Symbol("x")) ** 2 + sp.pi)
    >>> check_expression(sp.exp(sp.Symbol("x")))
    Traceback (most recent call last):
    ...
    symjac.errors.CodegenError: exp(x) is not supported in generated code (allowed: + * ** sin cos)
    """
    for node in distinct_nodes(exprs):  # each shared subexpression once
        if isinstance(node, sp.Symbol | sp.Add | sp.Mul | sp.sin | sp.cos | sp.sign) or node is sp.pi:
            continue
        if isinstance(node, sp.Number):
            float_literal(node)  # raises for infinities and NaN
            continue
        if isinstance(node, sp.Pow) and node.exp.is_Rational:
            continue
        raise CodegenError(f"{node} is not supported in generated code (allowed: + * ** sin cos)")

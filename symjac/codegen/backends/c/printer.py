"""The C printer of every C-family target: C99 over ``<math.h>`` (c), and in a real type ``real`` (c99, cpp)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp
from sympy.printing.c import C99CodePrinter

from symjac.codegen.printers import SymbolPrinting, float_literal

__all__ = ["CPrinter", "RealPrinter"]


class CPrinter(SymbolPrinting, C99CodePrinter):
    """C99 with ``<math.h>``: double literals, integer powers as products, ``pow`` otherwise.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> CPrinter({x: "q[0]"}).doprint(x ** 2 / 3 + sp.sin(x))
    '0.3333333333333333*q[0]*q[0] + sin(q[0])'
    """

    def __init__(self, names: Mapping[sp.Symbol, str]):
        super().__init__()
        self.names = names
        self.used = set()

    def _power(self, base: str, exponent: str) -> str:
        return f"pow({base}, {exponent})"


class RealPrinter(CPrinter):
    """C99 over ``<tgmath.h>`` in a real type ``real`` (double by default, float by one switch).

    Literals are cast to ``real`` (``literal``: C's ``(real)0.5``, or C++'s ``real(0.5)``), so that a
    single-precision build computes in single precision throughout (a bare ``0.5`` is a double and would promote
    every product it enters); ``<tgmath.h>`` (C) or overloading (C++) picks ``sinf`` or ``sin`` by the type.

    Examples
    --------
    >>> import sympy as sp
    >>> x = sp.Symbol("x")
    >>> RealPrinter({x: "q[0]"}).doprint(x / 2 + sp.cos(x) ** 2)
    '(real)0.5*q[0] + cos(q[0])*cos(q[0])'
    """

    def __init__(self, names: Mapping[sp.Symbol, str], literal: str = "(real){}"):
        super().__init__(names)
        self.literal = literal

    def _number(self, value: Any) -> str:
        return self.literal.format(float_literal(value))

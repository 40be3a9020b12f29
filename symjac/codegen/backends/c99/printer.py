"""The c99 target's printer: the c target's C99 printer, with every literal cast to the generated real type."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import sympy as sp

from symjac.codegen.backends.c.printer import CPrinter
from symjac.codegen.printers import float_literal

__all__ = ["RealPrinter"]


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

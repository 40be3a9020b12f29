"""The c target's printer: C99 over ``<math.h>``."""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp
from sympy.printing.c import C99CodePrinter

from symjac.codegen.printers import SymbolPrinting

__all__ = ["CPrinter"]


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

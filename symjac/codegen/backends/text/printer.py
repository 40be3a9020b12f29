"""The text target's printer: SymPy's own string form, symbols by their generated names."""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp
from sympy.printing.str import StrPrinter

__all__ = ["TextPrinter"]


class TextPrinter(StrPrinter):
    """Plain text: ``x0 = L*c1``."""

    def __init__(self, names: Mapping[sp.Symbol, str]):
        super().__init__()
        self.names = names

    def _print_Symbol(self, expr: sp.Symbol) -> str:
        return self.names.get(expr, expr.name)

    _print_Dummy = _print_Symbol

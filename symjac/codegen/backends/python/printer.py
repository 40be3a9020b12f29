"""The python target's printer: plain Python over ``math`` (bare ``sin``, ``cos``, ``sqrt``)."""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from symjac.codegen.printers import SymbolPrinting

__all__ = ["PythonPrinter"]


class PythonPrinter(SymbolPrinting, PythonCodePrinter):
    """Plain Python with ``from math import cos, sin, sqrt``: bare function names, float literals.

    Examples
    --------
    >>> x, y = sp.symbols("x y")
    >>> PythonPrinter({x: "theta1", y: "a2"}).doprint(y * sp.cos(x) ** 2 + x / 2)
    '0.5*theta1 + a2*cos(theta1)*cos(theta1)'
    """

    def __init__(self, names: Mapping[sp.Symbol, str]):
        super().__init__({"fully_qualified_modules": False, "standard": "python3"})
        self.names = names
        self.used = set()

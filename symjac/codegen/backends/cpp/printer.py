"""The cpp target's printer: the C99 printer with C++ casts, ``real(0.5)``, for any scalar type ``real``."""

from __future__ import annotations

from collections.abc import Mapping

import sympy as sp

from symjac.codegen.backends.c.printer import RealPrinter

__all__ = ["CppPrinter"]


class CppPrinter(RealPrinter):
    """C++ expressions in a template scalar ``real`` (``double``, ``float``, ``Eigen::AutoDiffScalar``, a jet).

    Functions are called unqualified (``sin(x)``), so that argument-dependent lookup finds the scalar type's own
    overloads beside the ``using std::sin`` of each generated function.

    Examples
    --------
    >>> x = sp.Symbol("x")
    >>> CppPrinter({x: "q[0]"}).doprint(x / 2 + sp.sin(x))
    'real(0.5)*q[0] + sin(q[0])'
    """

    def __init__(self, names: Mapping[sp.Symbol, str]):
        super().__init__(names, "real({})")

"""The c99 target's printer: the c target's C printer with literals cast to the real type (one C printer)."""

from __future__ import annotations

from symjac.codegen.backends.c.printer import RealPrinter

__all__ = ["RealPrinter"]

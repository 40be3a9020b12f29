"""The casadi target's printer: CasADi's SX functions (``ca.sin``), arithmetic as in the python target."""

from __future__ import annotations

from symjac.codegen.backends.python.printer import PythonPrinter

__all__ = ["CasadiPrinter"]


class CasadiPrinter(PythonPrinter):
    """``ca.sin``, ``ca.cos``, ``ca.sqrt`` on SX symbols; one SX node per CSE temporary."""

    _function_prefix = "ca."

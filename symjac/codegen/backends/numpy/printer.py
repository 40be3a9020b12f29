"""The numpy target's printer: NumPy ufuncs on arrays, arithmetic as in the python target."""

from __future__ import annotations

from symjac.codegen.backends.python.printer import PythonPrinter

__all__ = ["NumPyPrinter"]


class NumPyPrinter(PythonPrinter):
    """NumPy ufuncs (``np.sin``, ``np.sqrt``) on arrays; arithmetic as in :class:`PythonPrinter`."""

    _function_prefix = "np."

"""Old names kept working for a while: a module's ``__getattr__`` that serves a renamed name and says what it is now.

Examples
--------
>>> import warnings
>>> from symjac.printing import tables
>>> with warnings.catch_warnings(record=True) as caught:
...     warnings.simplefilter("always")
...     old = tables.dh_table_text
>>> old is tables.parameter_table_text, caught[0].category.__name__
(True, 'DeprecationWarning')
"""

from __future__ import annotations

import sys
import warnings
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["renamed"]


def renamed(module: str, names: Mapping[str, str]) -> Callable[[str], Any]:
    """A module-level ``__getattr__`` (PEP 562) for ``module``, serving each old name of ``names`` (old: new).

    The old name gives the object of the new one and a :class:`DeprecationWarning` naming it; any other name is an
    :class:`AttributeError`.
    """

    def __getattr__(name: str) -> Any:
        if name not in names:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        warnings.warn(f"{module}.{name} is deprecated; use {names[name]}", DeprecationWarning, stacklevel=2)
        return getattr(sys.modules[module], names[name])

    return __getattr__

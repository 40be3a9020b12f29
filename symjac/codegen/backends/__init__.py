"""The registry of targets: every subpackage of this package is one target and defines one ``BACKEND``.

A folder here is a target: ``backends/<target>/__init__.py`` holds its :class:`~symjac.codegen.description.Backend`
spec, ``printer.py`` its SymPy printer, and ``templates/<target>/`` its templates (README.md: the recipe).
:data:`TARGETS`, the CLI's ``--target`` choices and the tests' parametrization all read this registry. Modules with
a leading underscore are shared helpers, not targets.
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Mapping
from types import MappingProxyType

from symjac.codegen.description import Backend
from symjac.errors import CodegenError

__all__ = ["BACKENDS", "TARGETS", "backend"]


def _discover() -> Mapping[str, Backend]:
    """Import every subpackage of this package and collect its ``BACKEND``, ordered by :attr:`Backend.order`."""
    found: list[Backend] = []
    for info in pkgutil.iter_modules(__path__):
        if not info.ispkg or info.name.startswith("_"):
            continue
        spec = getattr(importlib.import_module(f"{__name__}.{info.name}"), "BACKEND", None)
        if not isinstance(spec, Backend):
            raise CodegenError(f"internal error: {__name__}.{info.name} defines no BACKEND")
        found.append(spec)
    found.sort(key=lambda b: (b.order, b.name))
    names = [b.name for b in found]
    if len(set(names)) != len(names):
        raise CodegenError(f"internal error: two backends share a name in {names}")
    return MappingProxyType({b.name: b for b in found})


BACKENDS: Mapping[str, Backend] = _discover()
"""Each code generation target's spec, by name: one folder of :mod:`symjac.codegen.backends` each."""
TARGETS: tuple[str, ...] = tuple(BACKENDS)
"""Names of the code generation targets, in the order of the documentation."""


def backend(target: str) -> Backend:
    """The :class:`Backend` of ``target``; :class:`~symjac.errors.CodegenError` naming the choices if unknown.

    Examples
    --------
    >>> backend("numpy").template
    'numpy/module.py.j2'
    """
    try:
        return BACKENDS[target]
    except (KeyError, TypeError):
        raise CodegenError(f"unknown target {target!r}; choose one of {', '.join(TARGETS)}") from None

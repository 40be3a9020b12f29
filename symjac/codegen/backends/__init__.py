"""The registry of targets: every module of this package defines one :class:`~symjac.codegen.description.Backend`.

A module here is a target: adding one means adding its module (with ``BACKEND = Backend(...)``), its template in
``templates/`` and its golden files; :data:`TARGETS`, the CLI's ``--target`` choices and the tests' parametrization
all read this registry.
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
    """Import every module of this package and collect its ``BACKEND``, ordered by :attr:`Backend.order`."""
    found: list[Backend] = []
    for info in pkgutil.iter_modules(__path__):
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
TARGETS: tuple[str, ...] = tuple(BACKENDS)


def backend(target: str) -> Backend:
    """The :class:`Backend` of ``target``; :class:`~symjac.errors.CodegenError` naming the choices if unknown.

    Examples
    --------
    >>> backend("numpy").template
    'numpy_module.py.j2'
    """
    try:
        return BACKENDS[target]
    except (KeyError, TypeError):
        raise CodegenError(f"unknown target {target!r}; choose one of {', '.join(TARGETS)}") from None

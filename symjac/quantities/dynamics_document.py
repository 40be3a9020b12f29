"""The ``symjac dynamics`` command's derivation and document (in progress)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from symjac.errors import ArgumentError

if TYPE_CHECKING:
    from symjac.printing.document import Document
    from symjac.quantities.spec import Request

__all__ = ["dynamics_command", "dynamics_document"]


def dynamics_command(request: Request) -> Document:
    """The parts of the dynamics asked for, derived."""
    raise ArgumentError("symjac dynamics is not written yet")


def dynamics_document(*args: Any, **kwargs: Any) -> Document:
    """The document of the dynamics parts."""
    raise ArgumentError("symjac dynamics is not written yet")

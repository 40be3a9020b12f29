"""Where a long derivation is: stages reported to whoever listens, never printed by the mathematics itself.

Pure modules call :func:`report` at the start of each costly stage (``"velocity propagation, link 7 of 30"``). By
default nobody listens and a report costs one context-variable lookup. A front end that wants to show progress
installs a listener for the duration of a computation with :func:`reporting_to` (the command line does, and prints
the latest stage on a terminal); the listener is context-local, so threads and async tasks do not see each other's.

Examples
--------
>>> stages = []
>>> with reporting_to(stages.append):
...     report("link 1 of 2")
>>> stages
['link 1 of 2']
>>> report("nobody listens")  # does nothing
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

__all__ = ["report", "reporting_to"]

_LISTENER: ContextVar[Callable[[str], None] | None] = ContextVar("symjac_progress_listener", default=None)


def report(stage: str) -> None:
    """Tell the current listener (if any) that the computation has reached ``stage``."""
    listener = _LISTENER.get()
    if listener is not None:
        listener(stage)


@contextmanager
def reporting_to(listener: Callable[[str], None]) -> Iterator[None]:
    """Send every :func:`report` made inside the ``with`` block to ``listener``."""
    token = _LISTENER.set(listener)
    try:
        yield
    finally:
        _LISTENER.reset(token)

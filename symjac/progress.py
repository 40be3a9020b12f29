"""Where a long derivation is: stages reported to whoever listens, never printed by the mathematics itself.

Pure modules call :func:`report` at the start of each costly stage (``"velocity propagation, link 7 of 30"``), and
may name a larger step with :func:`within` (its stages then read ``"Jacobian of puma560, cross product, joint 3 of
6"``). By default nobody listens and a report costs one context-variable lookup (about 0.1 us; the stage text is
built by the caller, a few hundred ns, so reports belong once per link or joint, never per expression). A front end
that wants to show progress installs a listener for the duration of a computation with :func:`reporting_to` (the
command line does: :func:`symjac.cli.output.progress_line`); the listener is context-local, so threads and async
tasks do not see each other's.

Examples
--------
>>> stages = []
>>> with reporting_to(stages.append), within("Jacobian"):
...     report("link 1 of 2")
>>> stages
['Jacobian', 'Jacobian, link 1 of 2']
>>> report("nobody listens")  # does nothing
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar

__all__ = ["report", "reporting_to", "within"]

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


@contextmanager
def within(what: str) -> Iterator[None]:
    """Report ``what``, then every stage reported inside the ``with`` block as ``"what, stage"``."""
    outer = _LISTENER.get()
    if outer is None:  # nobody listens: nothing to name
        yield
        return
    outer(what)
    with reporting_to(lambda stage: outer(f"{what}, {stage}")):
        yield

"""Output of the ``symjac`` command: progress on a terminal, the result to stdout or a file, errors as one line."""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from typing import Any

from symjac.errors import SymjacError
from symjac.files import write_text
from symjac.progress import reporting_to

__all__ = ["LARGE_CHAIN", "emit", "note_if_large", "one_line", "progress", "silence_stdout"]

LARGE_CHAIN = 40
"""Joints above which the command line says, before it starts, that a symbolic result will take long."""


def progress(what: str, compute: Callable[[], Any]) -> Any:
    """Run ``compute``, telling a human on a terminal what is happening and how long it took.

    After the first second, the stage the derivation has reached (what :func:`symjac.progress.report` was last
    told: a link, a joint, an angle basis) replaces the end of the line, at most a few times a second.
    """
    interactive = sys.stderr.isatty()
    if not interactive:
        return compute()
    head = f"deriving {what} ..."
    print(head, end="", file=sys.stderr, flush=True)
    start = time.perf_counter()
    shown = [start]  # when the line was last rewritten

    def show(stage: str) -> None:
        now = time.perf_counter()
        if now - start >= 1.0 and now - shown[0] >= 0.2:
            shown[0] = now
            print(f"\r{head} {now - start:.0f} s, {stage}\x1b[K", end="", file=sys.stderr, flush=True)

    try:
        with reporting_to(show):
            result = compute()
    except BaseException:
        print(file=sys.stderr)  # end the progress line, so the error or "interrupted" starts its own
        raise
    print(f"\r{head} {time.perf_counter() - start:.2f} s\x1b[K", file=sys.stderr)
    return result


def note_if_large(name: str, n_joints: int) -> None:
    """Say on stderr, before a derivation starts, that a chain with more than :data:`LARGE_CHAIN` joints is slow."""
    if n_joints > LARGE_CHAIN:
        print(f"symjac: note: {name} has {n_joints} joints; symbolic results this long can take minutes. Narrow the "
              "request to a sub-chain (a robot file with fewer joints, or --base-link/--tip-link of a URDF file); "
              "Ctrl-C stops cleanly.", file=sys.stderr, flush=True)


def emit(text: str, output: str | None) -> None:
    """Write the finished text to stdout (no ``-o``, or ``-o -``), or to ``output`` (:func:`.write_text`)."""
    if output is None or output == "-":
        sys.stdout.write(text)
        sys.stdout.flush()  # a closed pipe shows here, inside main, not at interpreter exit
    else:
        write_text(output, text)


def one_line(error: Exception) -> str:
    """What went wrong, on one line: symjac's own message, the file and reason of an OSError, or the error's type."""
    if isinstance(error, SymjacError):
        message = str(error)
    elif isinstance(error, OSError) and error.strerror:
        message = f"{error.filename}: {error.strerror}" if error.filename is not None else error.strerror
    elif isinstance(error, RecursionError):
        message = "the input is nested too deeply to process"
    elif isinstance(error, MemoryError):
        message = "out of memory"
    else:
        message = f"{type(error).__name__}: {error}"
    return " ".join(message.splitlines())


def silence_stdout() -> None:
    """Point stdout at /dev/null, so the interpreter's final flush does not report the broken pipe again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # stdout has no file descriptor (a captured stream): nothing left to flush
        pass

"""Output of the ``symjac`` command: progress on a terminal, the result to stdout or a file, errors as one line."""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from typing import Any

from symjac.errors import SymjacError
from symjac.files import write_text

__all__ = ["emit", "one_line", "progress", "silence_stdout"]


def progress(what: str, compute: Callable[[], Any]) -> Any:
    """Run ``compute``, telling a human on a terminal what is happening and how long it took."""
    interactive = sys.stderr.isatty()
    if interactive:
        print(f"deriving {what} ...", end="", file=sys.stderr, flush=True)
    start = time.perf_counter()
    try:
        result = compute()
    except BaseException:
        if interactive:
            print(file=sys.stderr)  # end the progress line, so the error or "interrupted" starts its own
        raise
    if interactive:
        print(f" {time.perf_counter() - start:.2f} s", file=sys.stderr)
    return result


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

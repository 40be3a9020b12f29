"""Output of the ``symjac`` command: progress on a terminal, the result to stdout or a file, errors as one line."""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from typing import Any, TextIO, TypeVar

from symjac.errors import SymjacError
from symjac.files import write_text
from symjac.progress import reporting_to, within

__all__ = ["LARGE_CHAIN", "PROGRESS_DELAY", "PROGRESS_INTERVAL", "emit", "note_if_large", "one_line", "progress",
           "progress_line", "silence_stdout"]

T = TypeVar("T")

LARGE_CHAIN = 40
"""Joints above which the command line says, before it starts, that a symbolic result will take long."""
PROGRESS_DELAY = 2.0
"""Seconds a command runs before its progress line appears (and another line on stderr stays alone)."""
PROGRESS_INTERVAL = 0.2
"""Seconds between two rewrites of the progress line."""


def progress(what: str, compute: Callable[[], T]) -> T:
    """Run ``compute``, its stages shown on the progress line as ``"what, stage"`` (:func:`progress_line`)."""
    with within(what):
        return compute()


@contextmanager
def progress_line(command: str) -> Iterator[None]:
    r"""While the block runs, show on a terminal's stderr the latest stage reported (:mod:`symjac.progress`).

    The line appears only after :data:`PROGRESS_DELAY` seconds, so quick commands print nothing; a daemon thread then
    rewrites it in place (``\r``) every :data:`PROGRESS_INTERVAL` seconds, with the time spent, so that a long SymPy
    call between two reports still shows where it is. Anything else written to ``sys.stderr`` meanwhile (a warning,
    a note, dask's progress bar) first clears the line, which then waits :data:`PROGRESS_DELAY` seconds before it
    comes back; the line is cleared when the block ends, however it ends (an error, Ctrl-C). When stderr is not a
    terminal nothing is installed and nothing is written; stdout is never touched.
    """
    stream = sys.stderr
    try:
        interactive = stream.isatty()
    except (AttributeError, OSError, ValueError):  # a closed or file-like stream without a terminal behind it
        interactive = False
    if not interactive:
        yield
        return
    line = _ProgressLine(stream, f"symjac {command}")
    thread = threading.Thread(target=line.run, name="symjac progress line", daemon=True)
    sys.stderr = _Interleaved(line)  # type: ignore[assignment]  # a stream by duck typing
    thread.start()
    try:
        with reporting_to(line.listen):
            yield
    finally:
        line.stopped.set()
        try:
            thread.join()
        finally:
            sys.stderr = stream
            line.clear()


class _ProgressLine:
    """The state of one progress line: the latest stage, whether the line is on screen, when it may show."""

    def __init__(self, stream: TextIO, head: str):
        self.stream, self.head, self.stage = stream, head, ""
        self.start = time.monotonic()
        self.hidden_until = self.start + PROGRESS_DELAY
        self.shown = False
        self.lock = threading.Lock()
        self.stopped = threading.Event()

    def listen(self, stage: str) -> None:
        """The listener: keep the latest stage (the thread shows it; a report itself writes nothing)."""
        self.stage = stage

    def run(self) -> None:
        """The thread: rewrite the line until stopped."""
        while not self.stopped.wait(PROGRESS_INTERVAL):
            with self.lock:
                now = time.monotonic()
                if now < self.hidden_until or self.stopped.is_set():
                    continue
                self._write(f"\r{self._text(now)}\x1b[K")
                self.shown = True

    def _text(self, now: float) -> str:
        """The line: what runs, for how long, and the end of the stage (a line longer than the terminal would wrap)."""
        text = f"{self.head}: {now - self.start:.0f} s"
        room = _width(self.stream) - 1 - len(text) - len(", ")
        stage = self.stage if len(self.stage) <= room else "..." + self.stage[len(self.stage) - room + 3:]
        return f"{text}, {stage}" if stage and room > 3 else text

    def clear(self) -> None:
        """Take the line off the screen (the cursor back at its start), if it is there."""
        with self.lock:
            self._clear()

    def _clear(self) -> None:
        if self.shown:
            self._write("\r\x1b[K")
            self.shown = False

    def other(self, text: str) -> int:
        """Someone else's text for stderr: written after the line is cleared, then left alone for a while."""
        with self.lock:
            self._clear()
            self.hidden_until = time.monotonic() + PROGRESS_DELAY
            return self.stream.write(text)

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError):  # stderr closed under us: progress is not worth an error
            self.stopped.set()


class _Interleaved:
    """``sys.stderr`` while a progress line is up: every write clears the line first (:func:`progress_line`)."""

    def __init__(self, line: _ProgressLine):
        self._line = line

    def write(self, text: str) -> int:
        return self._line.other(text)

    def writelines(self, lines: Iterable[str]) -> None:
        self.write("".join(lines))

    def __getattr__(self, name: str) -> Any:
        return getattr(self._line.stream, name)


def _width(stream: TextIO) -> int:
    """Columns of the terminal behind ``stream`` (80 when it cannot say): a longer line would wrap, not rewrite."""
    try:
        return os.get_terminal_size(stream.fileno()).columns or 80
    except (AttributeError, OSError, ValueError):
        return 80


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

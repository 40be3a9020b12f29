"""Writing results to files: atomically, so a failure never leaves a partial file behind."""

from __future__ import annotations

import errno
import os
import stat
import tempfile
from collections.abc import Mapping
from pathlib import Path

__all__ = ["write_bytes", "write_files", "write_text"]

# Paths that name a process's own streams or kernel objects (``/dev/stdout`` resolves through ``/proc/self/fd/1``
# to whatever the shell redirected it to): always written through, never replaced.
_SPECIAL_ROOTS = ("/dev/", "/proc/")


def write_text(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` (UTF-8, newline line ends) to ``path`` and return the path.

    What is at ``path`` decides how:

    - nothing, or a regular file: the text goes to a temporary file in the same folder, which then replaces the file
      (:func:`os.replace`), so a failure leaves no partial file and an existing file untouched. A new file gets the
      permissions the umask allows (0644 under the usual umask 022, 0640 under 027); a replaced file keeps its own.
    - a symbolic link: the same, done to the file the link points to; the link stays a link.
    - a FIFO, a device (``/dev/null``, ``/dev/stdout``) or a socket: opened and written through, never replaced.
    - a directory: :class:`IsADirectoryError`.

    Every :class:`OSError` raised names ``path`` as given, never the temporary file.
    """
    return _write(path, text)


def write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` (an image, an animation) to ``path`` as :func:`write_text` writes text: whole or not at all."""
    return _write(path, data)


def _write(path: str | os.PathLike[str], data: str | bytes) -> Path:
    target = Path(path)
    try:
        if _is_special(target):
            with open(target, "wb") as stream:
                stream.write(data.encode("utf-8") if isinstance(data, str) else data)
        else:
            _replace(Path(os.path.realpath(target)), data)
    except OSError as error:
        raise _naming(error, target) from None
    return target


def _is_special(target: Path) -> bool:
    """Whether ``target`` is to be written through: anything that exists and is not a regular file."""
    try:
        mode: int | None = target.stat().st_mode  # follows symbolic links
    except FileNotFoundError:
        mode = None  # a new file, or a dangling link: created where the link points
    if mode is not None and stat.S_ISDIR(mode):
        raise IsADirectoryError(errno.EISDIR, "is a directory, not a file", str(target))
    if str(target.absolute()).startswith(_SPECIAL_ROOTS):
        return True
    return mode is not None and not stat.S_ISREG(mode)


def _replace(real: Path, text: str | bytes) -> None:
    """Atomically replace (or create) the regular file ``real``, keeping an existing file's permissions."""
    temporary = _stage(real, text)
    try:
        os.replace(temporary, real)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise


def _naming(error: OSError, target: Path) -> OSError:
    """The same error, naming the user's path (and no second, internal file name)."""
    if error.errno is None:  # pragma: no cover - every OSError the calls above raise carries an errno
        return error
    return type(error)(error.errno, error.strerror, str(target))


def write_files(files: Mapping[Path, str | bytes]) -> None:
    """Write several regular files (text as UTF-8, or bytes) all or none, each through a temporary file beside it.

    Only when every temporary file is written do they replace their targets (:func:`os.replace`, in the given
    order); if a replacement fails, those already done are put back (old content restored, new files removed). An
    error names the path as given. A special file (a FIFO, a device) or a folder among the targets is refused.
    """
    staged: list[tuple[Path, Path, Path]] = []  # (target as given, real path, temporary)
    try:
        for target, text in files.items():
            if _is_special(target):
                raise _naming(OSError(errno.EINVAL, "is not a regular file; several files are written only to "
                                                    "regular files"), target)
            real = Path(os.path.realpath(target))
            try:
                staged.append((target, real, _stage(real, text)))
            except OSError as error:
                raise _naming(error, target) from None
        _commit(staged)
    finally:
        for _, _, temporary in staged:
            temporary.unlink(missing_ok=True)


def _stage(real: Path, text: str | bytes) -> Path:
    """``text`` (or bytes) in a temporary file beside ``real``, with the permissions ``real`` has (or the umask's)."""
    try:
        mode = real.stat().st_mode & 0o7777
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o666 & ~umask
    handle, temporary = tempfile.mkstemp(dir=real.parent, prefix=f".{real.name}.", suffix=".tmp")
    try:
        if isinstance(text, bytes):
            with os.fdopen(handle, "wb") as binary:
                binary.write(text)
        else:
            with os.fdopen(handle, "w", encoding="utf-8", newline="\n") as stream:
                stream.write(text)
        os.chmod(temporary, mode)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return Path(temporary)


def _commit(staged: list[tuple[Path, Path, Path]]) -> None:
    """Replace each target by its staged file; on a failure, undo the replacements already done."""
    done: list[tuple[Path, bytes | None]] = []
    for target, real, temporary in staged:
        try:
            old = real.read_bytes() if real.exists() else None
            os.replace(temporary, real)
        except OSError as error:
            for undone, previous in reversed(done):
                if previous is None:
                    undone.unlink(missing_ok=True)
                else:
                    undone.write_bytes(previous)
            raise _naming(error, target) from None
        done.append((real, old))

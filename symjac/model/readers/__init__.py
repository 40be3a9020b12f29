r"""Robot readers as plug-ins: each file format is one :class:`Reader`, chosen by the file's content.

A reader has a name (``"URDF"``), a sniffing function that decides from the first bytes of a file whether they are
its format (URDF claims the XML root element ``<robot>``, MJCF claims ``<mujoco>``), and a ``read`` function
``read(content, source, *, base_link, tip_link[, max_bytes][, tip_site]) -> Robot``. Tree formats
(:attr:`Reader.tree`) go through the shared :class:`~symjac.model.readers.tree.KinematicTree` and
:func:`~symjac.model.readers.tree.robot_from_tree`, so ``base_link`` and ``tip_link`` mean the same for all of them.
:func:`symjac.model.io.load_robot` asks :func:`reader_for` which reader takes a file; a file no reader claims gets
one line naming the formats known::

    arm.xml: not a robot file symjac reads (root element <sdf>); formats: MJCF, TOML robot file, URDF

This module imports nothing heavy: a reader's own module is imported when a file of its format is read.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from importlib import import_module
from typing import TYPE_CHECKING, Any

from symjac.errors import RobotFileError

if TYPE_CHECKING:
    from symjac.model.robot import Robot

__all__ = ["HEAD_BYTES", "MAX_TREE_LINKS", "LinksNotApplicableError", "Reader", "reader_for", "readers", "register",
           "too_large", "too_many_links", "tree_formats", "unregister", "xml_root"]

HEAD_BYTES = 65_536
"""How much of a file's start the sniffing functions see (a license comment before the root element fits)."""


@dataclass(frozen=True)
class Reader:
    """One robot file format.

    Parameters
    ----------
    name : str
        How messages name the format (``"URDF"``, ``"TOML robot file"``).
    sniff : callable
        ``sniff(head: bytes) -> bool``: whether a file starting with ``head`` (at most :data:`HEAD_BYTES`) is in
        this format. Decide by content, never by the file's name.
    read : callable
        ``read(content: bytes, source: str, *, base_link, tip_link[, max_bytes]) -> Robot``; ``source`` names the
        file in errors; ``max_bytes``, the size limit in force (:attr:`max_bytes`, or the caller's), is passed
        whenever there is one, so a reader with a limit checks what it reads besides the file (included files).
    tree : bool
        Whether the format is a kinematic tree, so that ``base_link`` and ``tip_link`` choose its chain.
    suffixes : tuple of str
        File name suffixes of the format (``".urdf"``): a file whose content no reader claims is given to the
        reader of its suffix, whose own error says what is wrong with it.
    max_bytes : int, optional
        The largest file read by default (refused in one line before it is read, see :func:`too_large`).
    sites : bool
        Whether the format names points on links (MJCF sites): ``read`` then takes ``tip_site`` too.
    """

    name: str
    sniff: Callable[[bytes], bool]
    read: Callable[..., Robot]
    tree: bool = False
    suffixes: tuple[str, ...] = ()
    max_bytes: int | None = None
    sites: bool = False


MAX_TREE_LINKS = 5_000
"""The most links (URDF links, MJCF bodies) a tree may have: the largest robot of a public collection of 69 has a few
hundred, and each link costs exact arithmetic, so a file with more is refused in one line before it is built."""


def too_many_links(count: int, source: str) -> None:
    """Refuse a tree of more than :data:`MAX_TREE_LINKS` links (``count``), in one line naming ``source``."""
    if count > MAX_TREE_LINKS:
        raise RobotFileError(f"{count} links (bodies) is more than the {MAX_TREE_LINKS} a robot tree may have",
                             source=source)


def too_large(limit: int) -> str:
    r"""Why a file over ``limit`` bytes is refused, and how to read it anyway (one line, for every reader).

    A reader parses the whole file in memory; real robot files are kilobytes, so the limit keeps out runaway and
    hostile files before any parsing starts.

    >>> print(too_large(5_000_000).replace(": ", ":\n"))
    file larger than 5000000 bytes, the limit that keeps runaway files out (robot files are kilobytes):
    raise it with max_bytes (--max-bytes on the command line) to read it
    """
    return (f"file larger than {limit} bytes, the limit that keeps runaway files out (robot files are kilobytes): "
            f"raise it with max_bytes (--max-bytes on the command line) to read it")


class LinksNotApplicableError(RobotFileError):
    """``base_link`` or ``tip_link`` was given for a robot whose format is no kinematic tree (a TOML robot file).

    ``formats`` names the tree formats (``"URDF"``), for a message in the caller's own words.
    """

    def __init__(self, source: str, formats: str):
        self.formats = formats
        super().__init__(f"base_link and tip_link apply to {formats} files only", source=source)


_READERS: dict[str, Reader] = {}


def register(reader: Reader) -> Reader:
    """Add ``reader`` (replacing the one of the same name); the first that claims a file reads it."""
    _READERS[reader.name] = reader
    return reader


def unregister(name: str) -> None:
    """Remove the reader called ``name`` (nothing if there is none)."""
    _READERS.pop(name, None)


def readers() -> tuple[Reader, ...]:
    """The registered readers, in the order they are asked."""
    return tuple(_READERS.values())


def tree_formats() -> str:
    """The names of the tree formats, for messages: ``"URDF"``, ``"URDF and MJCF"``."""
    names = [reader.name for reader in _READERS.values() if reader.tree]
    return " and ".join([", ".join(names[:-1]), names[-1]] if len(names) > 1 else names)


def reader_for(head: bytes, source: str, suffix: str = "") -> Reader:
    """The reader of a file starting with ``head``: the first that claims its content, else the one of its suffix.

    Raises
    ------
    RobotFileError
        When no reader claims the content and none has the suffix: one line naming what the file is and the formats
        symjac reads.
    """
    for reader in _READERS.values():
        if reader.sniff(head):
            return reader
    for reader in _READERS.values():
        if suffix.lower() in reader.suffixes:
            return reader
    formats = ", ".join(sorted(reader.name for reader in _READERS.values()))
    raise RobotFileError(f"not a robot file symjac reads ({_what(head)}); formats: {formats}", source=source)


def _what(head: bytes) -> str:
    """A few words on what a file no reader claims holds."""
    root = xml_root(head)
    if root is not None:
        return f"root element <{root}>"
    if _text(head) is None:
        return "binary data"
    return "text that is neither TOML nor XML" if head.strip() else "an empty file"


_BOM = b"\xef\xbb\xbf"
# linear patterns only (no nested repetition): a hostile head must not make the sniffing slow
_PROLOG = re.compile(rb"\s*(?:<\?.*?\?>|<!--.*?-->|<!DOCTYPE[^\[>]*(?:\[[^\]]*\])?[^>]*>)", re.DOTALL | re.IGNORECASE)
_ROOT = re.compile(rb"\s*<([A-Za-z_][\w.:-]*)")


def xml_root(head: bytes) -> str | None:
    r"""The name of the root element of an XML document starting with ``head`` (None if it is not XML).

    The XML declaration, comments, processing instructions and a document type declaration before the root are
    skipped; nothing is parsed or expanded. A namespace prefix is kept (``xacro:macro``).

    Examples
    --------
    >>> xml_root(b'<?xml version="1.0"?>\n<!-- an arm -->\n<robot name="arm">')
    'robot'
    >>> xml_root(b'name = "arm"') is None
    True
    """
    position = len(_BOM) if head.startswith(_BOM) else 0
    while match := _PROLOG.match(head, position):
        position = match.end()
    root = _ROOT.match(head, position)
    return root.group(1).decode("ascii") if root else None


def _text(head: bytes) -> str | None:
    """``head`` as UTF-8 text (a character cut at the end forgiven), or None for binary data."""
    if b"\x00" in head:
        return None
    try:
        return head.removeprefix(_BOM).decode("utf-8")
    except UnicodeDecodeError as error:
        return head[len(_BOM) if head.startswith(_BOM) else 0:error.start].decode("utf-8") \
            if error.start >= len(head) - 3 else None


# a TOML document's first statement: a key (bare, quoted or dotted) and '=', or a [table] / [[array]] header
_KEY = r"""(?:[A-Za-z0-9_-]+|"[^"\n]*"|'[^'\n]*')"""
_TOML_START = re.compile(rf"{_KEY}(?:\s*\.\s*{_KEY})*\s*=|\[")


def _is_toml(head: bytes) -> bool:
    """Text whose first statement (after blank lines and ``#`` comments) is TOML's, or only comments: TOML."""
    text = _text(head)
    if text is None or not text.strip():  # an empty file is any format's: its suffix decides
        return False
    for line in text.splitlines():
        stripped = line.strip()
        if stripped and not stripped.startswith("#"):
            return _TOML_START.match(stripped) is not None
    return True  # empty, or only comments: the TOML reader says what a robot file needs


def _read_toml(content: bytes, source: str, *, base_link: str | None = None, tip_link: str | None = None,
               max_bytes: int | None = None) -> Robot:
    robot_from_toml: Any = import_module("symjac.model.io").robot_from_toml  # io imports this module: late
    try:
        text = content.decode("utf-8-sig")  # a byte-order mark, as some editors write, is no TOML
    except UnicodeDecodeError as error:
        raise RobotFileError(f"cannot read file: {error}", source=source) from None
    return robot_from_toml(text, source=source)  # type: ignore[no-any-return]


def _read_urdf(content: bytes, source: str, *, base_link: str | None = None, tip_link: str | None = None,
               max_bytes: int | None = None) -> Robot:
    from symjac.model.readers.urdf import MAX_URDF_BYTES, robot_from_urdf  # the XML machinery only for a URDF

    return robot_from_urdf(content, source=source, base_link=base_link, tip_link=tip_link,
                           max_bytes=MAX_URDF_BYTES if max_bytes is None else max_bytes)


def _read_mjcf(content: bytes, source: str, *, base_link: str | None = None, tip_link: str | None = None,
               tip_site: str | None = None, max_bytes: int | None = None) -> Robot:
    from symjac.model.readers.mjcf import MAX_MJCF_BYTES, robot_from_mjcf  # the XML machinery only for MJCF

    return robot_from_mjcf(content, source=source, base_link=base_link, tip_link=tip_link, tip_site=tip_site,
                           max_bytes=MAX_MJCF_BYTES if max_bytes is None else max_bytes)


register(Reader("TOML robot file", _is_toml, _read_toml, suffixes=(".toml",)))
register(Reader("URDF", lambda head: xml_root(head) == "robot", _read_urdf, tree=True, suffixes=(".urdf",),
                max_bytes=5_000_000))  # MAX_URDF_BYTES, without importing the reader to know it
register(Reader("MJCF", lambda head: xml_root(head) == "mujoco", _read_mjcf, tree=True, suffixes=(".mjcf",),
                max_bytes=5_000_000, sites=True))  # MAX_MJCF_BYTES (with the included files)

r"""MJCF documents read safely: one XML tree with its ``<include>`` files in place, the compiler and default classes.

Safety
    Every file (the model and each included one) is parsed with the standard library's expat parser after refusing
    any document type or entity declaration, so no entity is expanded and nothing but the included files is read.
    ``<include file>`` names a file relative to the model's folder (MuJoCo's rule, also for includes inside included
    files); a file outside that folder (through the parent folder, an absolute path, a symbolic link leading out) is
    refused, and so is a file included twice (which is also how an include loop ends). The model and its included
    files together may hold at most :data:`MAX_MJCF_BYTES`. Elements that create bodies symjac does not expand
    (``<replicate>``, ``<attach>``, ``<composite>``, ``<flexcomp>``) are refused rather than silently left out.

Default classes
    The top-level ``<default>`` is class ``main``; a ``<default class>`` inside another inherits its settings and
    overrides them. An element takes the attributes of its ``class``, else of the ``childclass`` of the nearest
    enclosing ``<body>`` or ``<frame>`` that has one, else of ``main``; its own attributes win. An orientation given on
    the element replaces the class's orientation whatever its kind (``euler`` on the element, ``quat`` in the class).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

from symjac.errors import RobotFileError
from symjac.model.readers import too_large
from symjac.model.readers.mjcf_frames import ORIENTATIONS, Compiler

__all__ = ["MAX_MJCF_BYTES", "MAX_MJCF_INCLUDES", "Defaults", "compiler_of", "defaults_of", "model_root"]

MAX_MJCF_BYTES = 5_000_000
"""Largest MJCF model read, in bytes, with its included files (a Menagerie arm is tens of kilobytes)."""
MAX_MJCF_INCLUDES = 200
"""Most ``<include>`` elements followed in one model."""
_DECLARATION = re.compile(rb"<!\s*(DOCTYPE|ENTITY|ELEMENT|ATTLIST)", re.IGNORECASE)
_ENCODING = re.compile(rb"""^(?:\xef\xbb\xbf)?\s*<\?xml[^>]*encoding\s*=\s*["']([A-Za-z0-9._-]+)["']""")
_UNEXPANDED = ("replicate", "attach", "composite", "flexcomp")
_DEFAULTED = ("joint", "site", "equality")  # the elements whose defaults the kinematics reads


def _fail(source: str, message: str, element: str | None = None) -> RobotFileError:
    return RobotFileError(message, source=source, field=element)


def _parse(data: bytes, source: str) -> ET.Element:
    """One file's XML tree, refusing declarations, other encodings, NUL bytes and roots other than ``<mujoco>``."""
    if b"\x00" in data:
        raise _fail(source, "not a UTF-8 text file (NUL bytes)")
    declared = _ENCODING.match(data)
    if declared and declared.group(1).decode("ascii").lower().replace("_", "-") not in ("utf-8", "utf8"):
        raise _fail(source, f"only UTF-8 MJCF files are read, this one declares {declared.group(1).decode('ascii')!r}")
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise _fail(source, f"not UTF-8 text: {error}") from None
    if _DECLARATION.search(data):  # where entities live (billion laughs, external files): refused before parsing
        raise _fail(source, "document type and entity declarations (<!DOCTYPE, <!ENTITY) are not allowed in MJCF")
    try:
        root = ET.fromstring(data)
    except ET.ParseError as error:
        raise _fail(source, f"invalid XML: {error}") from None
    if root.tag != "mujoco":
        raise _fail(source, f"the root element must be <mujoco>, got <{root.tag}>")
    return root


@dataclass
class _Includes:
    folder: Path | None
    total: int
    limit: int
    seen: set[Path] = field(default_factory=set)
    count: int = 0


def model_root(data: bytes, source: str, folder: Path | None, max_bytes: int = MAX_MJCF_BYTES) -> ET.Element:
    """The model's ``<mujoco>`` element with every ``<include>`` replaced by the included file's elements.

    ``folder`` is the model's folder (None when the model is no file: then an include is refused); the model and its
    included files hold at most ``max_bytes`` together.
    """
    if len(data) > max_bytes:
        raise _fail(source, too_large(max_bytes))
    root = _parse(data, source)
    _expand(root, source, _Includes(folder, len(data), max_bytes))
    for tag in _UNEXPANDED:
        if root.find(f".//{tag}") is not None:
            raise _fail(source, f"<{tag}> is not read (symjac does not expand the bodies it makes); expand the model "
                                "first, e.g. with MuJoCo's compile tool", tag)
    return root


def _expand(element: ET.Element, source: str, includes: _Includes) -> None:
    """Replace the ``<include>`` children of ``element`` (and below) in place, depth first, iteratively."""
    stack = [element]
    while stack:
        parent = stack.pop()
        index = 0
        while index < len(parent):
            child = parent[index]
            if child.tag != "include":
                stack.append(child)
                index += 1
                continue
            included = _included(child.get("file"), source, includes)
            parent.remove(child)
            for offset, part in enumerate(included):
                parent.insert(index + offset, part)
            # the inserted elements are looked at again: an included file may include others


def _included(name: str | None, source: str, includes: _Includes) -> ET.Element:
    if not name:
        raise _fail(source, "<include> needs file=...", "include")
    where = f"include {name[:200]}"
    if includes.folder is None:
        raise _fail(source, "<include> needs the model's folder: load the model from its file", where)
    includes.count += 1
    if includes.count > MAX_MJCF_INCLUDES:
        raise _fail(source, f"more than {MAX_MJCF_INCLUDES} <include> elements", where)
    try:
        folder = includes.folder.resolve()
        path = (folder / name).resolve()
        if not path.is_relative_to(folder):
            raise _fail(source, f"included file {name[:200]!r} is outside the model's folder {str(folder)!r}", where)
        if path in includes.seen:
            raise _fail(source, f"{name[:200]!r} is included twice (an include loop, or a repeated include)", where)
        includes.seen.add(path)
        if not path.is_file():
            raise _fail(source, f"included file {name[:200]!r} does not exist in {str(folder)!r}", where)
        size = path.stat().st_size
        includes.total += size
        if includes.total > includes.limit:
            raise _fail(source, f"the model and its included files hold more than {includes.limit} bytes, the limit "
                                f"that keeps runaway files out: raise it with max_bytes (--max-bytes on the command "
                                f"line) to read them", where)
        data = path.read_bytes()
    except RobotFileError:
        raise  # said already, in one line
    except (OSError, ValueError) as error:  # a name too long for the system, a NUL byte, a file that vanished
        reason = getattr(error, "strerror", None) or error
        raise _fail(source, f"cannot read included file {name[:200]!r}: {reason}", where) from None
    return _parse(data, f"{source} (included {name})")


def compiler_of(root: ET.Element, source: str) -> Compiler:
    """The ``<compiler>`` settings: ``angle``, ``eulerseq``, ``autolimits``, ``inertiafromgeom`` (the last wins)."""
    settings: dict[str, str] = {}
    for element in root.iter("compiler"):
        settings.update(element.attrib)
    unit = settings.get("angle", "degree")
    if unit not in ("degree", "radian"):
        raise _fail(source, f"angle must be 'degree' or 'radian', got {unit!r}", "compiler")
    sequence = settings.get("eulerseq", "xyz")
    if len(sequence) != 3 or any(letter not in "xyzXYZ" for letter in sequence):
        raise _fail(source, f"eulerseq must be three of x, y, z, X, Y, Z, got {sequence!r}", "compiler")
    autolimits = settings.get("autolimits", "true")
    if autolimits not in ("true", "false"):
        raise _fail(source, f"autolimits must be 'true' or 'false', got {autolimits!r}", "compiler")
    return Compiler(unit == "degree", sequence, autolimits == "true", settings.get("inertiafromgeom") == "true")


@dataclass(frozen=True)
class Defaults:
    """The attributes each default class gives each element kind: ``classes[name][tag]``."""

    classes: dict[str, dict[str, dict[str, str]]]

    def attributes(self, element: ET.Element, childclass: str, source: str, where: str) -> dict[str, str]:
        """``element``'s attributes over those of its class (its ``class``, else ``childclass``)."""
        name = element.get("class", childclass)
        if name not in self.classes:
            raise _fail(source, f"default class {name!r} is not defined", where)
        merged = dict(self.classes[name].get(element.tag, {}))
        if any(key in element.attrib for key in ORIENTATIONS):
            for key in ORIENTATIONS:
                merged.pop(key, None)
        merged.update(element.attrib)
        merged.pop("class", None)
        return merged

    def check(self, name: str | None, source: str, where: str) -> None:
        """Refuse a ``childclass`` that names no class."""
        if name is not None and name not in self.classes:
            raise _fail(source, f"default class {name!r} is not defined", where)


def defaults_of(root: ET.Element, source: str) -> Defaults:
    """The default classes of the model: ``main`` and the nested ``<default class>`` elements."""
    classes: dict[str, dict[str, dict[str, str]]] = {"main": {}}
    stack = [(element, "main", True) for element in reversed(root.findall("default"))]
    while stack:
        element, parent, top = stack.pop()
        name = element.get("class", "main" if top else None)
        if name is None:
            raise _fail(source, "a nested <default> needs class=...", f"default in class {parent}")
        if name in classes and not (top and name == "main"):
            raise _fail(source, f"default class {name!r} is defined twice", f"default {name}")
        inherited = {tag: dict(values) for tag, values in classes[parent].items()}
        own = classes.setdefault(name, inherited)
        for child in element:
            if child.tag in _DEFAULTED:
                settings = own.setdefault(child.tag, {})
                if any(key in child.attrib for key in ORIENTATIONS):
                    for key in ORIENTATIONS:
                        settings.pop(key, None)
                settings.update(child.attrib)
        stack.extend((child, name, False) for child in reversed(element.findall("default")))
    return Defaults(classes)

"""Where a generated module comes from: how its header's command gets the robot back, and what it needs saying.

The header of every generated module says how to regenerate it: the command line that was typed, or the equivalent
``symjac.generate(...)`` call, which loads a catalog robot by name and a robot read from a file by its path. Whether
loading it again gives the same robot is checked once per robot file version (the files are read once, not once
per generated module).
"""

from __future__ import annotations

import functools
import itertools
import json
import os
import shlex
from pathlib import Path

from symjac.errors import SymjacError
from symjac.model.io import catalog, load_robot, urdf_catalog
from symjac.model.robot import Robot

__all__ = ["catalog_files", "names_relative_file", "robot_loader"]


def robot_loader(robot: Robot) -> tuple[str, str]:
    """How the header's Python call gets ``robot`` back, and a note when that needs saying.

    A catalog robot loads by name, a robot from a file by the file's path as it was given (the note says from which
    folder when it is relative) as long as loading it again gives the same robot; anything else (a mapping, a URDF
    that needed ``tip_link``) is written ``robot`` and the note says which robot that is.
    """
    names = _catalog_names()
    candidates = [robot.name] if robot.name in names else []
    candidates += [robot.source] if robot.source not in ("<mapping>", "<string>") else []
    for candidate in candidates:
        try:
            same = _loaded(candidate, _file_stamp(candidate)) == robot
        except SymjacError:
            continue
        if same:
            path = Path(candidate)
            relative = candidate not in names and not path.is_absolute() and path.is_file()
            return f"symjac.load_robot({_string(candidate)})", "in the folder it was run in" if relative else ""
    origin = "a mapping" if robot.source in ("<mapping>", "<string>") else robot.source
    return "robot", f"robot: the Robot given to symjac.generate, from {origin}"


@functools.cache
def _catalog_names() -> frozenset[str]:
    """The catalog's robot names, read once (listing the catalog reads every one of its files)."""
    return frozenset(catalog())


@functools.cache
def catalog_files() -> frozenset[str]:
    """The file names of the catalog's robots (``planar2r.toml``, ``ur5.urdf``), as their robots' ``source``."""
    return frozenset(f"{name}.toml" for name in _catalog_names()) | frozenset(urdf_catalog())


def _file_stamp(candidate: str) -> tuple[int, int] | None:
    """What says a robot file changed (modification time and size), or ``None`` for a catalog name."""
    try:
        status = os.stat(candidate)
    except OSError:
        return None
    return status.st_mtime_ns, status.st_size


@functools.lru_cache(maxsize=64)
def _loaded(candidate: str, stamp: tuple[int, int] | None) -> Robot:
    """``load_robot(candidate)``, read once per file version (``stamp``): every module of a robot asks again."""
    del stamp  # part of the cache key only
    return load_robot(candidate)


def _string(text: str) -> str:
    """A Python string literal for ``text`` in double quotes, control characters escaped (JSON's are Python's)."""
    return json.dumps(text)


def names_relative_file(source: str, command: str) -> bool:
    """Whether the command line refers to the robot file, or writes its output, through a relative path."""
    try:
        words = shlex.split(command)
    except ValueError:
        return False
    outputs = [after for before, after in itertools.pairwise(words) if before in ("-o", "--output")]
    outputs += [word.split("=", 1)[1] for word in words if word.startswith("--output=")]
    paths = [source] if Path(source).is_file() and source in words else []
    return any(not Path(path).is_absolute() and path != "-" for path in paths + outputs)

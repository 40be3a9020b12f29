"""Reading and writing robot files (TOML, URDF, MJCF), and the built-in catalog.

``load_robot`` accepts a catalog name (``"puma560"``), or a robot file in any format a reader of
:mod:`symjac.model.readers` claims by its content (a TOML robot file, a URDF file, a MuJoCo MJCF model; a built-in
URDF by its name: ``"panda.urdf"``, ``"ur5.urdf"``); ``robot_to_toml`` writes a robot back in the TOML format. The
catalog lives in ``symjac/robots/*.toml`` and ``symjac/robots/urdf/*.urdf`` inside the package, as data, not code.
"""

from __future__ import annotations

import json
import re
import sys
import tomllib
from dataclasses import replace
from importlib import resources
from pathlib import Path
from typing import Any

from symjac.errors import ArgumentError, RobotFileError, UnknownRobotError
from symjac.model.readers import (
    HEAD_BYTES,
    LinksNotApplicableError,
    Reader,
    reader_for,
    readers,
    too_large,
    tree_formats,
)
from symjac.model.readers.tree import ChainChoiceError
from symjac.model.robot import Robot
from symjac.model.robot_file import robot_from_mapping, robot_to_mapping

__all__ = ["catalog", "load_robot", "robot_from_toml", "robot_to_toml", "urdf_catalog"]


def catalog() -> dict[str, str]:
    """Names of the built-in robots, each with its one-line description, sorted by name."""
    robots = {}
    for entry in sorted(resources.files("symjac.robots").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            data = tomllib.loads(entry.read_text(encoding="utf-8"))
            robots[entry.name.removesuffix(".toml")] = data.get("description", "")
    return robots


def urdf_catalog() -> dict[str, str]:
    """The built-in URDF files (load them as ``load_robot("panda.urdf")``), each with its description."""
    robots = {}
    for entry in sorted(resources.files("symjac.robots").joinpath("urdf").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".urdf"):
            match = re.search(r"<!--\s*description:\s*(.*?)\s*-->", entry.read_text(encoding="utf-8"))
            robots[entry.name] = match.group(1) if match else ""
    return robots


def load_robot(name_or_path: str | Path, *, base_link: str | None = None, tip_link: str | None = None,
               tip_site: str | None = None, max_bytes: int | None = None) -> Robot:
    """Load a robot: a catalog name (see :func:`catalog`), or a robot file in any format symjac reads.

    A file's format is chosen by its content, whatever its name (:func:`symjac.model.readers.reader_for`): a URDF
    file is XML with the root element ``<robot>`` (``arm.xml`` too), a TOML robot file starts with a key or a table;
    a file whose content no reader claims goes to the reader of its suffix (``.urdf``, ``.toml``), which says what is
    wrong with it, or gets one line naming the formats known. A name without a directory part that is no file is
    looked up in the catalog, then among the built-in URDF files (see :func:`urdf_catalog`); a catalog name wins over
    a TOML file of the same name. ``base_link`` and ``tip_link`` choose the chain of a tree format such as URDF
    (defaults: the root link and the only leaf, or for a built-in file with several leaves the one its
    ``<!-- tip_link: ... -->`` comment names); see :mod:`symjac.model.readers.tree`. ``tip_site`` ends the chain at
    a site of an MJCF model instead (its frame is the tool frame; :mod:`symjac.model.readers.mjcf`). ``max_bytes``
    raises (or lowers) the size limit of the file's reader (:attr:`symjac.model.readers.Reader.max_bytes`: 5 MB for
    URDF and for an MJCF model with its included files).

    Raises
    ------
    UnknownRobotError
        If the argument is neither a catalog name nor an existing file.
    RobotFileError
        If the file is malformed or in no format symjac reads (the message names file, joint and field);
        :class:`~symjac.model.readers.LinksNotApplicableError` if links are given for a robot that is no tree.

    Examples
    --------
    >>> load_robot("puma560").n_joints
    6
    >>> load_robot("panda.urdf", tip_link="panda_link8").n_joints
    7
    """
    if max_bytes is not None and (isinstance(max_bytes, bool) or not isinstance(max_bytes, int) or max_bytes < 1):
        raise ArgumentError(f"max_bytes must be a positive whole number of bytes, got {max_bytes!r}")
    path = Path(name_or_path)
    head = _head(path)
    builtin = isinstance(name_or_path, str) and "/" not in name_or_path and "\\" not in name_or_path
    entry = resources.files("symjac.robots").joinpath(f"{name_or_path}.toml") \
        if builtin and path.suffix != ".toml" and name_or_path else None
    if entry is not None and not entry.is_file():
        entry = None
    if head is not None:
        try:
            reader = reader_for(head, str(path), path.suffix)
        except RobotFileError:
            if entry is None:
                raise
        else:
            if entry is None or reader.tree:  # a catalog name wins over a TOML file of the same name
                limit = reader.max_bytes if max_bytes is None else max_bytes
                return _read(reader, _file_bytes(path, limit), str(path), base_link, tip_link, tip_site, limit)
    if entry is not None:
        data = entry.read_bytes()
        return _read(reader_for(data[:HEAD_BYTES], f"{name_or_path}.toml", ".toml"), data, f"{name_or_path}.toml",
                     base_link, tip_link, tip_site, max_bytes)
    urdf_entry = resources.files("symjac.robots").joinpath("urdf", str(name_or_path)) if builtin else None
    if urdf_entry is not None and name_or_path and urdf_entry.is_file():
        data = urdf_entry.read_bytes()
        if tip_link is None:  # a built-in file with several leaves names its default tip in a comment
            tip = re.search(rb"<!--\s*tip_link:\s*([A-Za-z0-9_.-]+)\s*-->", data)
            tip_link = tip.group(1).decode("ascii") if tip else None
        return _read(reader_for(data[:HEAD_BYTES], str(name_or_path)), data, str(name_or_path), base_link, tip_link,
                     tip_site, max_bytes)
    if path.suffix.lower() == ".urdf":
        raise UnknownRobotError(f"{str(name_or_path)!r} is neither a URDF file nor a built-in one "
                                f"({', '.join(urdf_catalog())})")
    known = ", ".join(catalog())
    raise UnknownRobotError(f"{str(name_or_path)!r} is neither a built-in robot ({known}) nor a robot file")


def _head(path: Path) -> bytes | None:
    """The first :data:`~symjac.model.readers.HEAD_BYTES` of a regular file (None for a directory, a FIFO, nothing)."""
    if not path.is_file():  # a directory, a FIFO (opening it would block), or nothing
        return None
    try:
        with path.open("rb") as file:
            return file.read(HEAD_BYTES)
    except OSError as error:
        raise RobotFileError(f"cannot read file: {error}", source=str(path)) from None


def _file_bytes(path: Path, limit: int | None) -> bytes:
    """The whole file, after refusing one larger than ``limit`` bytes (the reader's own, or the caller's)."""
    try:
        if limit is not None and path.stat().st_size > limit:
            raise RobotFileError(too_large(limit), source=str(path))
        return path.read_bytes()
    except OSError as error:
        raise RobotFileError(f"cannot read file: {error}", source=str(path)) from None


def _read(reader: Reader, data: bytes, source: str, base_link: str | None, tip_link: str | None,
          tip_site: str | None, max_bytes: int | None) -> Robot:
    if not reader.tree and (base_link is not None or tip_link is not None):
        raise LinksNotApplicableError(source, tree_formats())
    options: dict[str, Any] = {} if max_bytes is None else {"max_bytes": max_bytes}  # a reader may have no limit
    if tip_site is not None:
        if not reader.sites:
            formats = " and ".join(r.name for r in readers() if r.sites)
            raise ChainChoiceError(f"{{tip_site}} applies to {formats} files only, not to a {reader.name}",
                                   source=source)
        options["tip_site"] = tip_site
    return reader.read(data, source, base_link=base_link, tip_link=tip_link, **options)


def robot_from_toml(text: str, source: str = "<string>") -> Robot:
    """Parse and validate the text of a TOML robot file."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise RobotFileError(f"invalid TOML: {error}", source=source) from None
    except ValueError:  # tomllib's int() past Python's int-string limit (sys.get_int_max_str_digits())
        raise _huge_integer(text, source) from None
    except RecursionError:
        raise RobotFileError("invalid TOML: arrays or tables nested too deeply", source=source) from None
    if not data:  # blank, or only comments
        raise RobotFileError("the file is empty: a robot file needs 'name', 'convention' and [[joints]]",
                             source=source)
    return replace(robot_from_mapping(data, source=source), source_format="TOML robot file")


def _huge_integer(text: str, source: str) -> RobotFileError:
    """The error for a decimal integer too long to read, naming its field and line when they can be found."""
    limit = sys.get_int_max_str_digits()
    match = re.search(rf"[0-9][0-9_]{{{limit},}}", text)
    if match is None:  # pragma: no cover - tomllib raises a plain ValueError only for such an integer
        return RobotFileError(f"a number is too long (more than {limit} digits)", source=source)
    line = text.count("\n", 0, match.start()) + 1
    key = re.match(r"\s*([\w\"'.-]+)\s*=", text.splitlines()[line - 1])
    digits = sum(c.isdigit() for c in match.group())
    return RobotFileError(f"integer with {digits} digits on line {line}; at most {limit} digits are read",
                          source=source, field=key.group(1).strip("\"'") if key else None)


def robot_to_toml(robot: Robot) -> str:
    """Write ``robot`` as a TOML robot file that :func:`robot_from_toml` reads back to an equal robot.

    Examples
    --------
    >>> print(robot_to_toml(load_robot("planar2r")).splitlines()[2])
    convention = "standard"
    """
    data = robot_to_mapping(robot)
    tables = [key for key, value in data.items() if isinstance(value, dict)]  # parameters, base, a convention's own
    lines = [f"{key} = {_toml_value(value)}" for key, value in data.items() if key not in tables and key != "joints"]
    if "parameters" in data:
        lines += ["", "[parameters]"] + [f"{name} = {_toml_value(v)}" for name, v in data["parameters"].items()]
    for joint in data["joints"]:
        lines += ["", "[[joints]]"] + [f"{key} = {_toml_value(v)}" for key, v in joint.items()
                                       if not isinstance(v, dict)]
        for sub in ("drive", "inertial"):  # joint i's drive and link i's inertial data: sub-tables of its joint row
            if sub in joint:
                lines += [f"[joints.{sub}]"] + [f"{key} = {_toml_value(v)}" for key, v in joint[sub].items()]
    for key in tables:
        if key != "parameters":
            lines += ["", f"[{key}]"] + [f"{k} = {_toml_value(v)}" for k, v in data[key].items()]
    return "\n".join(lines) + "\n"


def _toml_value(value: Any) -> str:
    """A TOML literal for the plain values robot files use (str, int, float, nested lists)."""
    if isinstance(value, str):
        # a JSON string is a valid TOML basic string, except that TOML also requires DEL (U+007F) escaped
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, bool):  # the product of exponentials' ``body``
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} to TOML")

"""Reading and writing robot files (TOML, URDF), and the built-in catalog.

``load_robot`` accepts a catalog name (``"puma560"``), a path to a TOML file, or a URDF file (a path, or the name of
a built-in one: ``"panda.urdf"``, ``"ur5.urdf"``); ``robot_to_toml`` writes a robot back in the TOML format. The
catalog lives in ``symjac/robots/*.toml`` and ``symjac/robots/urdf/*.urdf`` inside the package, as data, not code.
"""

from __future__ import annotations

import json
import re
import sys
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from symjac.errors import RobotFileError, UnknownRobotError
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


def load_robot(name_or_path: str | Path, *, base_link: str | None = None, tip_link: str | None = None) -> Robot:
    """Load a robot: a catalog name (see :func:`catalog`), the path of a TOML robot file, or a URDF file.

    A file whose text starts with ``<`` is read as URDF whatever its extension (``arm.xml``). A ``.urdf`` argument
    is a path, or, when no such file exists and it has no directory part, a built-in URDF file
    (see :func:`urdf_catalog`). ``base_link`` and ``tip_link`` choose the URDF chain (defaults: the root link and the
    only leaf, or for a built-in file with several leaves the one its ``<!-- tip_link: ... -->`` comment names); see
    :mod:`symjac.model.urdf`.

    Raises
    ------
    UnknownRobotError
        If the argument is neither a catalog name nor an existing file.
    RobotFileError
        If the file is malformed (the message names file, joint and field), or links are given for a TOML robot.

    Examples
    --------
    >>> load_robot("puma560").n_joints
    6
    >>> load_robot("panda.urdf", tip_link="panda_link8").n_joints
    7
    """
    path = Path(name_or_path)
    if path.suffix.lower() == ".urdf" or _is_xml(path):
        return _load_urdf(name_or_path, path, base_link, tip_link)
    if base_link is not None or tip_link is not None:
        raise RobotFileError("base_link and tip_link apply to URDF files only", source=str(name_or_path))
    if isinstance(name_or_path, str) and path.suffix != ".toml" and "/" not in name_or_path:
        entry = resources.files("symjac.robots").joinpath(f"{name_or_path}.toml")
        if entry.is_file():
            return robot_from_toml(entry.read_text(encoding="utf-8"), source=f"{name_or_path}.toml")
    if path.is_file():
        try:
            text = path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as error:
            raise RobotFileError(f"cannot read file: {error}", source=str(path)) from None
        return robot_from_toml(text, source=str(path))
    known = ", ".join(catalog())
    raise UnknownRobotError(f"{str(name_or_path)!r} is neither a built-in robot ({known}) nor a robot file")


def _is_xml(path: Path) -> bool:
    """Whether ``path`` is a file whose text starts with ``<`` (a URDF whatever its name): TOML never does."""
    if not path.is_file():  # a directory, a FIFO (opening it would block), or nothing
        return False
    try:
        with path.open("rb") as file:
            start = file.read(4096).removeprefix(b"\xef\xbb\xbf").lstrip()
    except OSError:  # not a file, or unreadable: the caller says so in its own words
        return False
    return start.startswith(b"<")


def _load_urdf(name_or_path: str | Path, path: Path, base_link: str | None, tip_link: str | None) -> Robot:
    from symjac.model.urdf import MAX_URDF_BYTES, robot_from_urdf  # the XML machinery only when a URDF is asked for

    if path.is_file():
        try:
            if path.stat().st_size > MAX_URDF_BYTES:
                raise RobotFileError(f"file larger than {MAX_URDF_BYTES} bytes", source=str(path))
            data = path.read_bytes()
        except OSError as error:
            raise RobotFileError(f"cannot read file: {error}", source=str(path)) from None
        return robot_from_urdf(data, source=str(path), base_link=base_link, tip_link=tip_link)
    if isinstance(name_or_path, str) and "/" not in name_or_path and "\\" not in name_or_path:
        entry = resources.files("symjac.robots").joinpath("urdf", name_or_path)
        if entry.is_file():
            data = entry.read_bytes()
            if tip_link is None:  # a built-in file with several leaves names its default tip in a comment
                tip = re.search(rb"<!--\s*tip_link:\s*([A-Za-z0-9_.-]+)\s*-->", data)
                tip_link = tip.group(1).decode("ascii") if tip else None
            return robot_from_urdf(data, source=name_or_path, base_link=base_link, tip_link=tip_link)
    known = ", ".join(urdf_catalog())
    raise UnknownRobotError(f"{str(name_or_path)!r} is neither a URDF file nor a built-in one ({known})")


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
    return robot_from_mapping(data, source=source)


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
        lines += ["", "[[joints]]"] + [f"{key} = {_toml_value(v)}" for key, v in joint.items() if key != "inertial"]
        if "inertial" in joint:  # link i's inertial data, a sub-table of its joint row
            lines += ["[joints.inertial]"] + [f"{key} = {_toml_value(v)}" for key, v in joint["inertial"].items()]
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

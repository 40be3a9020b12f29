"""Reading and writing robot files (TOML), and the built-in catalog.

``load_robot`` accepts a catalog name (``"puma560"``) or a path to a TOML file; ``robot_to_toml`` writes a robot
back in the same format. The catalog lives in ``symjac/robots/*.toml`` inside the package, as data, not code.
"""

from __future__ import annotations

import json
import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

from symjac.errors import RobotFileError, UnknownRobotError
from symjac.model import Robot, robot_from_mapping, robot_to_mapping

__all__ = ["catalog", "load_robot", "robot_from_toml", "robot_to_toml"]


def catalog() -> dict[str, str]:
    """Names of the built-in robots, each with its one-line description, sorted by name."""
    robots = {}
    for entry in sorted(resources.files("symjac.robots").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".toml"):
            data = tomllib.loads(entry.read_text(encoding="utf-8"))
            robots[entry.name.removesuffix(".toml")] = data.get("description", "")
    return robots


def load_robot(name_or_path: str | Path) -> Robot:
    """Load a robot: a catalog name (see :func:`catalog`) or the path of a TOML robot file.

    Raises
    ------
    UnknownRobotError
        If the argument is neither a catalog name nor an existing file.
    RobotFileError
        If the file is malformed (the message names file, joint and field).

    Examples
    --------
    >>> load_robot("puma560").dof
    6
    """
    path = Path(name_or_path)
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


def robot_from_toml(text: str, source: str = "<string>") -> Robot:
    """Parse and validate the text of a TOML robot file."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise RobotFileError(f"invalid TOML: {error}", source=source) from None
    return robot_from_mapping(data, source=source)


def robot_to_toml(robot: Robot) -> str:
    """Write ``robot`` as a TOML robot file that :func:`robot_from_toml` reads back to an equal robot.

    Examples
    --------
    >>> print(robot_to_toml(load_robot("planar2r")).splitlines()[2])
    convention = "standard"
    """
    data = robot_to_mapping(robot)
    lines = []
    for key in ("name", "description", "convention"):
        if key in data:
            lines.append(f"{key} = {_toml_value(data[key])}")
    if "parameters" in data:
        lines += ["", "[parameters]"] + [f"{name} = {_toml_value(v)}" for name, v in data["parameters"].items()]
    for joint in data["joints"]:
        lines += ["", "[[joints]]"] + [f"{key} = {_toml_value(v)}" for key, v in joint.items()]
    for key in ("base", "tool"):
        if key in data:
            lines += ["", f"[{key}]"] + [f"{k} = {_toml_value(v)}" for k, v in data[key].items()]
    return "\n".join(lines) + "\n"


def _toml_value(value: Any) -> str:
    """A TOML literal for the plain values robot files use (str, int, float, nested lists)."""
    if isinstance(value, str):
        # a JSON string is a valid TOML basic string, except that TOML also requires DEL (U+007F) escaped
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, bool):  # pragma: no cover - robot files hold no booleans
        raise TypeError("booleans are not used in robot files")
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {type(value).__name__} to TOML")

"""Conventions as plug-ins: each registered :class:`~symjac.model.robot.Convention` value and the object that knows it.

A plug-in (:class:`~symjac.model.conventions.base.ConventionPlugin`) turns its joints into the one internal joint form
the chain works from (:class:`~symjac.model.conventions.base.JointForm`), and tells the robot-file reader and writer,
the table printers and the converter what they need. A new convention is one module in this folder (with a
``PLUGIN``) and its name in :data:`MEMBERS`.
"""

from __future__ import annotations

from collections.abc import Mapping
from importlib import import_module
from typing import Any

from symjac.errors import RobotFileError
from symjac.model.conventions.base import ConventionPlugin, JointForm
from symjac.model.robot import Convention, Robot

__all__ = ["MEMBERS", "PLUGINS", "convention_named", "joint_forms", "plugin"]

MEMBERS: tuple[str, ...] = ("standard", "modified", "general", "poe")
"""The modules of this folder that are conventions, each with a ``PLUGIN``; a new convention adds its name here."""

PLUGINS: dict[Convention, ConventionPlugin] = {
    spec.convention: spec for spec in (import_module(f"{__name__}.{name}").PLUGIN for name in MEMBERS)}
"""Every convention symjac reads, by its value, in the order error messages list them."""


def plugin(convention: Convention | str) -> ConventionPlugin:
    """The plug-in of ``convention`` (a ``ValueError`` listing the registered ones if there is none)."""
    if convention in PLUGINS:
        return PLUGINS[convention]  # type: ignore[index]
    raise ValueError(f"{convention!r} is not a registered convention: {_choices()}")


def convention_named(data: Mapping[str, Any], source: str) -> Convention:
    """The registered convention a robot description names in its ``convention`` field (one-line error otherwise)."""
    if "convention" not in data:
        raise RobotFileError(f"'convention' is required (there is no default): say {_choices()}", source=source,
                             field="convention")
    text = data["convention"]
    if not isinstance(text, str) or text not in PLUGINS:
        raise RobotFileError(f"'convention' is required and must be {_choices()}, got {text!r}", source=source,
                             field="convention")
    return Convention(text)


def joint_forms(robot: Robot) -> tuple[JointForm, ...]:
    """Each joint of ``robot`` in the internal form, by its convention's plug-in."""
    return plugin(robot.convention).forms(robot)


def _choices() -> str:
    names = [f"'{name}'" for name in PLUGINS]
    return ", ".join(names[:-1]) + f" or {names[-1]}" if len(names) > 1 else names[0]

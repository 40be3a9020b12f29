"""Shared data for the robot-description tests: a minimal valid mapping, its variants and the error checks."""

from __future__ import annotations

import re
import tomllib

import pytest
import sympy as sp

from symjac.errors import RobotFileError
from symjac.model.io import catalog
from symjac.model.robot_file import robot_from_mapping

SOURCE = "arm.toml"
L1, L2 = sp.symbols("L1 L2", real=True)
theta1, theta2, theta3, d3 = sp.symbols("theta1 theta2 theta3 d3", real=True)

CATALOG = sorted(catalog())

# name -> (dof, convention, indices of prismatic joints, has base, has tool)
EXPECTED = {
    "planar2r": (2, "standard", (), False, False),
    "planar3r": (3, "modified", (), False, True),
    "articulated3r": (3, "modified", (), False, True),
    "stanford": (6, "modified", (3,), False, False),
    "puma560": (6, "modified", (), False, False),
    "scara": (4, "modified", (3,), False, False),
    "ur5": (6, "standard", (), False, False),
    "panda": (7, "modified", (), False, True),
    "palletizer": (5, "modified", (), False, False),
    "ur5_poe": (6, "poe", (), False, True),
}


def minimal(**overrides):
    """A valid two-joint planar arm; ``overrides`` replace top-level keys (value None removes the key)."""
    data = {
        "name": "arm",
        "convention": "standard",
        "parameters": {"L1": 1, "L2": 0.5},
        "joints": [{"type": "revolute", "a": "L1"}, {"type": "revolute", "a": "L2"}],
    }
    for key, value in overrides.items():
        if value is None:
            data.pop(key)
        else:
            data[key] = value
    return data


def with_joint(number, **fields):
    """``minimal()`` with joint ``number`` (1-based) updated by ``fields`` (value None removes the field)."""
    data = minimal()
    while len(data["joints"]) < number:
        data["joints"].append({"type": "revolute"})
    joint = data["joints"][number - 1]
    for key, value in fields.items():
        if value is None:
            joint.pop(key, None)
        else:
            joint[key] = value
    return data


def where(joint=None, field=None):
    """The regular expression of the location prefix of a RobotFileError message."""
    parts = [SOURCE]
    if joint is not None:
        parts.append(f"joint {joint}")
    if field is not None:
        parts.append(f"field '{field}'")
    return "^" + re.escape(", ".join(parts) + ": ")


def load_error(data, *, joint=None, field=None, message=""):
    """Check that ``data`` is rejected with the given location, and return the error."""
    with pytest.raises(RobotFileError, match=where(joint, field) + ".*" + message) as info:
        robot_from_mapping(data, source=SOURCE)
    error = info.value
    assert (error.source, error.joint, error.field) == (SOURCE, joint, field)
    return error


ROTATE_Z = [[0, -1, 0, 0.1], [1, 0, 0, 0], [0, 0, 1, "L1"], [0, 0, 0, 1]]

PLANAR = """\
name = "myarm"
description = "two links"
convention = "standard"

[parameters]
L1 = 0.5
L2 = 0.4

[[joints]]
type = "revolute"
a = "L1"

[[joints]]
type = "revolute"
a = "L2"
limits = [-3, 3]
"""


def load_robot_from_text(text):
    return robot_from_mapping(tomllib.loads(text))

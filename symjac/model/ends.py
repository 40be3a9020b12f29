"""The two ends of a whole arm, chosen in one place for every result, printer and generated module.

A whole-arm result (forward kinematics, the report's pose, a Jacobian whose point is not given, generated code) runs
from the *world* frame when the robot has a base transform, else from frame {0}, to the *tool* frame when it has a
tool transform (a URDF's tip link beyond the last joint), else to the last joint frame {n}. Its default point is the
origin of that last frame, the end of the chain: ``"tool"``, or ``"flange"`` (the origin of {n}; ``"wrist"`` is the
same point under its older name). Forward kinematics, the Jacobian and generated code all take this one default.

Examples
--------
>>> from symjac import load_robot
>>> robot = load_robot("planar2r")
>>> first_frame(robot), last_frame(robot), end_point(robot)
(0, 2, 'flange')
"""

from __future__ import annotations

from typing import Literal, Protocol, cast

__all__ = ["end_point", "first_frame", "last_frame"]


class _Ends(Protocol):
    """What the choice reads of a robot: whether it has a base and a tool, and its number of joints."""

    base: object
    tool: object
    n_joints: int


def _model(robot: object) -> _Ends:
    """The robot itself, or the robot of a derived chain (anything with a ``robot`` attribute)."""
    return cast(_Ends, getattr(robot, "robot", robot))


def first_frame(robot: object) -> Literal["world"] | int:
    """The frame a whole-arm result starts in: ``"world"`` with a base transform, else ``0``."""
    return "world" if _model(robot).base is not None else 0


def last_frame(robot: object) -> Literal["tool"] | int:
    """The frame a whole-arm result ends at: ``"tool"`` with a tool transform, else ``n`` (the last joint frame)."""
    model = _model(robot)
    return "tool" if model.tool is not None else model.n_joints


def end_point(robot: object) -> Literal["tool", "flange"]:
    """The default point of a whole-arm result, the origin of :func:`last_frame`: the tool point, else the flange.

    The flange is the origin of frame {n} (``"wrist"`` names it too, for compatibility).
    """
    return "tool" if _model(robot).tool is not None else "flange"

r"""How large a robot file's lengths and angles may be: beyond these a number is surely a unit error.

A length larger than :data:`MAX_LENGTH` (1000 m: the largest industrial arms and gantries reach tens of metres) is
a value written in millimetres or micrometres in a file that speaks metres, or a typing slip; an angle larger than
:data:`MAX_ANGLE` (1000 rad, about 160 turns) is a value in millidegrees or arc seconds, or a length in an angle's
field. Beyond these bounds floats also lose the digits that matter: :math:`\sin(10^{9})` in double precision is known
to about 1e-7.

Degrees are never silent: in a file that speaks radians (no ``angle_unit = "deg"``) a constant angle (``alpha``, a
``theta`` offset, an ``rpy`` entry) or a revolute joint's limit larger than one turn,

.. math:: |\varphi| > 2\pi + 0.01 \text{ rad},

is refused (:data:`MAX_TURN`, :func:`turn_problem`): ``alpha = -90`` or ``limits = [-170, 170]`` are degrees
written without the unit, and no DH table needs more than a turn. The 0.01 lets a turn rounded up pass (``6.2832``).
A file in degrees keeps only the :data:`MAX_ANGLE` bound. A URDF is always in radians, so an ``rpy`` entry beyond
:data:`MAX_TURN` is refused there with a message that says so (:func:`urdf_turn_problem`); its limits may be
multi-turn (a wrist of +-400 degrees is +-6.98 rad), so they are bounded by :data:`MAX_URDF_LIMIT` (two turns and the
same rounding), which still refuses +-170.

Examples
--------
>>> size_problem(0.4318, angle=False) is None
True
>>> size_problem(1e6, angle=False)
'1e+06 m is larger than 1000 m in size: lengths are in metres (is it in millimetres?)'
>>> turn_problem(6.2832) is None
True
>>> turn_problem(-90)
'-90 rad is more than a turn (2*pi): is it in degrees? say angle_unit = "deg" at the top of the file'
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

__all__ = ["MAX_ANGLE", "MAX_LENGTH", "MAX_TURN", "MAX_URDF_LIMIT", "file_limits", "size_problem", "turn_problem",
           "urdf_turn_problem"]

MAX_LENGTH = 1000.0
"""Metres: the largest length (a DH ``a`` or ``d``, an ``xyz`` entry, a screw's ``v`` or ``point``) a file may give."""
MAX_ANGLE = 1000.0
"""Radians: the largest constant angle (``alpha``, ``theta``, an ``rpy`` entry) a file may give."""
MAX_TURN = 2 * math.pi + 0.01
"""Radians: the largest angle or revolute limit a file in radians may give (a turn, rounded up as 6.2832 passes)."""
MAX_URDF_LIMIT = 4 * math.pi + 0.01
"""Radians: the largest revolute limit a URDF may give (two turns: multi-turn wrists exist, +-170 does not)."""


def size_problem(value: float, *, angle: bool, turn: bool = False) -> str | None:
    """Why ``value`` (in metres, or radians when ``angle``) is too large to be meant, or None when it is not.

    With ``turn`` (an angle a file gives in radians) an angle beyond :data:`MAX_TURN` is refused too.
    """
    if angle and turn:
        return turn_problem(value)
    if angle:
        if abs(value) > MAX_ANGLE:
            return (f"{value:.6g} rad is larger than {MAX_ANGLE:.0f} rad in size: angles are in radians unless "
                    f"the file says angle_unit = \"deg\"")
        return None
    if abs(value) > MAX_LENGTH:
        return f"{value:.6g} m is larger than {MAX_LENGTH:.0f} m in size: lengths are in metres (is it in millimetres?)"
    return None


def turn_problem(value: float) -> str | None:
    """Why ``value``, an angle or revolute limit a robot file gives in radians, is surely in degrees, or None."""
    if abs(value) > MAX_TURN:
        return (f"{value:.6g} rad is more than a turn (2*pi): is it in degrees? say angle_unit = \"deg\" at the top "
                "of the file")
    return None


def urdf_turn_problem(value: float, *, limit: bool = False) -> str | None:
    """Why ``value``, a URDF ``rpy`` entry (or revolute ``limit``), is surely in degrees, or None (URDF is radians)."""
    bound, what = (MAX_URDF_LIMIT, "two turns (4*pi)") if limit else (MAX_TURN, "a turn (2*pi)")
    if abs(value) > bound:
        return (f"{value:.6g} rad is more than {what}: URDF angles are in radians (write degrees times pi/180, "
                f"e.g. {value:.6g} deg is {math.radians(value):.6g})")
    return None


def file_limits(raw: Any, value: Any, defaults: Mapping[Any, Any], fail: Any, *, turn: bool = False) -> tuple[Any, Any]:
    """A robot file's ``limits = [lower, upper]``: parsed by ``value``, finite with the defaults, ``lower < upper``.

    ``value(raw)`` parses one entry and ``fail(message)`` is the error to raise (naming the file, joint and field).

    With ``turn`` (a revolute joint in a file in radians) a limit beyond :data:`MAX_TURN` is refused as degrees.
    """
    if not isinstance(raw, Sequence) or isinstance(raw, str) or len(raw) != 2:
        raise fail("'limits' must be a list [lower, upper]")
    lower, upper = value(raw[0]), value(raw[1])
    low_expr, high_expr = lower.subs(defaults), upper.subs(defaults)
    if not (_is_finite(low_expr) and _is_finite(high_expr)):
        raise fail(f"'limits' must be finite with lower < upper, got [{low_expr}, {high_expr}]")
    low, high = float(low_expr), float(high_expr)
    if low >= high:
        raise fail(f"'limits' must be finite with lower < upper, got [{low}, {high}]")
    problem = next((p for p in map(turn_problem, (low, high)) if p is not None), None) if turn else None
    if problem is not None:
        raise fail(f"limit {problem}")
    return lower, upper


def _is_finite(number: Any) -> bool:
    try:
        return math.isfinite(float(number))
    except TypeError:  # complex infinity (1/L1 with L1 = 0) has no float
        return False

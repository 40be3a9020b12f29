r"""How large a robot file's lengths and angles may be: beyond these a number is surely a unit error.

A length larger than :data:`MAX_LENGTH` (1000 m: the largest industrial arms and gantries reach tens of metres) is
a value written in millimetres or micrometres in a file that speaks metres, or a typing slip; an angle larger than
:data:`MAX_ANGLE` (1000 rad, about 160 turns) is a value in millidegrees or arc seconds, or a length in an angle's
field. Below them a value is taken as written: 90 in an ``alpha`` field may be a degree meant (``angle_unit =
"deg"`` says so), but it is also a valid angle, so only the sizes no robot has are refused. Beyond these bounds
floats also lose the digits that matter: :math:`\sin(10^{9})` in double precision is known to about 1e-7.

Examples
--------
>>> size_problem(0.4318, angle=False) is None
True
>>> size_problem(1e6, angle=False)
'1e+06 m is larger than 1000 m in size: lengths are in metres (is it in millimetres?)'
"""

from __future__ import annotations

__all__ = ["MAX_ANGLE", "MAX_LENGTH", "size_problem"]

MAX_LENGTH = 1000.0
"""Metres: the largest length (a DH ``a`` or ``d``, an ``xyz`` entry, a screw's ``v`` or ``point``) a file may give."""
MAX_ANGLE = 1000.0
"""Radians: the largest constant angle (``alpha``, ``theta``, an ``rpy`` entry) a file may give."""


def size_problem(value: float, *, angle: bool) -> str | None:
    """Why ``value`` (in metres, or radians when ``angle``) is too large to be meant, or None when it is not."""
    if angle:
        if abs(value) > MAX_ANGLE:
            return (f"{value:.6g} rad is larger than {MAX_ANGLE:.0f} rad in size: angles are in radians unless "
                    f"the file says angle_unit = \"deg\"")
        return None
    if abs(value) > MAX_LENGTH:
        return f"{value:.6g} m is larger than {MAX_LENGTH:.0f} m in size: lengths are in metres (is it in millimetres?)"
    return None

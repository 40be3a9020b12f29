r"""What the closed-form executor does at a singular step: the value shown for a free angle, a rounding merge undone.

- **The value shown** (:func:`shown_value`): where a step's angle takes every value (the UR5 at ``theta5 = 0``:
  ``theta6`` is free), 0 stands for the continuum unless the next step has no solution there. When that next step
  is a rotation to a distance whose ``delta^2`` is ``A + B cos(t) + C sin(t)`` in the free angle ``t`` (the UR5's
  elbow: the point where axes 4 and 5 meet turns on a circle with ``theta6``), the value shown is the middle of the
  interval of ``t`` nearest 0 where ``delta`` is within the step's reach, so that its two solutions are apart.
- **Merged by rounding** (:func:`unmerged`): a rotation to a distance merges its two solutions when ``1 - |c|`` is
  rounding-sized (a half angle below 3.4e-7). Near a wrist singularity (``theta5 = 1e-7``) the distance itself is
  accurate and the half angle is not rounding: ``sin^2(half / 2) = (delta'^2 - (|u'| - |v'|)^2) / (4 |u'| |v'|)``
  (``cos^2`` with ``(|u'| + |v'|)^2 - delta'^2`` on the other side) gives the two angles without the cancellation in
  ``1 - c``; the executor takes them where the merged angle leads to no solution.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from symjac.analysis.inverse_kinematics.subproblems import AngleSolutions

__all__ = ["shown_value", "unmerged"]


def _lengths(a: dict[str, Any]) -> tuple[float, float, float]:
    """For a rotation to a distance: ``|u'|``, ``|v'|`` (across the axis) and ``(k.(u - v))^2``."""
    k = np.array(a["k"], dtype=float)
    r = np.zeros(3) if a.get("point_on_axis") is None else np.array(a["point_on_axis"], dtype=float)
    u, v = np.array(a["p"], dtype=float) - r, np.array(a["q"], dtype=float) - r
    ru, rv = (float(np.linalg.norm(x - k * float(k @ x))) for x in (u, v))
    return ru, rv, float(k @ (u - v)) ** 2


def shown_value(arguments_at: Callable[[float], dict[str, Any]], subproblem: str,
                call: Callable[..., AngleSolutions], tolerance: float) -> float:
    """The value a free angle ``t`` shows: 0, unless the next step has no solution there.

    The next step is ``subproblem``, run by ``call`` on ``arguments_at(t)``. When it is a rotation to a distance
    (the module docstring) the value is the middle of the interval nearest 0 where it has solutions; 0 when no ``t``
    reaches (the step then says why it fails).
    """
    if subproblem != "rotation_to_distance" or call(**arguments_at(0.0), tolerance=tolerance).solutions:
        return 0.0
    samples = [arguments_at(t) for t in (0.0, math.pi / 2, math.pi, -math.pi / 2)]
    d = [a["delta"] ** 2 for a in samples]
    moved = any(a[name] != samples[0][name] for a in samples for name in a if name != "delta")
    if moved or abs(d[0] + d[2] - d[1] - d[3]) > tolerance * max(1.0, *d):
        return 0.0  # not a circle's distance
    ru, rv, along = _lengths(samples[0])
    mean, b, c = (d[0] + d[2]) / 2, (d[0] - d[2]) / 2, (d[1] - d[3]) / 2
    amplitude, phase = math.hypot(b, c), math.atan2(c, b)  # delta^2 = mean + amplitude cos(t - phase)
    if amplitude <= tolerance * max(1.0, mean):
        return 0.0
    low = ((ru - rv) ** 2 + along - mean) / amplitude
    high = ((ru + rv) ** 2 + along - mean) / amplitude
    if low > 1.0 or high < -1.0:
        return 0.0
    inner, outer = math.acos(min(high, 1.0)), math.acos(max(low, -1.0))  # t - phase in +-[inner, outer]
    middles = [phase] if inner == 0.0 else [phase + math.pi] if outer == math.pi else \
        [phase + (inner + outer) / 2, phase - (inner + outer) / 2]
    return min((math.remainder(t, 2 * math.pi) for t in middles), key=abs)


def unmerged(arguments: dict[str, Any], merged: float) -> tuple[float, float] | None:
    """The two angles of a rotation to a distance whose one solution ``merged`` was merged by rounding.

    In the subproblem's order (``theta0 - half``, then ``theta0 + half``), from the lengths (the module docstring);
    None where they coincide in floating point too.
    """
    ru, rv, along = _lengths(arguments)
    if ru * rv == 0.0:
        return None
    across = max(arguments["delta"] ** 2 - along, 0.0)
    closest = across - (ru - rv) ** 2 <= (ru + rv) ** 2 - across  # c near +1: the angle between u' and v' small
    share = (across - (ru - rv) ** 2 if closest else (ru + rv) ** 2 - across) / (4.0 * ru * rv)
    gap = 2.0 * math.asin(math.sqrt(min(max(share, 0.0), 1.0)))
    if merged - gap == merged:
        return None
    return (merged - gap, merged + gap) if closest else (merged + gap, merged - gap)

r"""Singular solutions against the joint limits: inside, outside, or partly inside them.

A solution :math:`q_k = r` with constant :math:`r` (parameters at their defaults) is inside when :math:`r` (or, for a
revolute joint, :math:`r + 2\pi m` for some integer :math:`m`) lies within the limits of joint :math:`k`. A curve
(:math:`r` depends on other joints, or the left side is a sum of joints) is sampled: the other joints on a
deterministic grid within their own limits (:math:`[-\pi, \pi]` for a revolute joint without limits), the solved
joint computed, and the real values counted; all inside, none inside or some inside give ``inside``, ``outside``
or ``partly``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from enum import StrEnum

import numpy as np
import sympy as sp

from symjac.analysis.singularity.solve import Solution
from symjac.kinematics.chain import Chain, as_chain
from symjac.model.robot import Joint, Robot

__all__ = ["LimitStatus", "limit_status", "within_limits"]

_SAMPLES = 257  # points per other joint on the grid (odd: the middle of each range is on it)
_MAX_POINTS = 20_000  # grid points in all, whatever the number of other joints
_TOLERANCE = 1e-9


class LimitStatus(StrEnum):
    """Where a singular solution lies relative to the joint limits."""

    INSIDE = "inside"
    OUTSIDE = "outside"
    PARTLY = "partly"
    UNLIMITED = "unlimited"
    """No joint of the solution has limits (nothing to check)."""
    UNKNOWN = "unknown"
    """Not solved in closed form, or no real value was found (the limits could not be checked)."""


def limit_status(robot: Robot | Chain, solution: Solution) -> LimitStatus:
    """Whether the singular set ``solution`` lies inside the joint limits (parameters at their defaults).

    Examples
    --------
    >>> from symjac import load_robot
    >>> d3 = sp.Symbol("d3", real=True)
    >>> str(limit_status(load_robot("stanford"), Solution(d3, sp.S.Zero)))  # d3 is limited to [0.3, 1.3]
    'outside'
    """
    model = as_chain(robot).robot
    if model.coupling is not None:  # a coupled joint's limits bound a combination of coordinates: not judged here
        return LimitStatus.UNLIMITED if all(j.limits is None for j in model.joints) else LimitStatus.UNKNOWN
    variables = list(model.q)
    joints = {joint.variable: joint for joint in model.joints}
    involved = [v for v in variables if solution.lhs.has(v) or solution.rhs.has(v)]
    solved = [v for v in involved if solution.lhs.has(v) and not solution.rhs.has(v)]
    if not any(joints[v].limits is not None for v in involved):
        return LimitStatus.UNLIMITED
    if not solved or solution.lhs.free_symbols - set(variables) - set(model.parameter_symbols):
        return LimitStatus.UNKNOWN
    pick = max(solved, key=variables.index)
    others = [v for v in involved if v != pick]
    lhs_rest = sp.expand(solution.lhs - pick)
    if lhs_rest.has(pick) or sp.expand(solution.lhs).coeff(pick) != 1:
        return LimitStatus.UNKNOWN  # the solved joint does not appear alone with coefficient one
    value = (solution.rhs - lhs_rest).xreplace(model.defaults)
    grid = _grid([_range(joints[v], model) for v in others])
    try:
        function = sp.lambdify(others, value, modules="numpy")
        with np.errstate(all="ignore"):
            values = np.broadcast_to(np.asarray(function(*grid), dtype=complex), grid[0].shape if grid else (1,))
    except (TypeError, ValueError, ZeroDivisionError):
        return LimitStatus.UNKNOWN
    real = values[np.isfinite(values) & (np.abs(values.imag) <= _TOLERANCE)].real
    if real.size == 0:
        return LimitStatus.UNKNOWN
    inside = _within(real, joints[pick], model)
    if inside.all():
        return LimitStatus.INSIDE
    return LimitStatus.PARTLY if inside.any() else LimitStatus.OUTSIDE


def within_limits(robot: Robot, q: Sequence[float]) -> bool:
    """Whether every coordinate of ``q`` lies within its joint's limits (a revolute angle modulo 2 pi)."""
    if robot.coupling is not None:
        return True  # a coupled joint's limits bound a combination of coordinates: not judged here
    return all(bool(_within(np.array([value]), joint, robot)[0]) for joint, value in zip(robot.joints, q, strict=True))


def _range(joint: Joint, robot: Robot) -> tuple[float, float]:
    if joint.limits is not None:
        low, high = (float(sp.sympify(v).xreplace(robot.defaults)) for v in joint.limits)
        return low, high
    return (-math.pi, math.pi) if joint.is_revolute else (-1.0, 1.0)


def _grid(ranges: list[tuple[float, float]]) -> list[np.ndarray]:
    """A grid over the ranges (coarser with more joints, at most ``_MAX_POINTS`` points), flattened per joint."""
    if not ranges:
        return []
    count = max(3, min(_SAMPLES, int(_MAX_POINTS ** (1 / len(ranges)))))
    axes = [np.linspace(low, high, count) for low, high in ranges]
    return [axis.ravel() for axis in np.meshgrid(*axes, indexing="ij")]


def _within(values: np.ndarray, joint: Joint, robot: Robot) -> np.ndarray:
    """Which values lie within the joint's limits (a revolute joint's angle modulo 2 pi)."""
    if joint.limits is None:
        return np.ones(values.shape, dtype=bool)
    low, high = _range(joint, robot)
    if joint.is_revolute:
        values = low + np.mod(values - low + _TOLERANCE, 2 * math.pi) - _TOLERANCE
    return (values >= low - _TOLERANCE) & (values <= high + _TOLERANCE)

"""What a sweep samples: designs (a grid over robot parameters) and configurations (joint values over the limits).

Joint samples are drawn chunk by chunk, each chunk a pure function of its index, so that the same sweep gives the
same samples however its chunks are scheduled: a scrambled Sobol sequence (SciPy's :class:`scipy.stats.qmc.Sobol`,
fast-forwarded to the chunk's first point) or a regular grid (``m`` points per joint, ``m ** n`` in all).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
import sympy as sp

from symjac.errors import ArgumentError
from symjac.model.robot import JointType, Robot

__all__ = ["JointSampler", "Sampling", "joint_ranges", "parameter_grid"]

Sampling = Literal["sobol", "grid"]


def parameter_grid(robot: Robot, params: Mapping[str, tuple[float, float, int] | Sequence[float]]
                   ) -> dict[str, np.ndarray]:
    """Each swept parameter's values: ``(low, high, count)`` evenly spaced (ends included), or the values given.

    Examples
    --------
    >>> from symjac import load_robot
    >>> parameter_grid(load_robot("planar2r"), {"L1": (0.2, 0.4, 3)})["L1"].tolist()
    [0.2, 0.30000000000000004, 0.4]
    """
    known = {parameter.name for parameter in robot.parameters}
    grid: dict[str, np.ndarray] = {}
    for name, spec in params.items():
        if name not in known:
            raise ArgumentError(f"{robot.name} has no parameter {name!r}; its parameters are "
                                f"{', '.join(sorted(known)) or 'none'}")
        if isinstance(spec, tuple) and len(spec) == 3 and isinstance(spec[2], int) and not isinstance(spec[2], bool):
            low, high, count = spec
            if count < 1 or not (math.isfinite(low) and math.isfinite(high)) or low > high:
                raise ArgumentError(f"{name}: the range {low}:{high}:{count} is empty or not finite (low <= high, "
                                    "count >= 1)")
            values = np.linspace(float(low), float(high), int(count))
        else:
            try:
                values = np.asarray(spec, dtype=float).reshape(-1)
            except (TypeError, ValueError):
                raise ArgumentError(f"{name}: give (low, high, count) or a list of values, got {spec!r}") from None
            if values.size == 0 or not np.all(np.isfinite(values)):
                raise ArgumentError(f"{name}: the values must be finite and at least one, got {spec!r}")
        grid[name] = values
    return grid


def joint_ranges(robot: Robot, ranges: Mapping[str, tuple[float, float]] | None = None) -> np.ndarray:
    """Per coordinate, the interval sampled: ``ranges[name]``, else the joint's limits, else (-pi, pi) for an angle.

    A prismatic coordinate without limits needs a range (there is no natural one).
    """
    given = dict(ranges or {})
    names = [str(c) for c in robot.q]
    unknown = set(given) - set(names)
    if unknown:
        raise ArgumentError(f"no coordinate {sorted(unknown)[0]!r} in {robot.name}: its coordinates are "
                            f"{', '.join(names)}")
    limits = {joint.variable: joint.limits for joint in robot.joints}
    result = np.empty((robot.n_coordinates, 2))
    for k, (name, kind) in enumerate(zip(names, robot.coordinate_types, strict=True)):
        bounds = limits.get(robot.q[k])
        if name in given:
            low, high = (float(v) for v in given[name])
        elif bounds is not None:
            low, high = (float(sp.sympify(b).xreplace(robot.defaults)) for b in bounds)
        elif kind is JointType.REVOLUTE:
            low, high = -math.pi, math.pi
        else:
            raise ArgumentError(f"{name} is a prismatic coordinate without limits: give its range")
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise ArgumentError(f"{name}: the range ({low}, {high}) is empty or not finite")
        result[k] = low, high
    return result


@dataclass(frozen=True)
class JointSampler:
    """``count`` configurations over ``ranges`` (rows low, high), drawn ``chunk`` at a time by :meth:`chunk`."""

    ranges: np.ndarray
    count: int
    method: Sampling = "sobol"
    seed: int = 0

    def __post_init__(self) -> None:
        if self.method not in ("sobol", "grid"):
            raise ArgumentError(f"unknown sampling {self.method!r}; choose sobol or grid")
        if not isinstance(self.count, int) or isinstance(self.count, bool) or self.count < 1:
            raise ArgumentError(f"samples must be a positive integer, got {self.count!r}")

    @property
    def per_axis(self) -> int:
        """Grid points per coordinate: the smallest m with m ** n >= count."""
        n = len(self.ranges)
        m = max(1, round(self.count ** (1 / n)))
        while m**n < self.count:
            m += 1
        return m

    @property
    def total(self) -> int:
        """How many configurations are drawn: ``count`` (Sobol), or ``per_axis ** n`` (grid)."""
        return self.count if self.method == "sobol" else self.per_axis ** len(self.ranges)

    def chunk(self, start: int, stop: int) -> np.ndarray:
        """Configurations ``start`` to ``stop - 1`` of the sequence, as rows."""
        low, high = self.ranges[:, 0], self.ranges[:, 1]
        if self.method == "grid":
            m = self.per_axis
            index = np.stack(np.unravel_index(np.arange(start, stop), (m,) * len(self.ranges)), axis=1)
            unit = (index + 0.5) / m  # cell centres: no point on a range's end counted twice for a full turn
        else:
            from scipy.stats import qmc

            engine = qmc.Sobol(d=len(self.ranges), scramble=True, seed=self.seed)
            with warnings.catch_warnings():  # chunks need not be powers of 2: the whole sequence is what counts
                warnings.simplefilter("ignore", UserWarning)
                if start:
                    engine.fast_forward(start)
                unit = engine.random(stop - start)
        return low + unit * (high - low)

"""What a sweep samples: designs (a grid over robot parameters) and configurations (joint values over the limits).

Joint samples are drawn chunk by chunk, each chunk a pure function of its place in the sequence, so that the same
sweep gives the same samples however it is chunked and scheduled: scrambled Sobol points (SciPy's
:class:`scipy.stats.qmc.Sobol`, in independently scrambled blocks of :data:`SOBOL_BLOCK`) or a regular grid of cell
centres (``m`` per coordinate, ``m ** n`` in all: ``samples`` is rounded up to the next such number).
"""

from __future__ import annotations

import functools
import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
import sympy as sp

from symjac.errors import ArgumentError
from symjac.model.robot import JointType, Robot

__all__ = ["MOST_VALUES", "SOBOL_BLOCK", "JointSampler", "Sampling", "joint_ranges", "parameter_grid"]

Sampling = Literal["sobol", "grid"]

MOST_VALUES = 10_000
"""The most values one parameter may take in a sweep."""

SOBOL_BLOCK = 1 << 16
"""Sobol points come in blocks of this many, each block scrambled on its own (seeded by the sweep's seed and the
block's index): randomized quasi-Monte Carlo with independent replicates. A chunk draws its points from the blocks
it overlaps, so neither the chunk size nor the scheduling changes the samples, and no chunk pays for skipping the
points before it."""


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
        values = _range(name, spec) if isinstance(spec, tuple) else _values(name, spec)
        if len(np.unique(values)) != len(values):
            raise ArgumentError(f"{name}: the values repeat ({values.tolist()}): each design once")
        grid[name] = values
    return grid


def _number(value: object, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(float(value)):
        raise ArgumentError(f"{what} must be a finite number, got {value!r}")
    return float(value)


def _range(name: str, spec: tuple[object, ...]) -> np.ndarray:
    """``(low, high, count)``: count evenly spaced values, ends included."""
    if len(spec) != 3:
        raise ArgumentError(f"{name}: a range is (low, high, count), got {spec!r} (a list gives the values)")
    low, high = _number(spec[0], f"{name}'s low end"), _number(spec[1], f"{name}'s high end")
    count = spec[2]
    if isinstance(count, bool) or not isinstance(count, numbers.Integral) or not 1 <= int(count) <= MOST_VALUES:
        raise ArgumentError(f"{name}: the count of {spec!r} must be a whole number from 1 to {MOST_VALUES}")
    if low > high or (low == high and int(count) > 1):
        raise ArgumentError(f"{name}: the range {low}:{high}:{count} is empty (low < high, or one value)")
    return np.linspace(low, high, int(count))


def _values(name: str, spec: object) -> np.ndarray:
    if isinstance(spec, str | bytes) or not isinstance(spec, Sequence | np.ndarray):
        raise ArgumentError(f"{name}: give (low, high, count) or a list of values, got {spec!r}")
    values = np.array([_number(v, f"a value of {name}") for v in spec], dtype=float)
    if values.size == 0 or values.size > MOST_VALUES:
        raise ArgumentError(f"{name}: give from 1 to {MOST_VALUES} values, got {values.size}")
    return values


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
            pair = given[name]
            if isinstance(pair, str | bytes) or not isinstance(pair, Sequence) or len(pair) != 2:
                raise ArgumentError(f"the range of {name} must be (low, high), got {pair!r}")
            low, high = (_number(v, f"an end of {name}'s range") for v in pair)
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
        if isinstance(self.count, bool) or not isinstance(self.count, numbers.Integral) or self.count < 1:
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
            first, last = start // SOBOL_BLOCK, (stop - 1) // SOBOL_BLOCK
            pieces = []
            for block in range(first, last + 1):
                points = _sobol_block(len(self.ranges), self.seed, block)
                offset = block * SOBOL_BLOCK
                pieces.append(points[max(start, offset) - offset:min(stop, offset + SOBOL_BLOCK) - offset])
            unit = np.concatenate(pieces)
        return low + unit * (high - low)


@functools.lru_cache(maxsize=4)
def _sobol_block(dimension: int, seed: int, block: int) -> np.ndarray:
    """Block ``block`` of the sweep's Sobol points: 2**16 scrambled points in the unit cube (read-only)."""
    from scipy.stats import qmc

    engine = qmc.Sobol(d=dimension, scramble=True, seed=np.random.default_rng([seed, block]))
    points = engine.random_base2(16)
    points.flags.writeable = False
    return points

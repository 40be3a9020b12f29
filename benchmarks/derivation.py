"""Derivation benchmark: ``python benchmarks/derivation.py [ROBOT ...]``.

For each robot (default: the whole catalog) it derives the simplified Jacobian from a cold start (a fresh chain, no
cached transforms) in frame {0}, then in every other frame, and prints the wall time and the operation count
(``sympy.count_ops``) of frame {0} and of the frame with the fewest operations, and the time to derive every
simplified step of the velocity and the force propagation (what ``symjac jacobian --steps`` prints). It measures;
it asserts nothing, so it never flakes. ``--snake N`` adds an N-joint snake arm (8 and 10 by default). The last
column is the time to the full singularity report (:func:`symjac.analysis.singularity.determinant.singularities`:
determinant, factors solved, classified and explained, or the minors of a redundant arm) from a cold cache.
Targets on a 2-core machine: PUMA 560 <= 1 s, UR5 <= 2 s, Panda <= 10 s and <= 1500 operations.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from symjac.analysis.singularity.singularities import singularities
from symjac.errors import SymjacError
from symjac.kinematics.chain import clear_caches
from symjac.kinematics.jacobian import jacobian
from symjac.kinematics.propagation import force_propagation, velocity_propagation
from symjac.model.io import catalog, load_robot
from symjac.model.robot import Robot
from symjac.model.robot_file import robot_from_mapping

__all__ = ["DerivationTiming", "main", "snake", "time_derivation", "time_singularities"]


@dataclass(frozen=True)
class DerivationTiming:
    """Cold-start derivation time and size of one robot's simplified Jacobian."""

    robot: str
    n_joints: int
    seconds_frame_0: float
    ops_frame_0: int
    best_frame: int
    seconds_best: float
    ops_best: int
    seconds_steps: float
    seconds_singularities: float | None


def snake(n: int) -> Robot:
    """An n-joint snake: revolute modules of length L whose axes alternate by +-90 degrees (standard DH)."""
    joints = [{"type": "revolute", "alpha": "pi/2" if i % 2 else "-pi/2", "a": "L"} for i in range(n)]
    return robot_from_mapping({"name": f"snake{n}", "convention": "standard", "parameters": {"L": 0.1},
                               "joints": joints})


def time_derivation(robot: Robot, singular: bool = True) -> DerivationTiming:
    """Derive the robot's Jacobian in every frame from a cold cache; frame {0} first, as a user would."""
    clear_caches()
    start = time.perf_counter()
    J_0 = jacobian(robot, frame=0)
    seconds_0 = time.perf_counter() - start
    ops_0 = int(sp.count_ops(J_0))
    best = (0, seconds_0, ops_0)
    for frame in range(1, robot.n_joints + 1):
        start = time.perf_counter()
        J_k = jacobian(robot, frame=frame)
        seconds = time.perf_counter() - start
        ops = int(sp.count_ops(J_k))
        if ops < best[2]:
            best = (frame, seconds, ops)
    start = time.perf_counter()
    velocity_propagation(robot)
    force_propagation(robot)
    seconds_steps = time.perf_counter() - start
    return DerivationTiming(robot.name, robot.n_joints, seconds_0, ops_0, *best, seconds_steps,
                            time_singularities(robot) if singular else None)


def time_singularities(robot: Robot) -> float | None:
    """Seconds to the full singularity report from a cold cache (``None`` if the arm has no square task rows)."""
    clear_caches()
    start = time.perf_counter()
    try:
        singularities(robot)
    except SymjacError:
        return None
    return time.perf_counter() - start


def coupling_overhead(robot: Robot, repeats: int = 3) -> tuple[float, float]:
    """Best-of-``repeats`` seconds to derive ``robot`` (every frame and the steps) with and without its coupling."""

    def seconds(arm: Robot) -> float:
        clear_caches()
        start = time.perf_counter()
        for frame in range(arm.n_joints + 1):
            jacobian(arm, frame=frame)
        velocity_propagation(arm)
        force_propagation(arm)
        return time.perf_counter() - start

    coupled = min(seconds(robot) for _ in range(repeats))
    uncoupled = min(seconds(robot.uncoupled) for _ in range(repeats))
    return coupled, uncoupled


def main(argv: Sequence[str] | None = None) -> int:
    """Print one line per robot: derivation time and operation count, frame {0} and best frame."""
    parser = argparse.ArgumentParser(prog="python benchmarks/derivation.py", description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", help="catalog names or robot files (default: the whole catalog)")
    parser.add_argument("--snake", type=int, action="append", default=[], metavar="N",
                        help="also time an N-joint snake arm (repeatable; default: 8 and 10 with the catalog)")
    args = parser.parse_args(argv)
    robots = [load_robot(name) for name in args.robots or catalog()]
    robots += [snake(n) for n in args.snake or ([] if args.robots else [8, 10])]
    print(f"{'robot':<14}{'n':>3}  {'frame 0: s':>11}{'ops':>7}  {'best frame':>10}{'s':>8}{'ops':>7}"
          f"  {'steps: s':>9}  {'singular: s':>11}")
    for robot in robots:
        t = time_derivation(robot, singular=robot.n_joints <= 7)
        singular = "-" if t.seconds_singularities is None else f"{t.seconds_singularities:.3f}"
        print(f"{t.robot:<14}{t.n_joints:>3}  {t.seconds_frame_0:>11.3f}{t.ops_frame_0:>7}  "
              f"{t.best_frame:>10}{t.seconds_best:>8.3f}{t.ops_best:>7}  {t.seconds_steps:>9.3f}  {singular:>11}",
              flush=True)
    for robot in (r for r in robots if r.coupling is not None):  # the coupling should add at most 20%
        coupled, uncoupled = coupling_overhead(robot)
        print(f"{robot.name}: coupled {coupled:.3f} s, the same chain uncoupled {uncoupled:.3f} s "
              f"({100 * (coupled / uncoupled - 1):+.0f}%)", flush=True)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

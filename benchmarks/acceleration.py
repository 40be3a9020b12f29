r"""Acceleration-level benchmark: ``python benchmarks/acceleration.py [ROBOT ...]``.

For each robot (default: the whole catalog, then snake arms of 6, 8 and 10 joints to show how the cost grows) it
derives, each from a cold start (:func:`symjac.kinematics.chain.clear_caches`, so the Jacobian is derived again too),
the simplified kinematic Hessian in frame {0}, the time derivative of the Jacobian and the bias acceleration
:math:`\dot J\dot q`, and prints wall times and operation counts (``sympy.count_ops``). The last column fits the
growth exponent p of time ~ n^p over the snakes. It measures and asserts nothing, so it never flakes.
Targets on this 2-core machine (issue 16): PUMA 560 Hessian <= 2 s, Panda Hessian <= 10 s.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import sympy as sp

sys.path.insert(0, str(Path(__file__).resolve().parent))  # the snake arm of the derivation benchmark

from derivation import snake

from symjac.kinematics.acceleration import bias_acceleration, hessian, jacobian_derivative
from symjac.kinematics.chain import clear_caches
from symjac.model.io import catalog, load_robot
from symjac.model.robot import Robot

__all__ = ["cold", "main"]


def cold(derive: Callable[[Robot], object], robot: Robot) -> tuple[float, int]:
    """Seconds and operation count of ``derive(robot)`` from an empty cache."""
    clear_caches()
    start = time.perf_counter()
    result = derive(robot)
    seconds = time.perf_counter() - start
    return seconds, int(sum(sp.count_ops(entry) for entry in sp.flatten(result)))


def main(argv: Sequence[str] | None = None) -> int:
    """Print one line per robot: Hessian, dJ/dt and bias acceleration, cold time and operation count."""
    parser = argparse.ArgumentParser(prog="python benchmarks/acceleration.py", description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", help="catalog names or robot files (default: the whole catalog)")
    parser.add_argument("--snake", type=int, action="append", default=[], metavar="N",
                        help="also time an N-joint snake arm (repeatable; default 6, 8 and 10 with the catalog)")
    args = parser.parse_args(argv)
    robots = [load_robot(name) for name in args.robots or catalog()]
    snakes = args.snake or ([] if args.robots else [6, 8, 10])
    robots += [snake(n) for n in snakes]
    print(f"{'robot':<14}{'n':>3}  {'hessian: s':>11}{'ops':>7}  {'dJ/dt: s':>9}{'ops':>7}  {'bias: s':>8}{'ops':>7}")
    growth: list[tuple[int, float]] = []
    for robot in robots:
        h = cold(hessian, robot)
        d = cold(jacobian_derivative, robot)
        b = cold(bias_acceleration, robot)
        if robot.name.startswith("snake"):
            growth.append((robot.n_joints, h[0]))
        print(f"{robot.name:<14}{robot.n_joints:>3}  {h[0]:>11.3f}{h[1]:>7}  {d[0]:>9.3f}{d[1]:>7}  "
              f"{b[0]:>8.3f}{b[1]:>7}", flush=True)
    if len(growth) >= 2:
        (n0, t0), (n1, t1) = growth[0], growth[-1]
        print(f"snake Hessian time grows like n^{math.log(t1 / t0) / math.log(n1 / n0):.1f} from n={n0} to n={n1}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

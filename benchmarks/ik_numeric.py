r"""Numeric inverse-kinematics benchmark: ``python benchmarks/ik_numeric.py [ROBOT ...] [-n POSES]``.

For each robot (default: the Panda, the iiwa 7 and the PUMA 560) it draws ``POSES`` configurations uniformly within
the joint limits (seeded, so every run sees the same poses), takes their tool poses from the compiled forward
kinematics (:func:`symjac.codegen.numeric_model.numeric_model`) and solves them with
:func:`symjac.analysis.inverse_kinematics.numeric.solve_numeric` twice: from one random seed only (``restarts=1``,
no further starts: the issue's "success from one random seed") and with the defaults (8 seeds, more until one
converges, all distinct solutions kept). It prints the success rate (every solution checked against the pose to
1e-9), mean iterations of the converged starts, mean distinct solutions and wall time per solve. It asserts
nothing, so it never flakes.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from symjac.analysis.inverse_kinematics import seed_bounds, solve_numeric
from symjac.codegen.numeric_model import numeric_model
from symjac.model.io import load_robot


def main() -> None:
    """Solve the poses of each robot in both modes and print one row per robot and mode."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["panda", "iiwa7", "puma560"])
    parser.add_argument("-n", "--poses", type=int, default=500)
    arguments = parser.parse_args()
    print(f"{'robot':10} {'mode':12} {'success':>9} {'iterations':>10} {'solutions':>9} {'ms/solve':>9}")
    for name in arguments.robots:
        robot = load_robot(name)
        model = numeric_model(robot)
        lower, upper = seed_bounds(robot)
        generator = np.random.default_rng(2026)
        poses = [np.asarray(model.fk(generator.uniform(lower, upper)), dtype=float) for _ in range(arguments.poses)]
        for mode, restarts, until_found in (("one seed", 1, 1), ("defaults", 8, 40)):
            solved, iterations, counts = 0, [], []
            start = time.perf_counter()
            results = [solve_numeric(robot, pose, model, rng=k, restarts=restarts,
                                     until_found=until_found) for k, pose in enumerate(poses)]
            elapsed = time.perf_counter() - start
            for pose, solutions in zip(poses, results, strict=True):
                exact = all(np.abs(np.asarray(model.fk(s.q)) - pose).max() < 1e-9 for s in solutions)
                solved += bool(solutions) and exact
                iterations += [s.iterations for s in solutions]
                counts.append(len(solutions))
            print(f"{name:10} {mode:12} {100 * solved / len(poses):8.1f}% {np.mean(iterations or [0]):10.1f} "
                  f"{np.mean(counts):9.2f} {1e3 * elapsed / len(poses):9.2f}")


if __name__ == "__main__":
    main()

"""How fast the arm is drawn: ``python benchmarks/drawing.py``.

Each row is one fresh Python process (cold: nothing cached) that has imported symjac and matplotlib and loaded the
robot, then times

* ``draw``: one drawing (``symjac.draw``: the frames evaluated, every artist made) written as a PNG, what
  ``symjac draw ROBOT -o arm.png`` costs after its imports (the issue's goal: 0.5 s or less for a 7-joint arm);
* ``update``: one slider step, ``ArmDrawing.update`` to a new configuration with the velocity ellipsoid, and the
  figure drawn again as a PNG, as notebook 09 does (goal: 100 ms or less); the median of 20 random steps;
* ``pose``: ``arm_pose`` alone (the numbers drawn), median of 200 calls, to show where the time goes.

Growth with the number of joints: ``snakeN`` is the growth benchmark's N-joint snake (``benchmarks/growth.py``).
It asserts nothing.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

_PROGRAM = """
import io, json, sys, time
import numpy as np
import matplotlib
matplotlib.use("Agg")
from matplotlib.figure import Figure
from symjac import ArmDrawing, arm_pose, draw, load_robot
from symjac.drawing.animation import figure_bytes

name = sys.argv[1]
if name.startswith("snake"):  # the growth benchmark's snake: N joints, axes alternating by +-90 degrees
    sys.path.insert(0, sys.argv[2])
    from growth import chain_of_family
    robot = chain_of_family("snake", int(name[5:]))
else:
    robot = load_robot(name)
rng = np.random.default_rng(0)
q = rng.uniform(-1, 1, robot.n_coordinates)
start = time.perf_counter()
figure_bytes(draw(robot, q), ".png")
first = time.perf_counter() - start
figure = Figure(figsize=(5.2, 5.2))
drawing = ArmDrawing(figure.add_subplot(projection="3d"), robot, ellipsoids=("velocity",))
drawing.update(q)
figure.savefig(io.BytesIO(), format="png", dpi=90)
steps = []
for _ in range(20):
    start = time.perf_counter()
    drawing.update(rng.uniform(-1, 1, robot.n_coordinates))
    figure.savefig(io.BytesIO(), format="png", dpi=90)
    steps.append(time.perf_counter() - start)
poses = []
for _ in range(200):
    values = rng.uniform(-1, 1, robot.n_coordinates)
    start = time.perf_counter()
    arm_pose(robot, values)
    poses.append(time.perf_counter() - start)
print(json.dumps([first, float(np.median(steps)), float(np.median(poses))]))
"""


def measure(robot: str) -> tuple[float, float, float]:
    """Seconds: one cold drawing with its PNG, one slider step, one pose (best process of three)."""
    here = str(Path(__file__).resolve().parent)
    runs = [json.loads(subprocess.run([sys.executable, "-c", _PROGRAM, robot, here], capture_output=True, text=True,
                                      check=True).stdout) for _ in range(3)]
    return min(r[0] for r in runs), min(r[1] for r in runs), min(r[2] for r in runs)


def main(robots: list[str]) -> None:
    """Print one table row per robot."""
    from symjac import load_robot

    print("| robot | joints | draw + PNG, s | slider step, ms | pose, us |")
    print("|---|---|---|---|---|")
    for name in robots:
        first, step, pose = measure(name)
        joints = name[5:] if name.startswith("snake") else load_robot(name).n_joints
        print(f"| {name} | {joints} | {first:.2f} | {step * 1e3:.0f} | {pose * 1e6:.0f} |",
              flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or ["planar3r", "puma560", "panda", "panda.urdf", "snake10", "snake20"])

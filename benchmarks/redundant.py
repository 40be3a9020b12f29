"""How fast a redundant arm's singularities are analysed: ``python benchmarks/redundant.py``.

Each row is one fresh Python process that has imported symjac and loaded the robot, then times
``singularities(robot)``: the seven square minors factored in final form (``minors``), then the singular sets found,
solved and explained (``sets``), and the whole call (``total``; the issue's goals: the KUKA iiwa 7 in 3 s or less,
the Panda in 10 s or less). ``command`` is ``symjac singularities ROBOT --format json`` as a user runs it, process
start and imports included. ``before`` is the same call on the previous release's route (a fraction-free
elimination over the polynomial ring, factored as it stood), measured once and kept here for comparison.
It asserts nothing.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time

ROBOTS = ("iiwa7", "panda")
BEFORE = {"iiwa7": 3.2, "panda": 26.1}  # s, the minors alone on the previous route (same machine)

_PROGRAM = """
import json, sys, time
from symjac import load_robot
from symjac.analysis.singularity import singularities
from symjac.analysis.singularity.determinant import determinant
from symjac.kinematics.chain import Chain

robot = load_robot(sys.argv[1])
chain = Chain(robot)
start = time.perf_counter()
for k in range(robot.n_coordinates):  # kept in the chain: singularities() below finds them there
    determinant(chain, columns=[c for c in range(robot.n_coordinates) if c != k])
middle = time.perf_counter()
report = singularities(chain)
end = time.perf_counter()
print(json.dumps([middle - start, end - middle, end - start, len(report.sets)]))
"""


def main() -> None:
    """Time every robot in its own process and print one table."""
    print(f"{'robot':8} {'minors (s)':>10} {'sets (s)':>9} {'total (s)':>9} {'sets':>5} {'command (s)':>11} "
          f"{'before (s)':>10}")
    for name in ROBOTS:
        output = subprocess.run([sys.executable, "-c", _PROGRAM, name], check=True, capture_output=True, text=True)
        minors, sets, total, count = json.loads(output.stdout)
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "symjac", "singularities", name, "--format", "json"], check=True,
                       capture_output=True)
        command = time.perf_counter() - start
        print(f"{name:8} {minors:10.2f} {sets:9.2f} {total:9.2f} {count:5d} {command:11.2f} {BEFORE[name]:10.1f}")


if __name__ == "__main__":
    main()

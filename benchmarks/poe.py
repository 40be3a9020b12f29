"""Space and body Jacobians of robots described by a product of exponentials: ``python benchmarks/poe.py``.

Each figure is one fresh Python process (cold: nothing cached), loading a PoE robot file and deriving its simplified
space Jacobian, then its body Jacobian; best of three. The robots: the UR5 of the catalog (``ur5_poe``, Modern
Robotics' dimensions) and the 7-joint Panda written as screws (``symjac convert panda --to poe``). The issue's goals:
the UR5 space Jacobian in 1 s or less, a 7-joint PoE arm in 2 s or less. It asserts nothing.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

_PROGRAM = """
import json, sys, time
from symjac import body_jacobian, load_robot, space_jacobian
robot = load_robot(sys.argv[1])
start = time.perf_counter(); space_jacobian(robot); space = time.perf_counter() - start
start = time.perf_counter(); body_jacobian(robot); body = time.perf_counter() - start
print(json.dumps([space, body]))
"""


def cold(robot: str) -> tuple[float, float]:
    """Best space and body Jacobian seconds over three fresh processes."""
    runs = [json.loads(subprocess.run([sys.executable, "-c", _PROGRAM, robot], capture_output=True, text=True,
                                      check=True).stdout) for _ in range(3)]
    return min(r[0] for r in runs), min(r[1] for r in runs)


def main() -> int:
    """Print the table."""
    from symjac import load_robot, robot_to_toml
    from symjac.kinematics.convert import convert

    with tempfile.TemporaryDirectory() as folder:
        panda = Path(folder) / "panda_poe.toml"
        panda.write_text(robot_to_toml(convert(load_robot("panda"), "poe")))
        print("| robot | joints | space Jacobian, s | body Jacobian, s | goal |\n|---|---|---|---|---|")
        for label, robot, joints, goal in (("UR5 (ur5_poe)", "ur5_poe", 6, "1 s"),
                                           ("Panda as screws", str(panda), 7, "2 s")):
            space, body = cold(robot)
            print(f"| {label} | {joints} | {space:.2f} | {body:.2f} | {goal} |", flush=True)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

r"""Dynamics derivation benchmark: ``python benchmarks/dynamics.py [ROBOT ...] [--planar N ...] [--limit S]``.

How long symjac takes to derive the equations of motion, cold (each point in a fresh Python process: no SymPy cache,
no derived chain), with ten symbolic inertial parameters per link (``m{i}``, ``cx{i}`` .. ``Izz{i}``): the gravity
torques g(q), the mass matrix M(q) from the link Jacobians and by Newton-Euler, the Coriolis matrix C(q, qd) from the
Christoffel symbols, and the Newton-Euler torques, laid out (``tau``) and raw (``tau raw``, ``simplify=False``: what
code would start from). ``--planar`` adds planar N-R arms (gravity in their plane) and ``--prefix ROBOT --joints 3 4
...`` the arms made of a catalog robot's first joints (``iiwa7:4``), for the growth with the joints; the last column
is the total of g, M, C and tau (the four results the issue asks of a 7-joint arm). A point past ``--limit``
seconds is stopped and shown as such. It measures and asserts nothing, so it never flakes.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time

__all__ = ["PARTS", "main", "measure"]

PARTS = ("g", "M", "M by Newton-Euler", "C", "tau", "tau raw")

_CHILD = r"""
import json, sys, time
import sympy as sp
from symjac import load_robot, robot_from_mapping
from symjac.analysis.dynamics import (Gravity, coriolis_matrix, gravity_torques, mass_matrix, newton_euler,
                                      newton_euler_mass_matrix)
from symjac.model.inertial_parameters import with_symbolic_inertials

name, part = sys.argv[1], sys.argv[2]
if name.startswith("planar-"):  # planar-3R: a generated arm, not the catalog's planar3r
    n = int(name[len("planar-"):-1])
    robot = robot_from_mapping({"name": "planar", "convention": "standard", "parameters": {"L": 0.3},
                                "joints": [{"type": "revolute", "alpha": 0, "a": "L"}] * n})
    gravity = Gravity(direction=(0, -1, 0))
elif ":" in name:  # iiwa7:4: the robot's first four joints
    import dataclasses
    base, count = name.split(":")
    whole = load_robot(base)
    robot = dataclasses.replace(whole, name=f"{base}_{count}", joints=whole.joints[:int(count)], tool=None,
                                inertials=whole.inertials[:int(count)])
    gravity = Gravity()
else:
    robot, gravity = load_robot(name), Gravity()
arm = with_symbolic_inertials(robot)
derive = {"g": lambda: gravity_torques(arm, gravity), "M": lambda: mass_matrix(arm),
          "M by Newton-Euler": lambda: newton_euler_mass_matrix(arm), "C": lambda: coriolis_matrix(arm),
          "tau": lambda: newton_euler(arm, gravity).torques,
          "tau raw": lambda: newton_euler(arm, gravity, simplify=False).torques}[part]
start = time.perf_counter()
result = derive()
seconds = time.perf_counter() - start
print(json.dumps({"seconds": seconds, "ops": int(sum(sp.count_ops(entry) for entry in result))}))
"""


def measure(name: str, part: str, limit: float) -> tuple[float | None, int | None]:
    """Seconds and operation count of one part for one robot in a fresh process; (None, None) past the limit."""
    try:
        done = subprocess.run([sys.executable, "-c", _CHILD, name, part], capture_output=True, text=True,
                              timeout=limit, check=True)
    except subprocess.TimeoutExpired:
        return None, None
    record = json.loads(done.stdout.splitlines()[-1])
    return record["seconds"], record["ops"]


def main(argv: list[str] | None = None) -> int:
    """Print one row per robot: seconds (operations) per part."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["puma560"], help="catalog robots (default: puma560)")
    parser.add_argument("--planar", type=int, nargs="*", default=[], help="planar N-R arms to add")
    parser.add_argument("--prefix", help="a catalog robot whose first --joints joints make arms (iiwa7, panda)")
    parser.add_argument("--joints", type=int, nargs="*", default=[3, 4, 5, 6, 7], help="joints of the --prefix arms")
    parser.add_argument("--limit", type=float, default=300.0, help="seconds per point before it is stopped")
    parser.add_argument("--parts", nargs="*", default=list(PARTS), choices=PARTS)
    options = parser.parse_args(argv)
    names = [*options.robots, *(f"planar-{n}R" for n in options.planar)]
    if options.prefix:
        names += [f"{options.prefix}:{n}" for n in options.joints]
    total_parts = [part for part in ("g", "M", "C", "tau") if part in options.parts]
    print("| robot | " + " | ".join(options.parts) + " | total " + " + ".join(total_parts) + " |")
    print("|---|" + "---|" * (len(options.parts) + 1))
    started = time.perf_counter()
    for name in names:
        cells, total = [], 0.0
        for part in options.parts:
            seconds, ops = measure(name, part, options.limit)
            cells.append(f"> {options.limit:.0f} s" if seconds is None else f"{seconds:.2f} s ({ops:,} ops)")
            if part in total_parts:
                total = float("inf") if seconds is None else total + seconds
        cells.append(f"{total:.1f} s" if total != float("inf") else "-")
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)
    print(f"\n(total {time.perf_counter() - started:.0f} s; cold, one process per point, symbolic inertial data)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

r"""Regressor derivation benchmark: ``python benchmarks/regressor.py [ROBOT ...] [--limit S] [--no-torques]``.

How long symjac takes to derive the regressor :math:`Y(q, \dot q, \ddot q)` of :math:`\tau = Y\pi` (ten standard
parameters per link, :func:`symjac.analysis.identification.regressor`), cold (each point in a fresh Python process:
no SymPy cache, no derived chain), with its size: the nonzero entries of the n x 10n matrix and their operations
(``count_ops``). For comparison, the Newton-Euler torques of the same arm with symbolic inertial data (``m{i}``,
``cx{i}`` .. ``Izz{i}``), laid out, which :math:`Y\pi` equals. Defaults: the PUMA 560 and the 7-joint iiwa7. A point
past ``--limit`` seconds is stopped and shown as such. It measures and asserts nothing, so it never flakes.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time

__all__ = ["main", "measure"]

_CHILD = r"""
import json, sys, time
import sympy as sp
from symjac import load_robot
from symjac.analysis.dynamics import newton_euler
from symjac.analysis.identification import regressor
from symjac.model.inertial_parameters import with_symbolic_inertials

name, part = sys.argv[1], sys.argv[2]
robot = load_robot(name)
if part == "regressor":
    start = time.perf_counter()
    result = regressor(robot).matrix
else:
    arm = with_symbolic_inertials(robot)
    start = time.perf_counter()
    result = newton_euler(arm).torques
seconds = time.perf_counter() - start
print(json.dumps({"seconds": seconds, "shape": list(result.shape), "nonzero": sum(1 for e in result if e != 0),
                  "ops": int(sum(sp.count_ops(entry) for entry in result))}))
"""


def measure(name: str, part: str, limit: float) -> dict | None:
    """Seconds, shape, nonzero entries and operations of one part for one robot in a fresh process; None past limit."""
    try:
        done = subprocess.run([sys.executable, "-c", _CHILD, name, part], capture_output=True, text=True,
                              timeout=limit, check=True)
    except subprocess.TimeoutExpired:
        return None
    return json.loads(done.stdout.splitlines()[-1])  # type: ignore[no-any-return]


def main(argv: list[str] | None = None) -> int:
    """Print one row per robot: the regressor's time and size, and the torques' time for comparison."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["puma560", "iiwa7"], help="catalog robots")
    parser.add_argument("--limit", type=float, default=300.0, help="seconds per point before it is stopped")
    parser.add_argument("--no-torques", action="store_true", help="leave out the Newton-Euler torques")
    options = parser.parse_args(argv)
    print("| robot | Y | regressor | nonzero entries | ops | tau, symbolic inertials |")
    print("|---|---|---|---|---|---|")
    started = time.perf_counter()
    for name in options.robots:
        Y = measure(name, "regressor", options.limit)
        tau = None if options.no_torques else measure(name, "torques", options.limit)
        cells = ["-", f"> {options.limit:.0f} s", "-", "-"] if Y is None else [
            " x ".join(map(str, Y["shape"])), f"{Y['seconds']:.2f} s", str(Y["nonzero"]), f"{Y['ops']:,}"]
        cells.append("-" if options.no_torques else f"> {options.limit:.0f} s" if tau is None else
                     f"{tau['seconds']:.2f} s ({tau['ops']:,} ops)")
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)
    print(f"\n(total {time.perf_counter() - started:.0f} s; cold, one process per point)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

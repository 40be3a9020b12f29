r"""Base-parameter benchmark: ``python benchmarks/base_parameters.py [ROBOT ...] [--limit S]``.

How long :func:`symjac.analysis.identification.base_parameters` takes to find an arm's base parameters in closed form
from its regressor, cold (each robot in a fresh Python process: no SymPy cache, no derived chain), beside the time of
the regressor itself, with the count, the numeric rank and the number of standard parameters grouped into others or
without effect. Inside the base-parameter time, the part spent writing the regressor's entries back into the
polynomial image (``column_table``) is shown on its own. Defaults: the PUMA 560 and the 7-joint iiwa7. A robot past
``--limit`` seconds is stopped and shown as such. It measures and asserts nothing, so it never flakes.
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
from symjac import load_robot
from symjac.analysis.identification import base_parameters, regressor
from symjac.analysis.identification import dependence

spent = []
table = dependence.column_table

def timed_table(*args, **kwargs):
    start = time.perf_counter()
    result = table(*args, **kwargs)
    spent.append(time.perf_counter() - start)
    return result

import symjac.analysis.identification.base as base_module
base_module.column_table = timed_table
robot = load_robot(sys.argv[1])
start = time.perf_counter()
Y = regressor(robot)
middle = time.perf_counter()
base = base_parameters(Y)
end = time.perf_counter()
print(json.dumps({"regressor": middle - start, "base": end - middle, "table": sum(spent), "count": len(base.symbols),
                  "rank": base.rank, "standard": len(Y.parameters), "grouped": len(base.grouped),
                  "none": len(base.unidentifiable)}))
"""


def measure(name: str, limit: float) -> dict | None:
    """The times and counts for one robot in a fresh process; None past ``limit`` seconds."""
    try:
        done = subprocess.run([sys.executable, "-c", _CHILD, name], capture_output=True, text=True, timeout=limit,
                              check=True)
    except subprocess.TimeoutExpired:
        return None
    return json.loads(done.stdout.splitlines()[-1])  # type: ignore[no-any-return]


def main(argv: list[str] | None = None) -> int:
    """Print one row per robot: regressor and base-parameter times, the count and the numeric rank."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["puma560", "iiwa7"], help="catalog robots")
    parser.add_argument("--limit", type=float, default=300.0, help="seconds per robot before it is stopped")
    options = parser.parse_args(argv)
    print("| robot | regressor | base parameters | of which the image | base / rank / standard | grouped | no effect |")
    print("|---|---|---|---|---|---|---|")
    started = time.perf_counter()
    for name in options.robots:
        found = measure(name, options.limit)
        if found is None:
            print(f"| {name} | > {options.limit:.0f} s | - | - | - | - | - |", flush=True)
            continue
        print(f"| {name} | {found['regressor']:.2f} s | {found['base']:.2f} s | {found['table']:.2f} s | "
              f"{found['count']} / {found['rank']} / {found['standard']} | {found['grouped']} | {found['none']} |",
              flush=True)
    print(f"\n(total {time.perf_counter() - started:.0f} s; cold, one process per robot)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

r"""Growth benchmark: ``python benchmarks/growth.py [--family F] [--sizes N ...] [--plot FILE]``.

How the cost of the simplified Jacobian in frame {0} grows with the number of joints, for three families of chains:

- ``planar``: N revolute joints, standard DH, a = 0.1, alpha = 0 (every axis parallel: one run of N joints);
- ``snake``: N revolute joints whose axes alternate by +-90 degrees (standard DH, a = L);
- ``generic``: N revolute joints with a generic twist 0.3 rad and offsets a = 0.1, d = 0.05.

Every point (family, N, method) runs in a fresh Python process (cold: no SymPy cache, no derived chain), with a time
limit; once a method exceeds it, larger N of that family are skipped for it. A result too large to write out
(more than ``symjac.symbolic.size.TERM_LIMIT`` terms: the frame-{0} Jacobian of a long 3-D snake, which grows about 1.8x
per joint) is refused by symjac within seconds; the table says "too large" and how long the refusal took.
``--frame middle`` asks for the Jacobian in frame {N // 2} instead, where each half of the chain stays short.
``--form shared`` times the exact Jacobian with shared subexpressions (``simplify=False``: what code generation
starts from) and counts its distinct subexpressions, which grow polynomially even where the expanded form cannot.

The table gives seconds and the result's operation count (``sympy.count_ops``); the summary fits
:math:`t \approx c\,N^k` by least squares in log-log coordinates and prints the exponent k per family and method.
``--plot`` saves the log-log plot (matplotlib, imported only then). It measures and asserts nothing, so it never flakes.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass

__all__ = ["FAMILIES", "GrowthPoint", "chain_of_family", "fitted_exponent", "main", "measure"]

METHODS = ("differentiation", "cross_product", "velocity_propagation", "force_propagation")
FAMILIES = {"planar": (2, 4, 6, 8, 10, 12, 16, 20, 30), "snake": (2, 4, 6, 8, 10, 12, 14, 16, 20),
            "generic": (2, 3, 4, 5, 6, 7)}


@dataclass(frozen=True)
class GrowthPoint:
    """One measurement: seconds and operation count, or ``None`` for both when it ran out of time."""

    family: str
    n: int
    method: str
    seconds: float | None
    ops: int | None
    refused: bool = False  # symjac refused a result too large to write out (after ``seconds``)


def chain_of_family(family: str, n: int):  # type: ignore[no-untyped-def]  # a Robot; imported lazily
    """The robot of ``family`` with ``n`` joints (see the module docstring)."""
    from symjac.model.robot_file import robot_from_mapping

    if family == "planar":
        joints = [{"type": "revolute", "alpha": 0, "a": 0.1} for _ in range(n)]
        parameters = {}
    elif family == "snake":
        joints = [{"type": "revolute", "alpha": "pi/2" if i % 2 else "-pi/2", "a": "L"} for i in range(n)]
        parameters = {"L": 0.1}
    else:
        joints = [{"type": "revolute", "alpha": 0.3, "a": 0.1, "d": 0.05} for _ in range(n)]
        parameters = {}
    return robot_from_mapping({"name": f"{family}{n}", "convention": "standard", "parameters": parameters,
                               "joints": joints})


def _one(family: str, n: int, method: str, frame: int, form: str) -> None:
    """Measure one point in this process and print it as JSON (the child side of :func:`measure`)."""
    robot = chain_of_family(family, n)  # imports symjac before SymPy: symjac sizes SymPy's cache (see the README)
    import sympy as sp

    from symjac.errors import ResultTooLargeError
    from symjac.kinematics.jacobian import jacobian
    from symjac.symbolic.dag import distinct_nodes

    start = time.perf_counter()
    try:
        J = jacobian(robot, frame=frame, method=method, simplify=form == "compact")  # type: ignore[arg-type]
    except ResultTooLargeError:
        print(json.dumps({"seconds": time.perf_counter() - start, "ops": None, "refused": True}))
        return
    seconds = time.perf_counter() - start
    size = int(sp.count_ops(J)) if form == "compact" else len(distinct_nodes(list(J)))  # a shared tree: its graph
    print(json.dumps({"seconds": seconds, "ops": size, "refused": False}))


def measure(family: str, n: int, method: str, limit: float, frame: str = "0", form: str = "compact") -> GrowthPoint:
    """Time one point in a fresh process; ``None`` values if it does not finish within ``limit`` seconds."""
    at = n // 2 if frame == "middle" else int(frame)
    command = [sys.executable, __file__, "--one", family, str(n), method, str(at), form]
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=limit, check=True)
    except subprocess.TimeoutExpired:
        return GrowthPoint(family, n, method, None, None)
    result = json.loads(done.stdout.strip().splitlines()[-1])
    return GrowthPoint(family, n, method, result["seconds"], result["ops"], result["refused"])


def fitted_exponent(points: Sequence[GrowthPoint]) -> float | None:
    r"""The least-squares slope k of :math:`\log t = k \log N + b` over the finished points with N >= 4."""
    data = [(math.log(p.n), math.log(p.seconds)) for p in points
            if p.seconds is not None and not p.refused and p.n >= 4]
    if len(data) < 2:
        return None
    mean_x = sum(x for x, _ in data) / len(data)
    mean_y = sum(y for _, y in data) / len(data)
    spread = sum((x - mean_x) ** 2 for x, _ in data)
    return sum((x - mean_x) * (y - mean_y) for x, y in data) / spread if spread else None


def _plot(points: Sequence[GrowthPoint], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(7, 5))
    for family, style in zip(FAMILIES, ("-", "--", ":"), strict=True):  # one line style per family
        for method, colour in zip(METHODS, ("C0", "C1", "C2", "C3"), strict=True):  # one colour per method
            done = [p for p in points if p.family == family and p.method == method and p.seconds is not None
                    and not p.refused]
            if done:
                axes.loglog([p.n for p in done], [p.seconds for p in done], marker="o", linestyle=style,
                            color=colour, label=f"{family}, {method.replace('_', ' ')}")
    axes.set_xlabel("joints N")
    axes.set_ylabel("seconds (cold process, frame {0})")
    axes.set_title("symjac: cost of the simplified Jacobian")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(path, dpi=120)


def main(argv: Sequence[str] | None = None) -> int:
    """Print the growth table and the fitted exponents; optionally save the log-log plot."""
    parser = argparse.ArgumentParser(prog="python benchmarks/growth.py", description=__doc__.splitlines()[0])
    parser.add_argument("--family", action="append", choices=sorted(FAMILIES), help="repeatable (default: all)")
    parser.add_argument("--method", action="append", choices=METHODS, help="repeatable (default: all four)")
    parser.add_argument("--sizes", type=int, nargs="+", help="joint counts (default: per family)")
    parser.add_argument("--limit", type=float, default=60.0, help="seconds per point before giving up (default 60)")
    parser.add_argument("--frame", choices=("0", "middle"), default="0",
                        help="the Jacobian's frame: {0} (default) or {N // 2}")
    parser.add_argument("--form", choices=("compact", "shared"), default="compact",
                        help="compact: simplified, operations counted (default); shared: simplify=False, distinct "
                             "subexpressions counted")
    parser.add_argument("--plot", metavar="FILE", help="save a log-log plot (PNG) here")
    parser.add_argument("--one", nargs=5, metavar=("FAMILY", "N", "METHOD", "FRAME", "FORM"), help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.one:
        _one(args.one[0], int(args.one[1]), args.one[2], int(args.one[3]), args.one[4])
        return 0
    points: list[GrowthPoint] = []
    print(f"frame {'{N // 2}' if args.frame == 'middle' else '{0}'}, {args.form} form")
    print(f"{'family':<9}{'N':>4}  {'method':<22}{'seconds':>9}{'ops' if args.form == 'compact' else 'nodes':>9}",
          flush=True)
    for family in args.family or FAMILIES:
        for method in args.method or METHODS:
            for n in args.sizes or FAMILIES[family]:
                point = measure(family, n, method, args.limit, args.frame, args.form)
                points.append(point)
                if point.seconds is None:
                    shown = f"{'> ' + format(args.limit, 'g'):>9}{'-':>9}"
                elif point.refused:
                    shown = f"{point.seconds:>9.2f}  too large (refused)"
                else:
                    shown = f"{point.seconds:>9.2f}{point.ops:>9}"
                print(f"{family:<9}{n:>4}  {method:<22}{shown}", flush=True)
                if point.seconds is None or point.refused:
                    break
    print("\nfitted growth t ~ N^k (points with N >= 4)")
    for family in args.family or FAMILIES:
        for method in args.method or METHODS:
            k = fitted_exponent([p for p in points if p.family == family and p.method == method])
            print(f"{family:<9}{method:<22}{'-' if k is None else format(k, '.2f'):>6}")
    if args.plot:
        _plot(points, args.plot)
        print(f"\nplot saved to {args.plot}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

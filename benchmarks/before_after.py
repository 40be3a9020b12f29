"""Before and after: ``python benchmarks/before_after.py OTHER_CHECKOUT [-n REPEATS]``.

Times the same workloads on this checkout and on another one (an earlier commit, checked out with
``git worktree add /tmp/before <commit>``), through the public API only (``from symjac import ...``), so that both
sides run the same calls whatever their internal layout. Every sample is a fresh interpreter (a cold cache, as a
user's first call); samples of the two checkouts alternate, so that a machine that slows down for a while slows
both; each cell is the best of ``REPEATS``. It prints one Markdown table with the ratio after / before and asserts
nothing.

Workloads: the simplified Jacobian in frame {0} of catalog robots and of a 7-joint chain with a generic twist and
offsets (the seams issue's example), the full singularity report, a generated NumPy module (derivation plus code
generation), and the generated Python and NumPy Jacobians' time per call and per batched configuration.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

__all__ = ["WORKLOADS", "main", "sample"]

HERE = Path(__file__).resolve().parent.parent

CHAIN7 = "\n".join(['name = "chain7"', 'convention = "modified"', ""] + [
    '[[joints]]\ntype = "revolute"\nalpha = 0.3\na = 0.1\nd = 0.05\ntheta = 0.2\n' for _ in range(7)])

_TIMED = """
import sys, time, timeit
from symjac import generate, jacobian, load_robot, singularities
robot = load_robot(sys.argv[1])
start = time.perf_counter()
{body}
"""

WORKLOADS: dict[str, tuple[str, str]] = {
    # label: (robot, body printing one number, seconds unless the label says otherwise)
    "Jacobian {0}, PUMA 560 (s)": ("puma560", "jacobian(robot); print(time.perf_counter() - start)"),
    "Jacobian {0}, UR5 (s)": ("ur5", "jacobian(robot); print(time.perf_counter() - start)"),
    "Jacobian {0}, Panda (s)": ("panda", "jacobian(robot); print(time.perf_counter() - start)"),
    "Jacobian {0}, 7-joint generic chain (s)": ("CHAIN7", "jacobian(robot); print(time.perf_counter() - start)"),
    "singularity report, PUMA 560 (s)": ("puma560", "singularities(robot); print(time.perf_counter() - start)"),
    "singularity report, UR5 (s)": ("ur5", "singularities(robot); print(time.perf_counter() - start)"),
    "codegen numpy, PUMA 560 (s)": ("puma560", "generate(robot, 'numpy'); print(time.perf_counter() - start)"),
    "codegen numpy, Panda (s)": ("panda", "generate(robot, 'numpy'); print(time.perf_counter() - start)"),
    "generated python J, PUMA 560 (us/call)": ("puma560", """
namespace = {}
exec(compile(generate(robot, 'python'), 'puma', 'exec'), namespace)
q = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]
print(min(timeit.repeat(lambda: namespace['jacobian'](q), number=20000, repeat=5)) / 20000 * 1e6)"""),
    "generated numpy J, PUMA 560 (ns/config)": ("puma560", """
import numpy as np
namespace = {}
exec(compile(generate(robot, 'numpy'), 'puma', 'exec'), namespace)
q = np.random.default_rng(0).uniform(-3, 3, (100000, 6))
print(min(timeit.repeat(lambda: namespace['jacobian'](q), number=5, repeat=5)) / 5 / 100000 * 1e9)"""),
}


def sample(checkout: Path, robot: str, body: str) -> float:
    """One fresh-interpreter measurement of ``body`` on ``checkout`` (its package first on the path)."""
    with tempfile.TemporaryDirectory() as folder:
        if robot == "CHAIN7":
            robot = str(Path(folder) / "chain7.toml")
            Path(robot).write_text(CHAIN7)
        environment = {**os.environ, "PYTHONPATH": str(checkout)}
        result = subprocess.run([sys.executable, "-c", _TIMED.format(body=body.strip()), robot], cwd=folder,
                                env=environment, capture_output=True, text=True, check=True)
    return float(result.stdout.split()[-1])


def main(argv: Sequence[str] | None = None) -> int:
    """Print the table: each workload's best time before and after, and their ratio."""
    parser = argparse.ArgumentParser(prog="python benchmarks/before_after.py", description=__doc__.splitlines()[0])
    parser.add_argument("before", type=Path, help="the other checkout (the 'before' column)")
    parser.add_argument("-n", "--repeats", type=int, default=5, help="fresh-process samples per cell (default 5)")
    args = parser.parse_args(argv)
    print("| workload | before | after | after / before |\n|---|---|---|---|")
    for label, (robot, body) in WORKLOADS.items():
        before, after = [], []
        for _ in range(args.repeats):
            before.append(sample(args.before.resolve(), robot, body))
            after.append(sample(HERE, robot, body))
        print(f"| {label} | {min(before):.3g} | {min(after):.3g} | {min(after) / min(before):.2f} |", flush=True)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

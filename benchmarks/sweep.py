"""Design sweeps against a hand-written NumPy pipeline, and from one dask worker to two: ``python benchmarks/sweep.py``.

1. PUMA 560, N joint samples (Sobol) times 16 values of a2, the metrics gci, manipulability and sigma_min:
   nanoseconds per sample of ``symjac.sweep`` on dask's threaded scheduler, and of the best pipeline written by
   hand over the same samples on the same cores (the ``c`` target's batched Jacobian, then batched singular values,
   in two threads over halves of the samples), with the ratio (the issue's goal: 1.5 or less). The manipulability of
   the square J is the product of the singular values the SVD already gives, so no determinant is taken apart.
2. The same sweep on a ``distributed.LocalCluster`` of one worker, then of two (one thread each): the speed-up (goal:
   1.6 or more on a 2-core machine).
3. Peak memory (resident set, MB) of a sweep of ``--big`` samples in a fresh process (goal for 1e8: below 500 MB).

``--samples N`` (default 1e6) and ``--big M`` (default 1e7; 1e8 takes about ten times longer) set the sizes. It
asserts nothing.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import json
import subprocess
import sys
import time

import numpy as np

from symjac import JacobianRequest, generate, load_robot, sweep
from symjac.sweeps.run import kernel_module
from symjac.sweeps.sampling import JointSampler, joint_ranges

METRICS = ("gci", "manipulability", "sigma_min")
A2 = (0.35, 0.50, 16)


def _best(run, repeat: int = 3) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def by_hand(samples: int, chunk: int = 65_536) -> float:
    """Seconds for the hand-written pipeline: J then SVD per chunk, two threads, all 16 designs."""
    robot = load_robot("puma560")
    module = kernel_module(generate(robot, "c", jacobians=[JacobianRequest(0, "wrist")]))
    sampler = JointSampler(joint_ranges(robot), samples)
    Q = sampler.chunk(0, samples)  # drawn once, outside the timing: the sweep draws them chunk by chunk

    def design(a2: float) -> float:
        total = 0.0
        for start in range(0, samples, chunk):
            sigma = np.linalg.svd(module.jacobian(Q[start:start + chunk], a2=a2), compute_uv=False)
            total += float(np.sum(sigma[:, -1] / sigma[:, 0])) + float(np.sum(np.prod(sigma, axis=1)))
        return total

    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        return _best(lambda: list(pool.map(design, np.linspace(*A2))))


def with_sweep(samples: int, **options) -> float:  # type: ignore[no-untyped-def]
    """Seconds for symjac.sweep over the same designs."""
    robot = load_robot("puma560")
    return _best(lambda: sweep(robot, {"a2": A2}, samples=samples, metrics=METRICS, **options))


def workers(samples: int) -> tuple[float, float]:
    """Seconds on a LocalCluster of one worker, then of two."""
    from distributed import Client, LocalCluster

    robot = load_robot("puma560")
    seconds = []
    for count in (1, 2):
        with LocalCluster(n_workers=count, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
                Client(cluster) as client:
            sweep(robot, {"a2": A2}, samples=1000, metrics=METRICS, client=client)  # warm: compile and import
            seconds.append(_best(lambda: sweep(robot, {"a2": A2}, samples=samples, metrics=METRICS,
                                               client=client), repeat=2))
    return seconds[0], seconds[1]


_PEAK = """
import json, resource, sys
from symjac import load_robot, sweep
sweep(load_robot("puma560"), {"a2": [0.4318]}, samples=int(sys.argv[1]), metrics=["gci", "manipulability"])
print(json.dumps(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024))
"""


def peak_memory(samples: int) -> float:
    """Peak resident MB of a one-design sweep of ``samples`` in a fresh process."""
    done = subprocess.run([sys.executable, "-c", _PEAK, str(samples)], capture_output=True, text=True, check=True)
    return float(json.loads(done.stdout))


def main(argv: list[str] | None = None) -> None:
    """Print the three tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=float, default=1e6)
    parser.add_argument("--big", type=float, default=1e7)
    args = parser.parse_args(argv)
    samples, big = int(args.samples), int(args.big)
    per = samples * A2[2] / 1e9
    hand, ours = by_hand(samples), with_sweep(samples)
    print(f"| PUMA 560, {samples:.0e} samples x 16 designs | ns/sample | ratio |\n|---|---|---|")
    print(f"| hand-written: c kernel + batched SVD, 2 threads | {hand / per:.0f} | 1.00 |")
    print(f"| symjac.sweep, dask threads | {ours / per:.0f} | {ours / hand:.2f} |", flush=True)
    one, two = workers(samples)
    print(f"\n| LocalCluster | s | speed-up |\n|---|---|---|\n| 1 worker | {one:.2f} | 1.00 |\n"
          f"| 2 workers | {two:.2f} | {one / two:.2f} |", flush=True)
    print(f"\n| one design, {big:.0e} samples | peak MB |\n|---|---|\n| symjac.sweep | {peak_memory(big):.0f} |")


if __name__ == "__main__":
    main()

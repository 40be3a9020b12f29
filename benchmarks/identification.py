r"""Identification workflow benchmark: ``python benchmarks/identification.py [ROBOT] [-n N] [--targets T ...]``.

The cost of the numeric side of identification with a generated module (``identification=True``): evaluating and
stacking the base regressor over N samples (:func:`symjac.analysis.identification.stack`; the ``numpy`` and ``c``
targets take the batch in one call, the ``python`` target one sample at a time), then solving by least squares
(:func:`~symjac.analysis.identification.identify`), and the largest residual on noise-free torques from the same
module's inverse dynamics. Default: the PUMA 560, 2000 samples of a Fourier trajectory, the numpy target. It
measures and asserts nothing, so it never flakes.
"""

from __future__ import annotations

import argparse
import importlib.util
import tempfile
import time
from pathlib import Path

import numpy as np

import symjac
from symjac.analysis.identification import fourier_trajectory, identify, stack

__all__ = ["main"]


def _module(robot: symjac.Robot, target: str, folder: Path):
    path = folder / f"{robot.name}_{target}.py"
    path.write_text(symjac.generate(robot, target, identification=True))
    spec = importlib.util.spec_from_file_location(path.stem, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _best(function, repeats: int = 3) -> tuple[float, object]:
    """The fastest of ``repeats`` calls (seconds) and the last result."""
    best, result = float("inf"), None
    for _ in range(repeats):
        start = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - start)
    return best, result


def main(argv: list[str] | None = None) -> int:
    """Print one row per target: generation, stacking per sample, the solve, and the estimate's error."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robot", nargs="?", default="puma560", help="a catalog robot with inertial data")
    parser.add_argument("-n", type=int, default=2000, help="samples")
    parser.add_argument("--targets", nargs="+", default=["numpy"], choices=["python", "numpy", "c"])
    options = parser.parse_args(argv)
    robot = symjac.load_robot(options.robot)
    joints = robot.n_coordinates
    coefficients = np.random.default_rng(0).normal(0.0, 0.3, (joints, 2, 3))
    t = np.linspace(0.0, 10.0, options.n, endpoint=False)
    q, qdot, qddot = fourier_trajectory(coefficients, 2 * np.pi / 10, np.zeros(joints), t)
    print("| robot | target | generate | stack, per sample | identify | rows x b | condition | largest residual |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        for target in options.targets:
            start = time.perf_counter()
            module = _module(robot, target, Path(folder))
            generated = time.perf_counter() - start
            tau = (np.array([module.inverse_dynamics(*sample) for sample in zip(q, qdot, qddot, strict=True)])
                   if target == "python" else np.asarray(module.inverse_dynamics(q, qdot, qddot)))
            stacking, W = _best(lambda module=module: stack(module.base_regressor, q, qdot, qddot))
            solving, exact = _best(lambda W=W, tau=tau: identify(W, tau))
            residual = float(np.abs(W @ exact.parameters - tau.reshape(-1)).max())
            print(f"| {robot.name} | {target} | {generated:.1f} s | {stacking / options.n * 1e6:.1f} us | "
                  f"{solving * 1e3:.1f} ms | {W.shape[0]} x {W.shape[1]} | {exact.condition_number:.0f} | "
                  f"{residual:.1e} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Benchmark of generated code: ``python benchmarks/generated_code.py [ROBOT ...] [-n N]``.

For each robot (default: puma560 and panda) it generates the Jacobian in frame {0} at the wrist for every target,
imports the modules from a temporary folder and measures, in the same run:

* microseconds per call, one configuration: ``sympy.lambdify`` of the unsimplified Jacobian without CSE (the
  baseline, ``math`` module, a flat list of entries), and the generated ``python``, ``lambdify`` and ``c`` modules
  (the ``c`` call writes into a preallocated ``out``, as a controller loop would);
* nanoseconds per configuration for a batch of N = 100 000: the baseline lambdified with NumPy and written into a
  preallocated array, and the generated ``numpy``, ``lambdify`` and ``c`` modules (new result array; ``c`` and
  ``numpy`` use up to ``THREADS`` threads, the number of CPUs by default).

With ``acceleration=True`` modules it then compares the bias acceleration ``Jdot qdot`` with the Jacobian: the
operations after CSE of each generated function (the ``# total ops`` of the generated code; the issue's target is
that PUMA's ``Jdot qdot`` costs at most twice its J) and the time per call (``python``, ``c`` one configuration into
``out``) and per batched configuration (``numpy``, ``c``).

It reports best-of-several timings and asserts nothing. Targets on a 2-core machine, PUMA 560: python <= 1.5 us,
numpy <= 100 ns/config, c <= 0.5 us and <= 50 ns/config. The C kernels are cached in ``$SYMJAC_CACHE_DIR``
(``~/.cache/symjac`` by default), so the first run also compiles them.
"""

from __future__ import annotations

import argparse
import importlib.util
import tempfile
import timeit
import types
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import sympy as sp

from symjac.codegen import ModuleRequest, describe, generate, write_module
from symjac.kinematics.jacobian import jacobian
from symjac.model.io import load_robot
from symjac.model.robot import Robot

__all__ = ["Measurement", "main", "measure", "measure_acceleration"]

PYTHON_TARGETS = ("python", "numpy", "lambdify", "c")
"""The targets that write one Python module (the others have their own benchmarks: cpp_vs_pinocchio, jax_casadi)."""


@dataclass(frozen=True)
class Measurement:
    """One line of the report: microseconds per call and nanoseconds per batched configuration (NaN: not run)."""

    robot: str
    implementation: str
    us_per_call: float
    ns_per_config: float
    note: str = ""


def _best(statement: str, namespace: dict[str, Any], seconds: float = 0.2, repeat: int = 7) -> float:
    """Best time of one execution of ``statement``, in seconds (loops of about ``seconds``, best of ``repeat``).

    The statement is timed as written (``jacobian(q)``), without a lambda around it.
    """
    timer = timeit.Timer(statement, globals=namespace)
    number, elapsed = timer.autorange()
    number = max(1, int(number * seconds / max(elapsed, 1e-9)))
    return min(timer.repeat(repeat=repeat, number=number)) / number


def _import(path: Path, name: str) -> types.ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise ImportError(f"cannot import {path}")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def measure(robot: Robot, count: int = 100_000, seconds: float = 0.2) -> list[Measurement]:
    """Time the baseline and every generated target for ``robot`` (Jacobian in {0} at the wrist)."""
    rng = np.random.default_rng(0)
    q = rng.uniform(-np.pi, np.pi, robot.n_coordinates)
    batch = rng.uniform(-np.pi, np.pi, (count, robot.n_coordinates))
    values = [float(p.default) for p in robot.parameters]
    n = robot.n_coordinates
    rows: list[Measurement] = []

    J = jacobian(robot, simplify=False)
    arguments = [*robot.q, *robot.parameter_symbols]
    entries = list(J)  # a flat list: lambdify of a Matrix breaks on batches with constant entries
    scalar = sp.lambdify(arguments, entries, modules="math")
    vectorised = sp.lambdify(arguments, entries, modules="numpy")
    q_list = [float(v) for v in q]
    out_batch = np.empty((count, 6 * n))

    def baseline_batch() -> None:
        for k, value in enumerate(vectorised(*batch.T, *values)):
            out_batch[:, k] = value

    names: dict[str, Any] = {"scalar": scalar, "q_list": q_list, "values": values, "baseline_batch": baseline_batch,
                             "q": q, "batch": batch, "out": np.empty((6, n))}
    rows.append(Measurement(robot.name, "sympy.lambdify, raw J, no CSE",
                            _best("scalar(*q_list, *values)", names, seconds) * 1e6,
                            _best("baseline_batch()", names, seconds) * 1e9 / count, "math / numpy modules"))

    with tempfile.TemporaryDirectory() as folder:
        for target in PYTHON_TARGETS:
            path = Path(folder) / f"bench_{robot.name}_{target}.py"
            write_module(path, generate(robot, target))
            names[target] = _import(path, f"bench_{robot.name}_{target}")
        threads = names["numpy"].THREADS
        rows.append(Measurement(robot.name, "generated python", _best("python.jacobian(q_list)", names, seconds) * 1e6,
                                float("nan"), "list in, nested tuples out"))
        rows.append(Measurement(robot.name, "generated numpy", float("nan"),
                                _best("numpy.jacobian(batch)", names, seconds) * 1e9 / count, f"{threads} thread(s)"))
        rows.append(Measurement(robot.name, "generated lambdify", _best("lambdify.jacobian(q)", names, seconds) * 1e6,
                                _best("lambdify.jacobian(batch)", names, seconds) * 1e9 / count,
                                "sympy.lambdify(cse=True) at import"))
        backend = names["c"].BACKEND
        rows.append(Measurement(robot.name, f"generated c ({backend})",
                                _best("c.jacobian(q, out)", names, seconds) * 1e6,
                                _best("c.jacobian(batch)", names, seconds) * 1e9 / count,
                                f"{threads} thread(s); one configuration into out=" if backend == "c"
                                else f"fallback: {names['c'].BUILD_ERROR}"))
        if backend == "c":
            names["c"].THREADS = 1
            rows.append(Measurement(robot.name, "generated c, 1 thread", _best("c.jacobian(q)", names, seconds) * 1e6,
                                    _best("c.jacobian(batch)", names, seconds) * 1e9 / count,
                                    "one configuration without out= (allocates)"))
            names["numpy"].THREADS = 1
            rows.append(Measurement(robot.name, "generated numpy, 1 thread", float("nan"),
                                    _best("numpy.jacobian(batch)", names, seconds) * 1e9 / count, ""))
    return rows


def measure_acceleration(robot: Robot, count: int = 100_000, seconds: float = 0.2) -> list[Measurement]:
    """Time ``jacobian`` against ``bias_acceleration`` (Jdot qdot) in modules generated with acceleration=True."""
    rng = np.random.default_rng(0)
    n = robot.n_coordinates
    q, qdot = rng.uniform(-np.pi, np.pi, n), rng.uniform(-1.0, 1.0, n)
    batch, rates = rng.uniform(-np.pi, np.pi, (count, n)), rng.uniform(-1.0, 1.0, (count, n))
    names: dict[str, Any] = {"q": q, "qdot": qdot, "q_list": [float(v) for v in q],
                             "qdot_list": [float(v) for v in qdot], "batch": batch, "rates": rates,
                             "J_out": np.empty((6, robot.n_coordinates)), "bias_out": np.empty(6)}
    rows: list[Measurement] = []
    with tempfile.TemporaryDirectory() as folder:
        for target in ("python", "numpy", "c"):
            path = Path(folder) / f"bench_{robot.name}_{target}_acceleration.py"
            write_module(path, generate(robot, target, acceleration=True))
            names[target] = _import(path, f"bench_{robot.name}_{target}_acceleration")
        functions = {f.name: f for f in describe(ModuleRequest(robot, "python", acceleration=True)).functions}
        for name, call, batched, out in (("jacobian", "(q_list)", "(batch)", "J_out"),
                                         ("bias_acceleration", "(q_list, qdot_list)", "(batch, rates)", "bias_out")):
            spec = functions[name]
            note = f"{spec.op_count} ops after CSE + {spec.trig_count} sin/cos"
            rows.append(Measurement(robot.name, f"python {name}", _best(f"python.{name}{call}", names, seconds) * 1e6,
                                    float("nan"), note))
            rows.append(Measurement(robot.name, f"numpy {name}", float("nan"),
                                    _best(f"numpy.{name}{batched}", names, seconds) * 1e9 / count, note))
            if names["c"].BACKEND == "c":
                c_call = call.replace("_list", "").replace(")", f", {out})")
                rows.append(Measurement(robot.name, f"c {name}", _best(f"c.{name}{c_call}", names, seconds) * 1e6,
                                        _best(f"c.{name}{batched}", names, seconds) * 1e9 / count, note))
    return rows


def main(argv: Sequence[str] | None = None) -> int:
    """Print one line per robot and implementation: us per call and ns per configuration."""
    parser = argparse.ArgumentParser(prog="python benchmarks/generated_code.py", description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["puma560", "panda"], help="catalog names or robot files")
    parser.add_argument("-n", type=int, default=100_000, help="configurations per batch (default 100000)")
    parser.add_argument("--seconds", type=float, default=0.2, help="length of one timing loop (default 0.2 s)")
    args = parser.parse_args(argv)
    print(f"{'robot':<10}{'implementation':<32}{'us/call':>9}{'ns/config':>11}  notes (N = {args.n})")
    for name in args.robots:
        for row in measure(load_robot(name), args.n, args.seconds):
            us = "-" if np.isnan(row.us_per_call) else f"{row.us_per_call:.2f}"
            ns = "-" if np.isnan(row.ns_per_config) else f"{row.ns_per_config:.1f}"
            print(f"{row.robot:<10}{row.implementation:<32}{us:>9}{ns:>11}  {row.note}", flush=True)
    print(f"\n{'robot':<10}{'acceleration=True module':<32}{'us/call':>9}{'ns/config':>11}  operations")
    for name in args.robots:
        robot = load_robot(name)
        functions = {f.name: f for f in describe(ModuleRequest(robot, "python", acceleration=True)).functions}
        for row in measure_acceleration(robot, args.n, args.seconds):
            us = "-" if np.isnan(row.us_per_call) else f"{row.us_per_call:.2f}"
            ns = "-" if np.isnan(row.ns_per_config) else f"{row.ns_per_config:.1f}"
            print(f"{row.robot:<10}{row.implementation:<32}{us:>9}{ns:>11}  {row.note}", flush=True)
        J, bias = functions["jacobian"].op_count, functions["bias_acceleration"].op_count
        print(f"{robot.name:<10}Jdot qdot / J operations: {bias} / {J} = {bias / J:.2f} (target <= 2)", flush=True)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

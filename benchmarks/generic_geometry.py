r"""Generic and calibrated geometry: ``python benchmarks/generic_geometry.py [--quick] [--json FILE] [-n RUNS]``.

Robots whose constant rotations are generic numbers (calibrated screw axes, twists such as 1.5702 rad) have no
textbook form; symjac derives them nested (``Chain(robot).nested``: floats, named intermediates, no simplification).
This script times them, each figure in fresh Python processes (cold: import symjac, load the robot file, derive),
best of ``-n`` runs (default 2), with the machine's one-minute load average at the start of each figure:

- **PoE arms**: 3 to 7 joints with random unit screw axes (every third joint prismatic) and a random home pose, all
  written with 17 significant digits: ``space_jacobian``, ``body_jacobian``, ``forward_kinematics(target="tool")``
  and ``jacobian(point="tool")`` each in its own process, and all four in one process. Goals: each within 2 s,
  all four within 4 s, 7 joints within twice 6 joints.
- **Calibrated PUMA**: the catalog's PUMA 560 (modified DH) with its lengths as numbers, calibrated twists
  (1.5702, -1.5709, 0.0004, 1.5711, -1.5703, 1.5706 rad) and small offsets added to ``a`` and ``d``, against the
  textbook ``puma560``: Jacobian time (goal within 1.5 times the textbook's) and ``symjac codegen FILE --target
  cpp -o DIR`` wall time (goal 3 s).
- **Long chains**: standard DH chains with random generic twists, lengths and offsets: ``codegen --target cpp`` of
  20 joints (goal 10 s), the Jacobian of 40 joints with the process's peak memory (goal 30 s and 1 GB).
- **Growth**: the Jacobian and forward kinematics of those chains at 5, 10, 20 and 40 joints, with the exponent
  :math:`k = \log(t_2 / t_1) / \log(n_2 / n_1)` of :math:`t \approx c\,n^k` between successive sizes (goal
  :math:`k \le 2`).
- **Numbers**: the 6-joint PoE arm's nested Jacobian evaluated at one configuration by ``symjac.evaluate_at`` and by
  ``symjac.numeric_jacobian`` (first call: the lambdify included), checked against each other.

``--quick`` keeps the small sizes (PoE 3 and 4 joints, growth 5 and 10, codegen of 6 joints, no 40-joint chain): a
smoke run for the test suite. The generators (:func:`poe_arm`, :func:`calibrated_puma`, :func:`generic_chain`) are
seeded, so every run times the same robots. The script asserts nothing; it prints tables (and ``--json`` saves them).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["calibrated_puma", "generic_chain", "main", "poe_arm"]

CALIBRATED_TWISTS = (1.5702, -1.5709, 0.0004, 1.5711, -1.5703, 1.5706)
"""The calibrated PUMA's twists alpha_{i-1} (radians)."""

SECTIONS = ("poe", "puma", "long", "growth", "numbers")
QUERIES = ("space_jacobian", "body_jacobian", "forward_kinematics", "jacobian")


def _number(value: float) -> str:
    return repr(float(value))  # 17 significant digits: round-trips a double


def _vector(values: Sequence[float]) -> str:
    return "[" + ", ".join(_number(v) for v in values) + "]"


def poe_arm(n: int, seed: int = 41) -> str:
    r"""The TOML text of an ``n``-joint PoE arm with generic float screws; joints 3, 6, ... are prismatic.

    A revolute joint's screw is :math:`(\omega, -\omega \times q)` with a random unit axis :math:`\omega` and a point
    :math:`q` in a 1 m cube; a prismatic one's is :math:`(0, v)` with a random unit :math:`v`. The home pose ``M`` is
    a random rotation (QR of a Gaussian matrix) and a random position.
    """
    rng = np.random.default_rng(seed + n)
    lines = [f'name = "poe{n}"', f'description = "generic PoE arm, {n} joints, seed {seed}"', 'convention = "poe"', ""]
    rotation, upper = np.linalg.qr(rng.normal(size=(3, 3)))
    rotation = rotation @ np.diag(np.sign(np.diag(upper)))
    if np.linalg.det(rotation) < 0:
        rotation[:, 2] *= -1
    position = rng.uniform(-0.5, 0.5, size=3) + np.array([0.0, 0.0, 0.3 * n])
    home = np.eye(4)
    home[:3, :3], home[:3, 3] = rotation, position
    rows = ", ".join([*(_vector(row) for row in home[:3]), "[0, 0, 0, 1]"])
    lines += ["[home]", f"matrix = [{rows}]", ""]
    for i in range(n):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        if (i + 1) % 3 == 0:
            kind, screw = "prismatic", [0.0, 0.0, 0.0, *axis]
        else:
            point = rng.uniform(-0.5, 0.5, size=3) + np.array([0.0, 0.0, 0.3 * i])
            kind, screw = "revolute", [*axis, *np.cross(point, axis)]  # v = -w x q = q x w
        lines += ["[[joints]]", f'type = "{kind}"', f"screw = {_vector(screw)}", ""]
    return "\n".join(lines)


def calibrated_puma(seed: int = 560) -> str:
    """The TOML text of the PUMA 560 of the catalog (modified DH) calibrated: :data:`CALIBRATED_TWISTS` and offsets.

    The lengths are numbers (a2 = 0.4318, a3 = 0.0203, d3 = 0.15005, d4 = 0.4318, no parameters), each ``a`` and
    ``d`` plus a random offset below 0.5 mm, written with 6 decimals.
    """
    rng = np.random.default_rng(seed)
    a = np.array([0, 0, 0.4318, 0.0203, 0, 0]) + rng.uniform(-5e-4, 5e-4, size=6)
    d = np.array([0, 0, 0.15005, 0.4318, 0, 0]) + rng.uniform(-5e-4, 5e-4, size=6)
    lines = ['name = "puma560_calibrated"', 'description = "PUMA 560 with calibrated twists and offsets"',
             'convention = "modified"', ""]
    for alpha, length, offset in zip(CALIBRATED_TWISTS, a, d, strict=True):
        lines += ["[[joints]]", 'type = "revolute"', f"alpha = {alpha}", f"a = {length:.6f}", f"d = {offset:.6f}",
                  "theta = 0", ""]
    return "\n".join(lines)


def generic_chain(n: int, seed: int = 41) -> str:
    """The TOML text of an ``n``-joint revolute chain in standard DH with random generic twists and lengths.

    Twists uniform in (-pi, pi), ``a`` in (0.05, 0.3) m, ``d`` in (-0.1, 0.1) m, all with 12 decimals.
    """
    rng = np.random.default_rng(seed + 1000 + n)
    lines = [f'name = "generic{n}"', f'description = "generic DH chain, {n} joints, seed {seed}"',
             'convention = "standard"', ""]
    for _ in range(n):
        alpha, a, d = rng.uniform(-math.pi, math.pi), rng.uniform(0.05, 0.3), rng.uniform(-0.1, 0.1)
        lines += ["[[joints]]", 'type = "revolute"', f"alpha = {alpha:.12f}", f"a = {a:.12f}", f"d = {d:.12f}", ""]
    return "\n".join(lines)


def _child(path: str, queries: Sequence[str]) -> None:
    """Time ``queries`` on the robot file ``path`` in this process; print seconds, peak memory and nesting as JSON."""
    import resource

    start = time.perf_counter()
    import symjac
    from symjac.kinematics.chain import Chain

    robot = symjac.load_robot(path)
    seconds: dict[str, float] = {"load": time.perf_counter() - start}
    calls = {"space_jacobian": lambda: symjac.space_jacobian(robot),
             "body_jacobian": lambda: symjac.body_jacobian(robot),
             "forward_kinematics": lambda: symjac.forward_kinematics(robot, target="tool"),
             "jacobian": lambda: symjac.jacobian(robot, point="tool"),
             "jacobian_0": lambda: symjac.jacobian(robot),
             "forward_kinematics_n": lambda: symjac.forward_kinematics(robot)}
    for query in queries:
        start = time.perf_counter()
        calls[query]()
        seconds[query] = time.perf_counter() - start
    maxrss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux
    print(json.dumps({"seconds": seconds, "maxrss_mb": maxrss / 1024, "nested": Chain(robot).nested}))


def _numbers_child(path: str) -> None:
    """Evaluate the nested Jacobian at one configuration by both public routes and written out; print them as JSON."""
    import symjac

    robot = symjac.load_robot(path)
    q = [0.1 * (i + 1) for i in range(robot.n_coordinates)]
    J = symjac.jacobian(robot, point="tool")
    report: dict[str, Any] = {"type": type(J).__name__}
    values = {}
    for name, call in (("inlined", lambda: _inlined_at(robot, J, q)),
                       ("evaluate_at", lambda: symjac.evaluate_at(robot, J, q)),
                       ("numeric_jacobian", lambda: symjac.numeric_jacobian(robot, q, point="tool"))):
        start = time.perf_counter()
        try:
            values[name] = np.array(call(), dtype=float)
            report[name] = time.perf_counter() - start
        except Exception as error:  # report, do not stop: whether they accept nested results is the question
            report[name] = f"{type(error).__name__}: {str(error)[:160]}"
    for name in ("evaluate_at", "numeric_jacobian"):
        if name in values and "inlined" in values:
            report[f"{name}_difference"] = float(np.max(np.abs(values[name] - values["inlined"])))
    print(json.dumps(report))


def _inlined_at(robot: Any, J: Any, q: Sequence[float]) -> Any:
    """The reference: ``J`` written out (intermediates inlined), then the configuration substituted."""
    import sympy as sp

    from symjac.kinematics.numeric import values_at
    from symjac.symbolic.nested import inline

    return sp.Matrix(J.shape[0], J.shape[1], inline(list(J))).xreplace(values_at(robot, q)).evalf()


def _run(arguments: Sequence[str], runs: int) -> dict[str, Any]:
    """Best of ``runs`` fresh processes of this script with ``arguments`` (per query), plus the load at the start."""
    load = os.getloadavg()[0]
    results = []
    for _ in range(runs):
        start = time.perf_counter()
        done = subprocess.run([sys.executable, __file__, *arguments], capture_output=True, text=True, check=False)
        wall = time.perf_counter() - start
        if done.returncode:
            return {"error": done.stderr.strip().splitlines()[-1] if done.stderr.strip() else "failed", "load": load}
        result = json.loads(done.stdout.strip().splitlines()[-1])
        results.append({**result, "wall": wall})
    best = {key: min(r["seconds"][key] for r in results) for key in results[0]["seconds"]}
    return {"seconds": best, "wall": min(r["wall"] for r in results), "load": load, "nested": results[0]["nested"],
            "maxrss_mb": max(r["maxrss_mb"] for r in results)}


def _codegen(path: Path, folder: Path, runs: int) -> dict[str, Any]:
    """Best wall time of ``symjac codegen PATH --target cpp -o FOLDER`` over ``runs`` fresh processes."""
    load, times = os.getloadavg()[0], []
    for _ in range(runs):
        start = time.perf_counter()
        done = subprocess.run([sys.executable, "-m", "symjac", "codegen", str(path), "--target", "cpp", "-o",
                               str(folder)], capture_output=True, text=True, check=False)
        if done.returncode:
            return {"error": (done.stderr.strip().splitlines() or ["failed"])[-1], "load": load}
        times.append(time.perf_counter() - start)
    return {"seconds": min(times), "load": load}


def _failure(result: dict[str, Any]) -> str:
    return f" failed: {result['error'][:200]}" if result.get("error") else ""


def _cell(value: float | None, digits: int = 2) -> str:
    return "-" if value is None else f"{value:.{digits}f}"


def main(argv: Sequence[str] | None = None) -> int:
    """Write the robots to a temporary folder, time every figure, print the tables."""
    parser = argparse.ArgumentParser(prog="python benchmarks/generic_geometry.py", description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes only (a smoke run)")
    parser.add_argument("--json", metavar="FILE", help="also save the figures as JSON here")
    parser.add_argument("-n", "--runs", type=int, default=2, help="fresh processes per figure, best kept (default 2)")
    parser.add_argument("--section", action="append", choices=SECTIONS, help="repeatable (default: all)")
    parser.add_argument("--child", nargs="+", metavar=("FILE", "QUERY"), help=argparse.SUPPRESS)
    parser.add_argument("--numbers", metavar="FILE", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        _child(args.child[0], args.child[1:])
        return 0
    if args.numbers:
        _numbers_child(args.numbers)
        return 0
    figures: dict[str, Any] = {"cores": os.cpu_count(), "runs": args.runs, "quick": args.quick}
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)

        def written(name: str, text: str) -> Path:
            path = folder / f"{name}.toml"
            path.write_text(text)
            return path

        print(f"cold processes, best of {args.runs}; load = one-minute load average at the start of each row "
              f"({os.cpu_count()} cores)\n")
        tables = {"poe": lambda: _poe_table(written, args), "puma": lambda: _puma_table(written, folder, args),
                  "long": lambda: _long_table(written, folder, args), "growth": lambda: _growth_table(written, args),
                  "numbers": lambda: _numbers(written)}
        for section in args.section or SECTIONS:
            figures[section] = tables[section]()
            print(flush=True)
    if args.json:
        Path(args.json).write_text(json.dumps(figures, indent=2) + "\n")
        print(f"figures saved to {args.json}")
    return 0


def _poe_table(written: Any, args: argparse.Namespace) -> list[dict[str, Any]]:
    print("PoE arms with generic float screws (s; goals: each <= 2, all four <= 4, 7 joints <= 2 x 6 joints)")
    print("| joints | nested | space J | body J | FK tool | J tool | all four | all four, wall | load |\n"
          "|---|---|---|---|---|---|---|---|---|", flush=True)
    rows = []
    for n in (3, 4) if args.quick else (3, 4, 5, 6, 7):
        path = str(written(f"poe{n}", poe_arm(n)))
        each = {query: _run(["--child", path, query], args.runs) for query in QUERIES}
        together = _run(["--child", path, *QUERIES], args.runs)
        if any("error" in r for r in (*each.values(), together)):
            errors = [r["error"] for r in (*each.values(), together) if "error" in r]
            print(f"| {n} | failed: {errors[0]} |", flush=True)
            rows.append({"joints": n, "error": errors[0]})
            continue
        row = {"joints": n, "nested": together["nested"], "load": each["jacobian"]["load"],
               **{query: each[query]["seconds"][query] for query in QUERIES},
               "all_four": sum(together["seconds"][q] for q in QUERIES), "all_four_wall": together["wall"]}
        rows.append(row)
        print(f"| {n} | {row['nested']} | " + " | ".join(_cell(row[q]) for q in QUERIES)
              + f" | {_cell(row['all_four'])} | {_cell(row['all_four_wall'])} | {row['load']:.1f} |", flush=True)
    done = {r["joints"]: r for r in rows if "error" not in r}
    if 6 in done and 7 in done:
        print("7 joints / 6 joints: " + ", ".join(f"{q} {done[7][q] / done[6][q]:.2f}"
                                                   for q in (*QUERIES, "all_four")))
    return rows


def _puma_table(written: Any, folder: Path, args: argparse.Namespace) -> dict[str, Any]:
    print("Calibrated PUMA 560 against the textbook one (s; goals: Jacobian <= 1.5 x textbook, codegen cpp <= 3)")
    path = written("puma560_calibrated", calibrated_puma())
    result: dict[str, Any] = {}
    print("| robot | nested | Jacobian {0} | FK | codegen cpp, wall | load |\n|---|---|---|---|---|---|", flush=True)
    for label, robot in (("puma560", "puma560"), ("calibrated", str(path))):
        timed = _run(["--child", robot, "jacobian_0", "forward_kinematics_n"], args.runs)
        generated = _codegen(Path(robot) if robot != "puma560" else Path("puma560"), folder / f"cpp_{label}", args.runs)
        result[label] = {"jacobian": timed.get("seconds", {}).get("jacobian_0"), "nested": timed.get("nested"),
                         "forward_kinematics": timed.get("seconds", {}).get("forward_kinematics_n"),
                         "codegen_cpp": generated.get("seconds"), "load": timed["load"],
                         "error": timed.get("error") or generated.get("error")}
        row = result[label]
        print(f"| {label} | {row['nested']} | {_cell(row['jacobian'], 3)} | {_cell(row['forward_kinematics'], 3)} | "
              f"{_cell(row['codegen_cpp'])} | {row['load']:.1f} |" + _failure(row), flush=True)
    if result["puma560"]["jacobian"] and result["calibrated"]["jacobian"]:
        ratio = result["calibrated"]["jacobian"] / result["puma560"]["jacobian"]
        result["jacobian_ratio"] = ratio
        print(f"calibrated / textbook Jacobian: {ratio:.2f}")
    return result


def _long_table(written: Any, folder: Path, args: argparse.Namespace) -> dict[str, Any]:
    print("Long generic chains (goals: codegen cpp of 20 joints <= 10 s; Jacobian of 40 joints <= 30 s, <= 1 GB)")
    result: dict[str, Any] = {}
    size = 6 if args.quick else 20
    generated = _codegen(written(f"generic{size}", generic_chain(size)), folder / f"cpp{size}", args.runs)
    result[f"codegen_cpp_{size}"] = generated
    print(f"| figure | seconds | peak memory, MB | load |\n|---|---|---|---|\n"
          f"| codegen cpp, {size} joints | {_cell(generated.get('seconds'))} | - | {generated['load']:.1f} |"
          + _failure(generated), flush=True)
    if not args.quick:
        timed = _run(["--child", str(written("generic40", generic_chain(40))), "jacobian_0"], args.runs)
        result["jacobian_40"] = timed
        print(f"| Jacobian {{0}}, 40 joints | {_cell(timed.get('seconds', {}).get('jacobian_0'))} | "
              f"{_cell(timed.get('maxrss_mb'), 0)} | {timed['load']:.1f} |" + _failure(timed), flush=True)
    return result


def _growth_table(written: Any, args: argparse.Namespace) -> list[dict[str, Any]]:
    print("Growth, generic DH chains (s; k: exponent of t ~ n^k from the previous size; goal k <= 2)")
    print("| joints | Jacobian {0} | k | FK | k | peak memory, MB | load |\n|---|---|---|---|---|---|---|", flush=True)
    rows: list[dict[str, Any]] = []
    for n in (5, 10) if args.quick else (5, 10, 20, 40):
        timed = _run(["--child", str(written(f"generic{n}", generic_chain(n))), "jacobian_0"], args.runs)
        fk = _run(["--child", str(written(f"generic{n}", generic_chain(n))), "forward_kinematics_n"], args.runs)
        row = {"joints": n, "jacobian": timed.get("seconds", {}).get("jacobian_0"), "load": timed["load"],
               "forward_kinematics": fk.get("seconds", {}).get("forward_kinematics_n"),
               "maxrss_mb": timed.get("maxrss_mb")}
        for key in ("jacobian", "forward_kinematics"):
            before = rows[-1][key] if rows else None
            row[f"k_{key}"] = (math.log(row[key] / before) / math.log(n / rows[-1]["joints"])
                               if before and row[key] else None)
        rows.append(row)
        print(f"| {n} | {_cell(row['jacobian'])} | {_cell(row['k_jacobian'])} | {_cell(row['forward_kinematics'])} "
              f"| {_cell(row['k_forward_kinematics'])} | {_cell(row['maxrss_mb'], 0)} | {row['load']:.1f} |"
              + _failure(timed) + _failure(fk), flush=True)
    return rows


def _numbers(written: Any) -> dict[str, Any]:
    print("Numbers from the nested Jacobian (6-joint PoE arm, point tool, one configuration)")
    done = subprocess.run([sys.executable, __file__, "--numbers", str(written("poe6", poe_arm(6)))],
                          capture_output=True, text=True, check=False)
    if done.returncode:
        report = {"error": (done.stderr.strip().splitlines() or ["failed"])[-1]}
    else:
        report = json.loads(done.stdout.strip().splitlines()[-1])
    for key, value in report.items():
        print(f"{key}: {value:.3g}" if isinstance(value, float) else f"{key}: {value}")
    return report


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

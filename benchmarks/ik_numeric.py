r"""Numeric inverse-kinematics benchmark: ``python benchmarks/ik_numeric.py [ROBOT ...] [-n POSES]``.

For each robot (default: the Panda, the iiwa 7, a generic 7-joint chain, the PUMA 560 and the UR5) it draws ``POSES``
configurations uniformly within the joint limits (seeded, so every run sees the same poses) and takes their tool
poses from the compiled forward kinematics (:func:`symjac.codegen.numeric_model.numeric_model`). Each pose is solved
by one call from one random seed (the call's ``rng`` or ``seed`` is the pose's index; within the call the solver may
restart from further seeds drawn from it, as TRAC-IK does):

- ``python``: :func:`symjac.analysis.inverse_kinematics.numeric.solve_numeric` with ``restarts=1`` (the first
  solution found);
- ``c99``: the generated ``<robot>_inverse_kinematics_numeric`` (``ModuleRequest(..., numeric_ik=True)``), compiled
  with ``gcc -O2`` and timed in C by a small driver (no Python in the loop; processor time, the best of three runs,
  since the machine may be shared);
- ``cpp``: the generated header's ``inverse_kinematics_numeric`` (Eigen, ``g++ -O2``), timed the same way;
- ``ik_LM``: the Robotics Toolbox's Levenberg-Marquardt on its own model of the arm (DH models of the Panda, UR5 and
  PUMA, the URDF LBR for the iiwa, a DHRobot of the same generic chain), poses from its own forward kinematics at the
  same configurations, its defaults (tolerance 1e-6 on its error, symjac's is 1e-10 per norm).

It prints the success rate (every symjac solution checked against the pose to 1e-9 and within the limits),
mean iterations per call (all starts), mean starts and the time per solve. It asserts nothing, so it never flakes.
"""

from __future__ import annotations

import argparse
import ctypes
import math
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from symjac.analysis.inverse_kinematics import seed_bounds, solve_numeric
from symjac.codegen import ModuleRequest, describe, render_files
from symjac.codegen.numeric_model import numeric_model
from symjac.model.io import load_robot, robot_from_toml

DRIVER = r"""
#define _POSIX_C_SOURCE 199309L
#include <time.h>
#include "{robot}.h"

/* Solve count poses (16 entries each); returns the processor seconds it took (the machine may be shared). */
double sj_bench(const double *poses, int count, double *qs, int *found, int *iterations)
{{
    struct timespec begin, end;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &begin);
    for (int k = 0; k < count; k++) {{
        found[k] = {robot}_inverse_kinematics_numeric(poses + 16 * k, NULL, NULL, (unsigned long long)k,
                                                     qs + {n} * k, iterations + k, NULL, NULL);
    }}
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &end);
    return (double)(end.tv_sec - begin.tv_sec) + 1e-9 * (double)(end.tv_nsec - begin.tv_nsec);
}}
"""


CPP_DRIVER = r"""
#include <ctime>
#include "{robot}.hpp"

// Solve count poses (16 entries each, row-major); returns the processor seconds it took.
extern "C" double sj_bench(const double *poses, int count, double *qs, int *found, int *iterations)
{{
    using Matrix = Eigen::Matrix<double, 4, 4, Eigen::RowMajor>;
    const std::clock_t begin = std::clock();
    for (int k = 0; k < count; k++) {{
        const Eigen::Matrix4d pose = Eigen::Map<const Matrix>(poses + 16 * k);
        Eigen::Matrix<double, {n}, 1> q;
        found[k] = symjac::{robot}::inverse_kinematics_numeric<double>(pose, (unsigned long long)k, q,
                                                                        iterations + k);
        Eigen::Map<Eigen::Matrix<double, {n}, 1>>(qs + {n} * k) = q;
    }}
    return double(std::clock() - begin) / CLOCKS_PER_SEC;
}}
"""


def generic_dh(n: int = 7, seed: int = 41) -> list[tuple[float, float, float]]:
    """Standard-DH (alpha, a, d) of an ``n``-joint chain: twists in (-pi, pi), a in (0.05, 0.3), d in (-0.1, 0.1)."""
    rng = np.random.default_rng(seed + 1000 + n)
    rows = [(rng.uniform(-math.pi, math.pi), rng.uniform(0.05, 0.3), rng.uniform(-0.1, 0.1)) for _ in range(n)]
    return [(round(alpha, 12), round(a, 12), round(d, 12)) for alpha, a, d in rows]


def generic_chain(n: int = 7, seed: int = 41) -> str:
    """The TOML text of :func:`generic_dh`'s chain, every joint limited to +-170 degrees."""
    lines = [f'name = "generic{n}"', f'description = "generic DH chain, {n} joints, seed {seed}"',
             'convention = "standard"', ""]
    for alpha, a, d in generic_dh(n, seed):
        lines += ["[[joints]]", 'type = "revolute"', f"alpha = {alpha:.12f}", f"a = {a:.12f}", f"d = {d:.12f}",
                  "limits = [-2.967, 2.967]", ""]
    return "\n".join(lines)


def _robot(name: str):
    return robot_from_toml(generic_chain(), "generic7") if name == "generic7" else load_robot(name)


def _compiled_solver(robot, folder: Path, target: str):
    """The generated solver of ``target`` (c99 or cpp) with a driver that times it, compiled: its ``sj_bench``."""
    files = render_files(describe(ModuleRequest(robot, target, numeric_ik=True)))
    for file, text in files.items():
        (folder / file).write_text(text)
    if target == "c99":
        (folder / "driver.c").write_text(DRIVER.format(robot=robot.name, n=robot.n_joints))
        source = next(file for file in files if file.endswith(".c"))
        command = ["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", source, "driver.c", "-lm"]
    else:
        (folder / "driver.cpp").write_text(CPP_DRIVER.format(robot=robot.name, n=robot.n_joints))
        command = ["g++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "-O2", "-I/usr/include/eigen3", "driver.cpp"]
    subprocess.run([*command, "-fPIC", "-shared", "-o", f"lib{target}.so"], cwd=folder, check=True,
                   capture_output=True)
    bench = ctypes.CDLL(str(folder / f"lib{target}.so")).sj_bench
    bench.restype = ctypes.c_double
    return bench


def _toolbox(name: str, robot):
    """The Robotics Toolbox's model of the arm, or None (not installed, or no model of it)."""
    try:
        import roboticstoolbox as rtb
    except ImportError:
        return None
    if name == "generic7":
        links = [rtb.RevoluteDH(d=d, a=a, alpha=alpha, qlim=[-2.967, 2.967]) for alpha, a, d in generic_dh()]
        return rtb.DHRobot(links, name="generic7")
    factories = {"panda": lambda: rtb.models.DH.Panda(), "iiwa7": lambda: rtb.models.LBR(),
                 "puma560": lambda: rtb.models.DH.Puma560(), "ur5": lambda: rtb.models.DH.UR5()}
    try:
        return factories[name]() if name in factories else None
    except Exception:  # a model that needs a download
        return None


def _row(name: str, mode: str, success: float, iterations: float, starts: float, seconds: float) -> None:
    print(f"{name:9} {mode:7} {100 * success:8.1f}% {iterations:10.1f} {starts:7.2f} {1e6 * seconds:11.1f}")


def main() -> None:
    """Solve the poses of each robot with each solver and print one row per robot and solver."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["panda", "iiwa7", "generic7", "puma560", "ur5"])
    parser.add_argument("-n", "--poses", type=int, default=500)
    parser.add_argument("--no-toolbox", action="store_true", help="leave the Robotics Toolbox out")
    arguments = parser.parse_args()
    print(f"{'robot':9} {'solver':7} {'success':>9} {'iterations':>10} {'starts':>7} {'us/solve':>11}")
    for name in arguments.robots:
        robot = _robot(name)
        model = numeric_model(robot)
        lower, upper = seed_bounds(robot)
        generator = np.random.default_rng(2026)
        configurations = [generator.uniform(lower, upper) for _ in range(arguments.poses)]
        poses = [np.asarray(model.fk(q), dtype=float) for q in configurations]

        def good(q: np.ndarray, pose: np.ndarray, model=model, lower=lower, upper=upper) -> bool:
            return bool(np.abs(np.asarray(model.fk(q)) - pose).max() < 1e-9
                        and np.all(q >= lower - 1e-12) and np.all(q <= upper + 1e-12))

        start = time.perf_counter()
        results = [solve_numeric(robot, pose, model, rng=k, restarts=1) for k, pose in enumerate(poses)]
        elapsed = (time.perf_counter() - start) / len(poses)
        solved = sum(bool(s) and good(s[0].q, pose) for s, pose in zip(results, poses, strict=True))
        _row(name, "python", solved / len(poses), np.mean([s[0].iterations for s in results if s] or [0]),
             np.mean([s[0].start + 1 for s in results if s] or [0]), elapsed)

        for target in ("c99", "cpp"):
            with tempfile.TemporaryDirectory() as folder:
                bench = _compiled_solver(robot, Path(folder), target)
                flat = np.ascontiguousarray(np.stack(poses), dtype=float)
                qs, found = np.zeros((len(poses), robot.n_joints)), np.zeros(len(poses), dtype=np.int32)
                steps = np.zeros(len(poses), dtype=np.int32)
                pointer = ctypes.POINTER(ctypes.c_double)
                seconds = min(bench(flat.ctypes.data_as(pointer), len(poses), qs.ctypes.data_as(pointer),
                                    found.ctypes.data_as(ctypes.POINTER(ctypes.c_int)),
                                    steps.ctypes.data_as(ctypes.POINTER(ctypes.c_int))) for _ in range(3))
            solved = sum(bool(f) and good(q, pose) for f, q, pose in zip(found, qs, poses, strict=True))
            _row(name, target, solved / len(poses), float(steps.mean()), math.nan, seconds / len(poses))

        toolbox = None if arguments.no_toolbox else _toolbox(name, robot)
        if toolbox is not None:
            low, high = toolbox.qlim
            rtb_poses = [toolbox.fkine(low + (high - low) * np.random.default_rng(k).random(toolbox.n))
                         for k in range(len(poses))]
            np.random.seed(2026)  # ik_LM draws restarts from NumPy's global state
            start = time.perf_counter()
            answers = [toolbox.ik_LM(pose) for pose in rtb_poses]
            elapsed = (time.perf_counter() - start) / len(poses)
            _row(name, "ik_LM", np.mean([a.success for a in answers]), np.mean([a.iterations for a in answers]),
                 np.mean([a.searches for a in answers]), elapsed)


if __name__ == "__main__":
    main()

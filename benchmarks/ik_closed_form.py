r"""Closed-form inverse kinematics benchmark: ``python benchmarks/ik_closed_form.py [ROBOT ...] [-n POSES]``.

For each robot (default: the PUMA 560 and the UR5) it draws ``POSES`` configurations uniformly within the joint
limits (seeded, so every run sees the same poses), takes their tool poses from the compiled forward kinematics and
solves every pose for all its solutions with:

- the generated C++ (``symjac codegen --target cpp --inverse-kinematics``), compiled with ``g++ -O2`` into one
  program that times a loop over the poses (no Python in the loop; the best of 25 short rounds);
- the numpy target's ``inverse_kinematics`` on the whole batch, and :meth:`NumericModel.ik
  <symjac.codegen.numeric_model.NumericModel.ik>` on the batch and on one pose at a time;
- EAIK (PyPI ``EAIK``, subproblem decomposition after IK-Geo) on the same arm from its standard DH parameters, one
  pose per call and batched on one thread, when it is installed and knows the robot.

It prints the time per pose, the mean number of solutions, the largest FK(q) - pose error of the solutions (for the
generated ones) and on how many poses the counts agree with EAIK's. It asserts nothing, so it never flakes.
"""

from __future__ import annotations

import argparse
import importlib.util
import shutil
import subprocess
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from symjac.analysis.inverse_kinematics import seed_bounds
from symjac.codegen.module import ModuleRequest, describe, render_files
from symjac.codegen.numeric_model import numeric_model
from symjac.model.io import load_robot

EAIK_DH = {  # standard DH (alpha, a, d) of the same arms, for EAIK's DhRobot
    "puma560": ([np.pi / 2, 0.0, -np.pi / 2, np.pi / 2, -np.pi / 2, 0.0], [0.0, 0.4318, 0.0203, 0.0, 0.0, 0.0],
                [0.0, 0.0, 0.15005, 0.4318, 0.0, 0.0]),
    "ur5": ([np.pi / 2, 0.0, 0.0, np.pi / 2, -np.pi / 2, 0.0], [0.0, -0.425, -0.39225, 0.0, 0.0, 0.0],
            [0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823]),
}

PROGRAM = """#include "{robot}.hpp"
#include <chrono>
#include <cstdio>
#include <fstream>
#include <vector>
int main(int argc, char** argv)
{{
    (void)argc;
    using namespace symjac::{robot};
    std::ifstream file(argv[1], std::ios::binary);
    std::vector<double> data(std::stoul(argv[2]) * 16);
    file.read(reinterpret_cast<char*>(data.data()), static_cast<std::streamsize>(data.size() * sizeof(double)));
    std::vector<Eigen::Matrix4d> poses;
    for (std::size_t k = 0; k < data.size() / 16; ++k) {{
        poses.push_back(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(&data[16 * k]));
    }}
    std::array<Eigen::Matrix<double, {n}, 1>, ik_max_solutions> solutions;
    std::array<int, ik_max_solutions> branches;
    std::FILE* out = std::fopen(argv[3], "wb");
    for (const auto& pose : poses) {{  // the solutions once, for the check
        const int count = inverse_kinematics(pose, solutions, branches);
        double row[ik_max_solutions * {n} + 1] = {{static_cast<double>(count)}};
        for (int k = 0; k < count; ++k) {{
            for (int i = 0; i < {n}; ++i) {{
                row[1 + k * {n} + i] = solutions[k](i);
            }}
        }}
        std::fwrite(row, sizeof(double), ik_max_solutions * {n} + 1, out);
    }}
    std::fclose(out);
    const long repeats = std::stol(argv[4]);
    double checksum = 0.0, best = 1e300;
    long total = 0;
    for (int round = 0; round < 25; ++round) {{  // the best of 25 short rounds: the machine may be shared
        const auto start = std::chrono::steady_clock::now();
        for (long r = 0; r < repeats; ++r) {{
            for (const auto& pose : poses) {{
                const int count = inverse_kinematics(pose, solutions, branches);
                total += count;
                checksum += solutions[0](0);
            }}
        }}
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        best = seconds < best ? seconds : best;
    }}
    std::printf("%.6g %ld %.6g\\n", 1e9 * best / (repeats * poses.size()), total, checksum);
    return 0;
}}
"""


def _timed(function: Callable[[], object], seconds: float) -> float:
    """Seconds per call of ``function``: repeated until ``seconds`` have passed (the best of three rounds)."""
    best = float("inf")
    for _ in range(3):
        calls, start = 0, time.perf_counter()
        while True:
            function()
            calls += 1
            elapsed = time.perf_counter() - start
            if elapsed >= seconds / 3:
                break
        best = min(best, elapsed / calls)
    return best


def _cpp(robot, poses: np.ndarray, folder: Path, repeats: int) -> tuple[float, list[np.ndarray]] | None:
    """The generated C++ in a compiled loop: nanoseconds per pose and each pose's solutions."""
    if shutil.which("g++") is None or not Path("/usr/include/eigen3/Eigen/Dense").is_file():
        return None
    (name, text), = render_files(describe(ModuleRequest(robot, "cpp", inverse_kinematics=True))).items()
    (folder / name).write_text(text)
    n = robot.n_joints
    (folder / "bench.cpp").write_text(PROGRAM.format(robot=robot.name, n=n))
    subprocess.run(["g++", "-std=c++17", "-O2", "-I/usr/include/eigen3", "bench.cpp", "-o", "bench"], cwd=folder,
                   check=True)
    np.ascontiguousarray(poses, dtype=float).tofile(folder / "poses.bin")
    result = subprocess.run([str(folder / "bench"), "poses.bin", str(len(poses)), "solutions.bin", str(repeats)],
                            cwd=folder, check=True, capture_output=True, text=True)
    rows = np.fromfile(folder / "solutions.bin").reshape(len(poses), -1)
    found = [row[1:1 + int(row[0]) * n].reshape(-1, n) for row in rows]
    return float(result.stdout.split()[0]), found


def _module(robot, target: str, folder: Path):
    (name, text), = render_files(describe(ModuleRequest(robot, target, inverse_kinematics=True))).items()
    path = folder / f"{target}_{name}"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location(f"bench_{target}_{robot.name}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _eaik(name: str, q: np.ndarray, seconds: float) -> tuple[float, float, list[int]] | None:
    """EAIK on the same configurations' poses (its own FK): us per pose one by one, batched, and the counts."""
    if name not in EAIK_DH or importlib.util.find_spec("eaik") is None:
        return None
    from eaik.IK_DH import DhRobot

    alpha, a, d = (np.array(v) for v in EAIK_DH[name])
    robot = DhRobot(alpha, a, d)
    poses = [robot.fwdKin(row) for row in q]
    counts = [int(np.sum(~np.asarray(robot.IK(pose).is_LS, dtype=bool))) for pose in poses]
    single = _timed(lambda: [robot.IK(pose) for pose in poses], seconds) / len(poses)
    batched = _timed(lambda: robot.IK_batched(poses, 1), seconds) / len(poses)
    return 1e6 * single, 1e6 * batched, counts


def _error(model, found: list[np.ndarray], poses: np.ndarray) -> float:
    errors = [np.abs(model.fk(rows) - pose).max() for rows, pose in zip(found, poses, strict=True) if len(rows)]
    return float(max(errors, default=0.0))


def main() -> None:
    """Solve the poses of each robot with every solver and print one row per robot and solver."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["puma560", "ur5"])
    parser.add_argument("-n", "--poses", type=int, default=2000)
    parser.add_argument("--seconds", type=float, default=1.0, help="time per measurement from Python")
    parser.add_argument("--repeats", type=int, default=3, help="passes over the poses per round of the C++ loop")
    arguments = parser.parse_args()
    print(f"{'robot':8} {'solver':26} {'us/pose':>9} {'solutions':>9} {'max error':>10} {'counts = EAIK':>13}")
    for name in arguments.robots:
        _robot(name, arguments.poses, arguments.seconds, arguments.repeats)


def _robot(name: str, count: int, seconds: float, repeats: int) -> None:
    """One robot's rows: every solver on the same poses."""
    robot = load_robot(name)
    model = numeric_model(robot)
    lower, upper = seed_bounds(robot)
    q = np.random.default_rng(2026).uniform(lower, upper, (count, robot.n_joints))
    poses = np.asarray(model.fk(q))
    eaik = _eaik(name, q, seconds)
    rows: list[tuple[str, float, list[np.ndarray]]] = []
    with tempfile.TemporaryDirectory() as temporary:
        folder = Path(temporary)
        cpp = _cpp(robot, poses, folder, repeats)
        if cpp is not None:
            rows.append(("generated C++ (loop)", cpp[0] / 1e3, cpp[1]))
        numpy_module = _module(robot, "numpy", folder)
        solutions, counts, _ = numpy_module.inverse_kinematics(poses)
        found = [s[:k] for s, k in zip(solutions, counts, strict=True)]
        rows.append(("numpy target, batch", 1e6 * _timed(lambda: numpy_module.inverse_kinematics(poses), seconds)
                     / len(poses), found))
    solutions, counts, _ = model.ik(poses)
    found = [s[:k] for s, k in zip(solutions, counts, strict=True)]
    rows.append((f"NumericModel.ik ({model.backend}), batch",
                 1e6 * _timed(lambda: model.ik(poses), seconds) / len(poses), found))
    few = poses[:50]
    rows.append((f"NumericModel.ik ({model.backend}), one",
                 1e6 * _timed(lambda: [model.ik(p) for p in few], seconds) / len(few), found))
    for label, per_pose, solved in rows:
        agree = "" if eaik is None else f"{sum(len(f) == c for f, c in zip(solved, eaik[2], strict=True))}/{count}"
        print(f"{name:8} {label:26} {per_pose:9.3f} {np.mean([len(f) for f in solved]):9.2f} "
              f"{_error(model, solved, poses):10.2e} {agree:>13}")
    if eaik is not None:
        print(f"{name:8} {'EAIK, one pose per call':26} {eaik[0]:9.3f} {np.mean(eaik[2]):9.2f}")
        print(f"{name:8} {'EAIK, batched (1 thread)':26} {eaik[1]:9.3f} {np.mean(eaik[2]):9.2f}")

if __name__ == "__main__":
    main()

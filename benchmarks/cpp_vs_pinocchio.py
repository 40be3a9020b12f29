"""Generated C and C++ against pinocchio, in one binary: ``python benchmarks/cpp_vs_pinocchio.py [ROBOT ...]``.

For each robot (default: puma560 and panda; modified DH, revolute joints) it generates the ``cpp`` header and the
``c99`` pair of the Jacobian in frame {0} at the wrist, builds the same chain as a pinocchio model (one ``JointModelRZ``
per joint, placed by symjac's own link transform at zero angle: for modified DH, ``Rx Tx Rz(offset) Tz`` commutes
with the joint's rotation), and times in one C++ program compiled with ``-O2``:

* pinocchio's ``computeFrameJacobian`` (``LOCAL_WORLD_ALIGNED``, at the last joint's origin), which also runs the
  forward kinematics it needs;
* the ``cpp`` target's ``jacobian<double>(q)`` and the ``c99`` target's ``<robot>_jacobian(q, NULL, J)``;
* the sines and cosines of the joint angles alone, the floor of any closed form.

Each figure is the best of seven runs of a million calls with a changing ``q``; the program first checks that the
three Jacobians agree. It also times compiling the header alone with ``-O2``. Pinocchio comes from PyPI (``pin``,
part of the test extra); without it the pinocchio column says so. It prints a Markdown table and asserts nothing.
"""

from __future__ import annotations

import argparse
import math
import shutil
import site
import subprocess
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path

import sympy as sp

from symjac import load_robot
from symjac.codegen import ModuleRequest, describe, render_files
from symjac.kinematics.chain import Chain
from symjac.model.robot import Convention, Robot

__all__ = ["main", "placements"]

EIGEN = "/usr/include/eigen3"

DRIVER = """
#include <chrono>
#include <cmath>
#include <cstdio>
{pinocchio_include}
#include "{robot}.hpp"
#include "{robot}.h"

constexpr int N = {n};
constexpr int CALLS = 1000000;
using Clock = std::chrono::steady_clock;

template <class F>
static double best_ns(F f)
{{
    double best = 1e300;
    for (int run = 0; run < 7; run++) {{
        const auto start = Clock::now();
        for (int k = 0; k < CALLS; k++) {{
            f(k);
        }}
        best = std::min(best, std::chrono::duration<double, std::nano>(Clock::now() - start).count() / CALLS);
    }}
    return best;
}}

int main()
{{
    Eigen::Matrix<double, N, 1> q;
    for (int k = 0; k < N; k++) {{
        q(k) = 0.3 + 0.2 * k;
    }}
    volatile double sink = 0;
    double J99[6 * N];
    const Eigen::Matrix<double, 6, N> Jcpp = symjac::{robot}::jacobian(q);
    {robot}_jacobian(q.data(), nullptr, J99);
    double differs = 0;
    for (int i = 0; i < 6; i++) {{
        for (int j = 0; j < N; j++) {{
            differs = std::max(differs, std::abs(Jcpp(i, j) - J99[i * N + j]));
        }}
    }}
{pinocchio_setup}
    const double cpp = best_ns([&](int k) {{
        q(0) += 1e-12 * (k & 1 ? 1 : -1);
        const Eigen::Matrix<double, 6, N> J = symjac::{robot}::jacobian(q);
        sink = sink + J(0, 0) + J(5, N - 1);
    }});
    const double c99 = best_ns([&](int k) {{
        q(0) += 1e-12 * (k & 1 ? 1 : -1);
        {robot}_jacobian(q.data(), nullptr, J99);
        sink = sink + J99[0] + J99[6 * N - 1];
    }});
    const double sincos = best_ns([&](int k) {{
        q(0) += 1e-12 * (k & 1 ? 1 : -1);
        double sum = 0;
        for (int j = 0; j < N; j++) {{
            sum += std::sin(q(j)) + std::cos(q(j));
        }}
        sink = sink + sum;
    }});
{pinocchio_timing}
    std::printf("agree %.3e\\npinocchio %.2f\\ncpp %.2f\\nc99 %.2f\\nsincos %.2f\\n", differs, pin, cpp, c99, sincos);
    return 0;
}}
"""

PINOCCHIO_SETUP = """
    pinocchio::Model model;
    pinocchio::JointIndex parent = 0;
{joints}
    const pinocchio::FrameIndex tip = model.addFrame(
        pinocchio::Frame("tip", parent, pinocchio::SE3::Identity(), pinocchio::OP_FRAME));
    pinocchio::Data data(model);
    Eigen::Matrix<double, 6, Eigen::Dynamic> Jpin = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, N);
    pinocchio::computeFrameJacobian(model, data, q, tip, pinocchio::LOCAL_WORLD_ALIGNED, Jpin);
    for (int i = 0; i < 6; i++) {
        for (int j = 0; j < N; j++) {
            differs = std::max(differs, std::abs(Jpin(i, j) - Jcpp(i, j)));
        }
    }
"""

PINOCCHIO_TIMING = """
    const double pin = best_ns([&](int k) {
        q(0) += 1e-12 * (k & 1 ? 1 : -1);
        pinocchio::computeFrameJacobian(model, data, q, tip, pinocchio::LOCAL_WORLD_ALIGNED, Jpin);
        sink = sink + Jpin(0, 0) + Jpin(5, N - 1);
    });
"""


def placements(robot: Robot) -> list[tuple[tuple[float, ...], tuple[float, ...]]]:
    """Each joint's placement in its parent as (row-major rotation, translation): the link transform at zero angle."""
    if robot.convention != Convention.MODIFIED or not all(joint.is_revolute for joint in robot.joints):
        raise SystemExit(f"{robot.name}: this benchmark builds modified-DH chains of revolute joints only")
    chain = Chain(robot)
    zero = {**robot.defaults, **dict.fromkeys(robot.q, 0)}
    found = []
    for i in range(1, robot.n_joints + 1):
        T = sp.Matrix(chain.transform(i - 1, i)).subs(zero).evalf()
        found.append((tuple(float(T[r, c]) for r in range(3) for c in range(3)),
                      tuple(float(T[r, 3]) for r in range(3))))
    return found


def pinocchio_prefix() -> Path | None:
    for folder in site.getsitepackages():
        prefix = Path(folder) / "cmeel.prefix"
        if (prefix / "include" / "pinocchio").is_dir():
            return prefix
    return None


def measure(name: str, folder: Path) -> dict[str, float]:
    """Generate, compile and run the driver for one robot; its figures in nanoseconds (and compile seconds)."""
    robot = load_robot(name)
    files = {**render_files(describe(ModuleRequest(robot, "cpp"))),
             **render_files(describe(ModuleRequest(robot, "c99")))}
    for file_name, text in files.items():
        (folder / file_name).write_text(text)
    prefix = pinocchio_prefix()
    joints = "\n".join(
        f"    parent = model.addJoint(parent, pinocchio::JointModelRZ(), pinocchio::SE3((Eigen::Matrix3d() << "
        f"{', '.join(map(repr, rotation))}).finished(), Eigen::Vector3d({', '.join(map(repr, translation))})), "
        f'"joint{k}");' for k, (rotation, translation) in enumerate(placements(robot), start=1))
    driver = DRIVER.format(
        robot=robot.name, n=robot.n_coordinates,
        pinocchio_include="#include <pinocchio/multibody.hpp>\n#include <pinocchio/algorithm/frames.hpp>" if prefix
        else "#include <Eigen/Dense>",
        pinocchio_setup=PINOCCHIO_SETUP.replace("{joints}", joints) if prefix else "",
        pinocchio_timing=PINOCCHIO_TIMING if prefix else "    const double pin = std::nan(\"\");")
    (folder / "driver.cpp").write_text(driver)
    (folder / "header_only.cpp").write_text(
        f'#include "{robot.name}.hpp"\ntemplate Eigen::Matrix<double, 6, {robot.n_coordinates}> '
        f"symjac::{robot.name}::jacobian<double>(const Eigen::Matrix<double, {robot.n_coordinates}, 1>&, "
        f"const symjac::{robot.name}::Params<double>&);\n")
    start = time.perf_counter()
    subprocess.run(["g++", "-std=c++17", "-O2", f"-I{EIGEN}", "-c", "header_only.cpp"], cwd=folder, check=True)
    compile_seconds = time.perf_counter() - start
    subprocess.run(["gcc", "-std=c99", "-O2", "-c", f"{robot.name}.c", "-o", "c99.o"], cwd=folder, check=True)
    flags = ["-std=c++17", "-O2", f"-I{EIGEN}", "-I."]
    if prefix:
        flags += ["-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS", "-DBOOST_MPL_LIMIT_LIST_SIZE=30",
                  "-DBOOST_MPL_LIMIT_VECTOR_SIZE=30", f"-I{prefix / 'include'}", f"-L{prefix / 'lib'}",
                  f"-Wl,-rpath,{prefix / 'lib'}"]
    libraries = ["-lpinocchio_default"] if prefix else []
    subprocess.run(["g++", *flags, "driver.cpp", "c99.o", "-o", "driver", *libraries, "-lm"], cwd=folder, check=True)
    output = subprocess.run([str(folder / "driver")], check=True, capture_output=True, text=True).stdout
    figures = {key: float(value) for key, value in (line.split() for line in output.splitlines())}
    figures["compile"] = compile_seconds
    return figures


def main(argv: Sequence[str] | None = None) -> int:
    """Print the table: ns per Jacobian call for pinocchio, cpp, c99 and the sines and cosines alone, with ratios."""
    parser = argparse.ArgumentParser(prog="python benchmarks/cpp_vs_pinocchio.py", description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["puma560", "panda"], help="catalog names (modified DH)")
    args = parser.parse_args(argv)
    if shutil.which("g++") is None:
        raise SystemExit("g++ is needed (Debian: apt-get install g++ libeigen3-dev)")
    if pinocchio_prefix() is None:
        print("pinocchio (PyPI 'pin') is not installed: its column is skipped")
    print("| robot | pinocchio ns | cpp ns | c99 ns | sin+cos ns | pinocchio / cpp | cpp / sin+cos | header -O2 s |"
          "\n|---|---|---|---|---|---|---|---|")
    for name in args.robots:
        with tempfile.TemporaryDirectory() as folder:
            f = measure(name, Path(folder))
        if f["agree"] > 1e-9:
            raise SystemExit(f"{name}: the Jacobians disagree by {f['agree']:.2e}")
        ratio = "-" if math.isnan(f["pinocchio"]) else f"{f['pinocchio'] / f['cpp']:.1f}"
        print(f"| {name} | {f['pinocchio']:.0f} | {f['cpp']:.0f} | {f['c99']:.0f} | {f['sincos']:.0f} | {ratio} | "
              f"{f['cpp'] / f['sincos']:.2f} | {f['compile']:.1f} |", flush=True)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

r"""Generated dynamics against pinocchio, in one C++ binary: ``python benchmarks/dynamics_vs_pinocchio.py [ROBOT ...]``.

For the PUMA 560 (the catalog's, modified DH, with the inertial data of Armstrong, Khatib and Burdick its file
carries), the UR5 and the Panda (example-robot-data's URDFs
with their own inertial data), symjac lowers inverse dynamics, the mass matrix, the bias forces
:math:`C\dot q + g`, the gravity torques and the Coriolis matrix (:mod:`symjac.codegen.dynamics`), and this script
prints each as a plain C function with the project's C printer (one ``sin`` and one ``cos`` per joint, the CSE
temporaries, the outputs); forward dynamics is :math:`M^{-1}(\tau - b)` by a Cholesky solve of the generated M.
The same binary also links what users get: the ``c99`` target's source and header and the ``cpp`` target's header
(``--dynamics``, the same strategy; their gravity is the parameter ``g`` at its default 9.81, their own
``forward_dynamics``: the c99 one's Cholesky in C, the cpp one's Eigen's ``LLT``).
Pinocchio gets the same model: for the PUMA built joint by joint from symjac's link transforms and inertial data; for
the URDF arms read from the file, with the joints off symjac's chain (the Panda's fingers) locked by
``buildReducedModel``, their bodies lumped into the hand by both libraries.

The program first checks that every symjac function (plain C, c99, cpp) agrees with pinocchio's (``rnea``, ``crba``,
``computeGeneralizedGravity``, ``rnea`` with zero acceleration, ``computeCoriolisMatrix``, ``aba``) to 1e-9
relative at random states, then times each: the best of five runs of a million calls with a changing ``q``
(``-O2``; every output of symjac's functions passes an empty ``asm`` barrier, so none is dropped). It prints ns
per call, pinocchio / symjac per column, and the multiplications and additions of each plain C function
(after CSE; a subtraction counts as an addition, a negation as nothing). It asserts nothing.
"""

from __future__ import annotations

import argparse
import dataclasses
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from importlib import metadata
from pathlib import Path

import sympy as sp
from cpp_vs_pinocchio import pinocchio_prefix

from symjac import load_robot
from symjac.analysis.dynamics import EARTH
from symjac.codegen import ModuleRequest, describe, render_files
from symjac.codegen.backends.c.printer import CPrinter
from symjac.codegen.dynamics import (
    lowered_bias_forces,
    lowered_coriolis_matrix,
    lowered_gravity_torques,
    lowered_inverse_dynamics,
    lowered_mass_matrix,
    numeric_gravity,
)
from symjac.codegen.lower import LoweredFunction
from symjac.kinematics.chain import Chain
from symjac.model.robot import Robot
from symjac.symbolic.dag import distinct_nodes

__all__ = ["FUNCTIONS", "main", "operations", "puma560_akb"]

EIGEN = "/usr/include/eigen3"
URDF = {"ur5": ("ur_description/urdf/ur5_robot.urdf", "tool0"),
        "panda": ("panda_description/urdf/panda.urdf", "panda_link8")}

FUNCTIONS: dict[str, Callable[..., LoweredFunction]] = {
    "tau": lowered_inverse_dynamics, "M": lowered_mass_matrix, "g": lowered_gravity_torques,
    "b": lowered_bias_forces, "C": lowered_coriolis_matrix,
}

def puma560_akb() -> Robot:
    """The catalog PUMA 560, which carries Armstrong, Khatib and Burdick's inertial data (its file cites them).

    Its rigid bodies only: the file's motor data (armature, friction) are left out, as pinocchio's model here has none.
    """
    return dataclasses.replace(load_robot("puma560"), drives=())


def operations(lowered: LoweredFunction) -> tuple[int, int]:
    """Multiplications and additions of a lowered function (distinct subexpressions; x*x counts one)."""
    exprs = [e for _, e in lowered.temporaries] + list(lowered.outputs)
    mul = add = 0
    for node in distinct_nodes(exprs):
        if node.is_Add:
            add += len(node.args) - 1
        elif node.is_Mul:
            factors = [a for a in node.args if a not in (-1, sp.S.NegativeOne)]
            mul += len(factors) - 1
        elif node.is_Pow and node.exp.is_Integer:
            mul += abs(int(node.exp)) - 1 + (1 if node.exp < 0 else 0)
    return mul, add


def _example_robots() -> Path:
    files = metadata.distribution("example-robot-data").files or []
    marker = next(f for f in files if str(f).endswith("share/example-robot-data/package.xml"))
    return Path(str(marker.locate())).parent / "robots"


def arm(name: str):  # -> (Robot, pinocchio.Model)
    """The symjac robot and the pinocchio model with the same joints, geometry and inertial data."""
    import numpy as np
    import pinocchio as pin

    if name == "puma560":
        robot = puma560_akb()
        chain = Chain(robot)
        numbers = {**robot.defaults, **dict.fromkeys(robot.q, 0)}
        model = pin.Model()
        for k, body in enumerate(robot.inertials, start=1):
            T = np.array(sp.Matrix(chain.transform(k - 1, k)).subs(numbers).evalf(), dtype=float)
            joint = model.addJoint(k - 1, pin.JointModelRZ(), pin.SE3(T[:3, :3], T[:3, 3]), f"joint{k}")
            model.appendBodyToJoint(joint, pin.Inertia(float(body.mass), np.array(body.com, dtype=float),
                                                       np.array(body.inertia, dtype=float)), pin.SE3.Identity())
        return robot, model
    path, tip = URDF[name]
    file = str(_example_robots() / path)
    robot = load_robot(file, tip_link=tip)
    full = pin.buildModelFromUrdf(file)
    chain_ids = [full.getJointId(joint.name) for joint in robot.joints]
    others = [i for i in range(1, full.njoints) if i not in chain_ids]  # held at zero, their bodies lumped
    model = pin.buildReducedModel(full, others, pin.neutral(full)) if others else full
    if [model.joints[model.getJointId(j.name)].idx_q for j in robot.joints] != list(range(robot.n_joints)):
        raise SystemExit(f"{name}: pinocchio orders the joints differently")
    return robot, model


def _model_code(model) -> str:
    """C++ statements building ``model`` (joint types, placements, inertias) with pinocchio's API."""
    lines = ["    pinocchio::Model model;"]
    for i in range(1, model.njoints):
        kind = model.joints[i].shortname()
        if kind not in ("JointModelRX", "JointModelRY", "JointModelRZ"):
            raise SystemExit(f"joint type {kind} is not handled by this benchmark")
        place, body = model.jointPlacements[i], model.inertias[i]
        R = ", ".join(repr(float(v)) for v in place.rotation.flatten())
        t = ", ".join(repr(float(v)) for v in place.translation)
        c = ", ".join(repr(float(v)) for v in body.lever)
        J = ", ".join(repr(float(v)) for v in body.inertia.flatten())
        lines.append(f"    model.addJoint({model.parents[i]}, pinocchio::{kind}(), pinocchio::SE3("
                     f"(Eigen::Matrix3d() << {R}).finished(), Eigen::Vector3d({t})), \"j{i}\");")
        lines.append(f"    model.appendBodyToJoint({i}, pinocchio::Inertia({float(body.mass)!r}, Eigen::Vector3d({c}), "
                     f"(Eigen::Matrix3d() << {J}).finished()), pinocchio::SE3::Identity());")
    return "\n".join(lines)


def c_function(name: str, lowered: LoweredFunction, robot: Robot) -> str:
    """``static void name(q, qdot, qddot, params, out)``: the lowered function as C statements."""
    names: dict[sp.Symbol, str] = {}
    arrays = {"q": "q", "qdot": "qdot", "qddot": "qddot"}
    for argument, symbols in lowered.inputs:
        names.update({s: f"{arrays[argument]}[{k}]" for k, s in enumerate(symbols)})
    used = lowered.used_symbols
    parameters = [(k, p) for k, p in enumerate(robot.parameter_symbols) if p in used]
    names.update({p: f"p_{p.name}" for _, p in parameters})
    for sine, cosine, _ in lowered.angles:
        names[sine], names[cosine] = sine.name.removeprefix("_"), cosine.name.removeprefix("_")
    for k, (symbol, _) in enumerate(lowered.temporaries):
        names[symbol] = f"x{k}"
    printer = CPrinter(names)
    body = [f"    const double p_{p.name} = params[{k}];" for k, p in parameters]
    for sine, cosine, angle in lowered.angles:
        argument = printer.doprint(angle)
        body.append(f"    const double {names[sine]} = sin({argument}), {names[cosine]} = cos({argument});")
    body += [f"    const double {names[s]} = {printer.doprint(e)};" for s, e in lowered.temporaries]
    body += [f"    out[{k}] = {printer.doprint(e)};" for k, e in enumerate(lowered.outputs)]
    return (f"static void {name}(const double* q, const double* qdot, const double* qddot, const double* params, "
            f"double* out)\n{{\n    (void)q; (void)qdot; (void)qddot; (void)params;\n" + "\n".join(body) + "\n}\n")


DRIVER = r"""
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <pinocchio/multibody.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/algorithm/crba.hpp>
#include <pinocchio/algorithm/aba.hpp>
#include "@ROBOT@.h"
#include "@ROBOT@.hpp"

constexpr int N = @N@;
constexpr int CALLS = 1000000;
using Clock = std::chrono::steady_clock;
using Vector = Eigen::Matrix<double, N, 1>;
namespace cpp = symjac::@ROBOT@;

// Every output of every implementation reaches memory: the compiler may not drop the ones the timing loop ignores.
static inline void escape(void* p) { asm volatile("" : : "g"(p) : "memory"); }

@FUNCTIONS@

static void forward_dynamics(const double* q, const double* qdot, const double* tau, const double* params,
                             double* qddot)
{
    double M[N * N], b[N], L[N * N];
    symjac_M(q, nullptr, nullptr, params, M);
    symjac_b(q, qdot, nullptr, params, b);
    for (int j = 0; j < N; j++) {
        double d = M[j * N + j];
        for (int k = 0; k < j; k++) d -= L[j * N + k] * L[j * N + k];
        const double root = std::sqrt(d), inverse = 1.0 / root;
        L[j * N + j] = root;
        for (int i = j + 1; i < N; i++) {
            double s = M[i * N + j];
            for (int k = 0; k < j; k++) s -= L[i * N + k] * L[j * N + k];
            L[i * N + j] = s * inverse;
        }
    }
    double y[N];
    for (int i = 0; i < N; i++) {
        double s = tau[i] - b[i];
        for (int k = 0; k < i; k++) s -= L[i * N + k] * y[k];
        y[i] = s / L[i * N + i];
    }
    for (int i = N - 1; i >= 0; i--) {
        double s = y[i];
        for (int k = i + 1; k < N; k++) s -= L[k * N + i] * qddot[k];
        qddot[i] = s / L[i * N + i];
    }
}

template <class F>
static double best_ns(F f)
{
    double best = 1e300;
    for (int run = 0; run < 5; run++) {
        const auto start = Clock::now();
        for (int k = 0; k < CALLS; k++) f(k);
        best = std::min(best, std::chrono::duration<double, std::nano>(Clock::now() - start).count() / CALLS);
    }
    return best;
}

template <class Derived>
static void store(double* out, const Eigen::MatrixBase<Derived>& value)
{
    for (int i = 0; i < value.rows(); i++)
        for (int j = 0; j < value.cols(); j++) out[i * value.cols() + j] = value(i, j);
}

static double differs(const double* a, const double* b, int size)
{
    double scale = 1.0, worst = 0.0;
    for (int k = 0; k < size; k++) scale = std::max(scale, std::abs(b[k]));
    for (int k = 0; k < size; k++) worst = std::max(worst, std::abs(a[k] - b[k]));
    return worst / scale;
}

// worst[column][function]: the plain C functions, the c99 target, the cpp target against pinocchio
static void compare(double (*worst)[6], int function, const double (*out)[N * N], const double* expected, int size)
{
    for (int column = 0; column < 3; column++)
        worst[column][function] = std::max(worst[column][function], differs(out[column], expected, size));
}

int main()
{
@MODEL@
    pinocchio::Data data(model);
    const double params[] = {@PARAMS@ 0.0};
    std::mt19937 generator(44);
    std::uniform_real_distribution<double> uniform(-2.0, 2.0);
    double worst[3][6] = {};
    for (int trial = 0; trial < 10; trial++) {
        Vector q, v, a;
        for (int k = 0; k < N; k++) {
            q(k) = uniform(generator);
            v(k) = uniform(generator);
            a(k) = uniform(generator);
        }
        double out[3][N * N], expected[N * N];
        symjac_tau(q.data(), v.data(), a.data(), params, out[0]);
        @ROBOT@_inverse_dynamics(q.data(), nullptr, v.data(), a.data(), out[1]);
        store(out[2], cpp::inverse_dynamics(q, v, a));
        store(expected, pinocchio::rnea(model, data, q, v, a));
        compare(worst, 0, out, expected, N);
        symjac_M(q.data(), nullptr, nullptr, params, out[0]);
        @ROBOT@_mass_matrix(q.data(), nullptr, out[1]);
        store(out[2], cpp::mass_matrix(q));
        pinocchio::crba(model, data, q);
        data.M.triangularView<Eigen::StrictlyLower>() = data.M.transpose().triangularView<Eigen::StrictlyLower>();
        store(expected, data.M);
        compare(worst, 1, out, expected, N * N);
        symjac_g(q.data(), nullptr, nullptr, params, out[0]);
        @ROBOT@_gravity_torques(q.data(), nullptr, out[1]);
        store(out[2], cpp::gravity_torques(q));
        store(expected, pinocchio::computeGeneralizedGravity(model, data, q));
        compare(worst, 2, out, expected, N);
        symjac_b(q.data(), v.data(), nullptr, params, out[0]);
        @ROBOT@_bias_forces(q.data(), nullptr, v.data(), out[1]);
        store(out[2], cpp::bias_forces(q, v));
        store(expected, pinocchio::rnea(model, data, q, v, Vector::Zero()));
        compare(worst, 3, out, expected, N);
        symjac_C(q.data(), v.data(), nullptr, params, out[0]);
        @ROBOT@_coriolis_matrix(q.data(), nullptr, v.data(), out[1]);
        store(out[2], cpp::coriolis_matrix(q, v));
        store(expected, pinocchio::computeCoriolisMatrix(model, data, q, v));
        compare(worst, 4, out, expected, N * N);
        forward_dynamics(q.data(), v.data(), a.data(), params, out[0]);
        @ROBOT@_forward_dynamics(q.data(), nullptr, v.data(), a.data(), out[1]);
        store(out[2], cpp::forward_dynamics(q, v, a));
        store(expected, pinocchio::aba(model, data, q, v, a));
        compare(worst, 5, out, expected, N);
    }
    for (int column = 0; column < 3; column++) {
        std::printf("agree");
        for (int k = 0; k < 6; k++) std::printf(" %.3e", worst[column][k]);
        std::printf("\n");
    }
    Vector q, v, a;
    for (int k = 0; k < N; k++) { q(k) = 0.3 + 0.2 * k; v(k) = 0.5 - 0.1 * k; a(k) = 0.2 * k - 0.4; }
    volatile double sink = 0;
    double out[N * N];
    auto nudge = [&](int k) { q(0) += 1e-12 * (k & 1 ? 1 : -1); };
    const double* p = params;
    using Out1 = Eigen::Matrix<double, N, 1>;
    using OutN = Eigen::Matrix<double, N, N>;
    std::printf("tau %.2f %.2f %.2f %.2f\n",
        best_ns([&](int k) { nudge(k); sink = sink + pinocchio::rnea(model, data, q, v, a)(N - 1); }),
        best_ns([&](int k) { nudge(k); symjac_tau(q.data(), v.data(), a.data(), p, out); escape(out); }),
        best_ns([&](int k) {
            nudge(k); @ROBOT@_inverse_dynamics(q.data(), nullptr, v.data(), a.data(), out); escape(out); }),
        best_ns([&](int k) { nudge(k); Out1 r = cpp::inverse_dynamics(q, v, a); escape(r.data()); }));
    std::printf("M %.2f %.2f %.2f %.2f\n",
        best_ns([&](int k) { nudge(k); sink = sink + pinocchio::crba(model, data, q)(0, N - 1); }),
        best_ns([&](int k) { nudge(k); symjac_M(q.data(), nullptr, nullptr, p, out); escape(out); }),
        best_ns([&](int k) { nudge(k); @ROBOT@_mass_matrix(q.data(), nullptr, out); escape(out); }),
        best_ns([&](int k) { nudge(k); OutN r = cpp::mass_matrix(q); escape(r.data()); }));
    std::printf("g %.2f %.2f %.2f %.2f\n",
        best_ns([&](int k) { nudge(k); sink = sink + pinocchio::computeGeneralizedGravity(model, data, q)(0); }),
        best_ns([&](int k) { nudge(k); symjac_g(q.data(), nullptr, nullptr, p, out); escape(out); }),
        best_ns([&](int k) { nudge(k); @ROBOT@_gravity_torques(q.data(), nullptr, out); escape(out); }),
        best_ns([&](int k) { nudge(k); Out1 r = cpp::gravity_torques(q); escape(r.data()); }));
    const Vector zero = Vector::Zero();
    std::printf("b %.2f %.2f %.2f %.2f\n",
        best_ns([&](int k) { nudge(k); sink = sink + pinocchio::rnea(model, data, q, v, zero)(N - 1); }),
        best_ns([&](int k) { nudge(k); symjac_b(q.data(), v.data(), nullptr, p, out); escape(out); }),
        best_ns([&](int k) { nudge(k); @ROBOT@_bias_forces(q.data(), nullptr, v.data(), out); escape(out); }),
        best_ns([&](int k) { nudge(k); Out1 r = cpp::bias_forces(q, v); escape(r.data()); }));
    std::printf("C %.2f %.2f %.2f %.2f\n",
        best_ns([&](int k) { nudge(k); sink = sink + pinocchio::computeCoriolisMatrix(model, data, q, v)(0, 1); }),
        best_ns([&](int k) { nudge(k); symjac_C(q.data(), v.data(), nullptr, p, out); escape(out); }),
        best_ns([&](int k) { nudge(k); @ROBOT@_coriolis_matrix(q.data(), nullptr, v.data(), out); escape(out); }),
        best_ns([&](int k) { nudge(k); OutN r = cpp::coriolis_matrix(q, v); escape(r.data()); }));
    std::printf("fd %.2f %.2f %.2f %.2f\n",
        best_ns([&](int k) { nudge(k); sink = sink + pinocchio::aba(model, data, q, v, a)(N - 1); }),
        best_ns([&](int k) { nudge(k); forward_dynamics(q.data(), v.data(), a.data(), p, out); escape(out); }),
        best_ns([&](int k) {
            nudge(k); @ROBOT@_forward_dynamics(q.data(), nullptr, v.data(), a.data(), out); escape(out); }),
        best_ns([&](int k) { nudge(k); Out1 r = cpp::forward_dynamics(q, v, a); escape(r.data()); }));
    std::printf("sincos %.2f %.2f\n", 0.0, best_ns([&](int k) {
        nudge(k);
        double sum = 0;
        for (int j = 0; j < N; j++) sum += std::sin(q(j)) + std::cos(q(j));
        sink = sink + sum;
    }));
    return 0;
}
"""

COLUMNS = ("plain C", "c99", "cpp")
LABELS = {"tau": "inverse dynamics (rnea)", "M": "mass matrix (crba)", "g": "gravity (computeGeneralizedGravity)",
          "b": "bias forces (rnea, qdd = 0)", "C": "Coriolis matrix (computeCoriolisMatrix)",
          "fd": "forward dynamics (aba)", "sincos": "sin + cos of the joint angles"}


def measure(name: str, strategy: str, folder: Path) -> tuple[dict[str, tuple[float, ...]],
                                                              dict[str, LoweredFunction], dict[str, float],
                                                              list[list[float]]]:
    """Lower, print, generate, compile and run one robot.

    Returns (pinocchio, plain C, c99, cpp) ns per function (sin + cos: (0, ns)), the lowered functions, the lowering
    seconds and the agreement (one list of six per column: plain C, c99, cpp).
    """
    robot, model = arm(name)
    chain = Chain(robot)
    lowered, seconds = {}, {}
    for key, lower in FUNCTIONS.items():
        start = time.perf_counter()
        # gravity's 9.81 written in, as pinocchio's model holds it (generated modules take it as the parameter g)
        lowered[key] = lower(chain, strategy, numeric_gravity(EARTH)) if key in ("tau", "b", "g") else \
            lower(chain, strategy)
        seconds[key] = time.perf_counter() - start
    for target in ("c99", "cpp"):  # the generated targets as users get them (g = 9.81 their parameters' default)
        request = ModuleRequest(robot, target, strategy=strategy, name=name, dynamics=True)
        for file_name, text in render_files(describe(request)).items():
            (folder / file_name).write_text(text)
    functions = "\n".join(c_function(f"symjac_{key}", lowered[key], robot) for key in FUNCTIONS)
    params = "".join(f"{float(robot.defaults[p])!r}, " for p in robot.parameter_symbols)
    driver = (DRIVER.replace("@N@", str(robot.n_coordinates)).replace("@FUNCTIONS@", functions)
              .replace("@MODEL@", _model_code(model)).replace("@PARAMS@", params).replace("@ROBOT@", name))
    (folder / "driver.cpp").write_text(driver)
    prefix = pinocchio_prefix()
    assert prefix is not None
    flags = ["-std=c++17", "-O2", f"-I{EIGEN}", "-DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS",
             "-DBOOST_MPL_LIMIT_LIST_SIZE=30", "-DBOOST_MPL_LIMIT_VECTOR_SIZE=30", "-DBOOST_FUSION_INVOKE_MAX_ARITY=12",
             "-DPINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION", f"-I{prefix / 'include'}",
             f"-L{prefix / 'lib'}", f"-Wl,-rpath,{prefix / 'lib'}"]
    subprocess.run(["gcc", "-std=c99", "-O2", "-c", f"{name}.c", "-o", "c99.o"], cwd=folder, check=True)
    subprocess.run(["g++", *flags, "-I.", "driver.cpp", "c99.o", "-o", "driver", "-lpinocchio_default", "-lm"],
                   cwd=folder, check=True)
    output = subprocess.run([str(folder / "driver")], check=True, capture_output=True, text=True).stdout
    figures: dict[str, tuple[float, ...]] = {}
    agree: list[list[float]] = []
    for line in output.splitlines():
        key, *values = line.split()
        if key == "agree":
            agree.append([float(v) for v in values])
        else:
            figures[key] = tuple(float(v) for v in values)
    return figures, lowered, seconds, agree


def main(argv: Sequence[str] | None = None) -> int:
    """Print one table per robot: ns per call, ratios, operation counts."""
    parser = argparse.ArgumentParser(prog="python benchmarks/dynamics_vs_pinocchio.py",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("robots", nargs="*", default=["puma560", "ur5", "panda"])
    parser.add_argument("--strategy", default="fastest", choices=("fastest", "raw", "simplified"))
    parser.add_argument("--keep", type=Path, help="write each robot's driver.cpp into this folder and keep it")
    args = parser.parse_args(argv)
    if shutil.which("g++") is None or pinocchio_prefix() is None:
        print("needs g++ and pinocchio (PyPI 'pin'): nothing measured")
        return 0
    for name in args.robots:
        with tempfile.TemporaryDirectory() as scratch:
            folder = Path(scratch) if args.keep is None else args.keep / name
            folder.mkdir(parents=True, exist_ok=True)
            figures, lowered, seconds, agree = measure(name, args.strategy, folder)
        worst = max((max(column) for column in agree), default=float("inf"))
        if len(agree) != len(COLUMNS) or worst > 1e-9:
            print(f"{name}: symjac ({', '.join(COLUMNS)}) and pinocchio disagree (tau, M, g, b, C, fd): {agree}",
                  file=sys.stderr)
            return 1
        print(f"\n{name} (agree to {worst:.1e}; strategy {args.strategy!r})\n")
        print("| function | pinocchio ns | plain C ns | c99 ns | cpp ns | pinocchio / plain C | pinocchio / c99 | "
              "pinocchio / cpp | plain C mul | plain C add | lowering s |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        for key, values in figures.items():
            if key == "sincos":
                print(f"| {LABELS[key]} | - | {values[1]:.0f} | - | - | - | - | - | - | - | - |")
                continue
            pin_ns, *ours = values
            if key in lowered:
                mul, add = operations(lowered[key])
                counts = f"{mul} | {add} | {seconds[key]:.1f}"
            else:
                counts = "M, b + Cholesky | | "
            print(f"| {LABELS[key]} | {pin_ns:.0f} | {' | '.join(f'{ns:.0f}' for ns in ours)} | "
                  f"{' | '.join(f'{pin_ns / ns:.1f}' for ns in ours)} | {counts} |", flush=True)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())

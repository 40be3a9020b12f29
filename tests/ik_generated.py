"""Generated closed-form inverse kinematics, made and called the same way in every target (for the IK tests).

:func:`ik_solvers` generates a robot's module for each target, compiles what needs compiling (c99 with gcc, cpp with
g++ on Eigen, both ``-Wall -Wextra -Werror``) and returns, per target, a function from a batch of 4 x 4 poses to the
list of each pose's solutions (an array of shape (count, n)); its ``pairs`` gives each pose's solutions and their
branch indices in ``IK_BRANCHES`` (jax and casadi: the positions of the valid rows).
"""

from __future__ import annotations

import ctypes
import importlib.util
import subprocess
from collections.abc import Callable
from pathlib import Path

import numpy as np

from symjac.codegen.module import ModuleRequest, describe, render_files

EIGEN = Path("/usr/include/eigen3")
C_FLAGS = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-O2"]
CPP_FLAGS = ["-std=c++17", "-Wall", "-Wextra", "-Werror", "-O2", f"-I{EIGEN}"]

Pairs = Callable[[np.ndarray], list[tuple[np.ndarray, np.ndarray]]]


class Solver:
    """A target's solver: called on a batch of poses, each pose's solutions; ``pairs`` adds their branch indices."""

    def __init__(self, pairs: Pairs) -> None:
        self.pairs = pairs

    def __call__(self, poses: np.ndarray) -> list[np.ndarray]:
        return [rows for rows, _ in self.pairs(poses)]


def ik_files(robot, target: str, **options) -> dict[str, str]:
    """Every file of ``robot``'s module for ``target`` with inverse kinematics."""
    return render_files(describe(ModuleRequest(robot, target, inverse_kinematics=True, **options)))


def _python(folder: Path, robot, target: str) -> Pairs:
    (name, text), = ik_files(robot, target).items()
    path = folder / f"{target}_{name}"
    path.write_text(text)
    spec = importlib.util.spec_from_file_location(f"ik_{target}_{robot.name}_{id(path)}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    if target == "python":
        def single(poses: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
            found = []
            for pose in poses:
                rows, count, branches = module.inverse_kinematics(pose)
                assert len(rows) == count == len(branches)
                found.append((np.array(rows).reshape(-1, robot.n_coordinates), np.array(branches, dtype=int)))
            return found

        return single
    if target == "jax":
        import jax

        jax.config.update("jax_enable_x64", True)
        solve = jax.jit(jax.vmap(module.inverse_kinematics))

        def masked(poses: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
            solutions, valid = (np.asarray(a) for a in solve(poses))
            return [(rows[ok], np.flatnonzero(ok)) for rows, ok in zip(solutions, valid, strict=True)]

        return masked
    if target == "casadi":
        defaults = np.array([value for value in module.PARAMETER_DEFAULTS], dtype=float)

        def function(poses: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
            found = []
            for pose in poses:
                solutions, valid = (np.asarray(a) for a in module.inverse_kinematics(pose, defaults))
                ok = valid.ravel() > 0.5
                found.append((solutions[ok], np.flatnonzero(ok)))
            return found

        return function

    def batched(poses: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        solutions, count, branches = module.inverse_kinematics(poses)
        assert np.all((branches >= 0) == (np.arange(branches.shape[-1]) < count[:, None]))
        return [(rows[:k], indices[:k]) for rows, k, indices in zip(solutions, count, branches, strict=True)]

    return batched


def _c99(folder: Path, robot) -> Pairs:
    files = ik_files(robot, "c99")
    for name, text in files.items():
        (folder / name).write_text(text)
    library = folder / f"lib{robot.name}_ik.so"
    subprocess.run(["gcc", *C_FLAGS, "-fPIC", "-shared", f"{robot.name}.c", "-o", library.name, "-lm"],
                   cwd=folder, check=True, capture_output=True)
    lib = ctypes.CDLL(str(library))
    function = getattr(lib, f"{robot.name}_inverse_kinematics")
    function.restype = ctypes.c_int
    maximum = int(next(line.split()[-1] for line in files[f"{robot.name}.h"].splitlines()
                       if line.startswith(f"#define {robot.name.upper()}_IK_MAX_SOLUTIONS")))
    n = robot.n_coordinates

    def solve(poses: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        found = []
        for pose in poses:
            flat = np.ascontiguousarray(pose, dtype=float).ravel()
            out = np.full(maximum * n, np.nan)
            branches = np.full(maximum, -1, dtype=np.intc)
            count = function(flat.ctypes.data_as(ctypes.c_void_p), None, ctypes.c_double(1e-9),
                             out.ctypes.data_as(ctypes.c_void_p), branches.ctypes.data_as(ctypes.c_void_p))
            found.append((out.reshape(maximum, n)[:count].copy(), branches[:count].astype(int)))
        return found

    return solve


CPP_SHIM = """#include "{robot}.hpp"
extern "C" int solve(const double* pose, double* out, int* indices)
{{
    using namespace symjac::{robot};
    const Eigen::Matrix4d T = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(pose);
    std::array<Eigen::Matrix<double, {n}, 1>, ik_max_solutions> solutions;
    std::array<int, ik_max_solutions> branches;
    const int count = inverse_kinematics(T, solutions, branches);
    for (int k = 0; k < count; ++k) {{
        indices[k] = branches[k];
        for (int i = 0; i < {n}; ++i) {{
            out[k * {n} + i] = solutions[k](i);
        }}
    }}
    return count;
}}
extern "C" int maximum() {{ return symjac::{robot}::ik_max_solutions; }}
"""


def _cpp(folder: Path, robot) -> Pairs:
    (name, text), = ik_files(robot, "cpp").items()
    (folder / name).write_text(text)
    n = robot.n_coordinates
    (folder / "ik_shim.cpp").write_text(CPP_SHIM.format(robot=robot.name, n=n))
    subprocess.run(["g++", *CPP_FLAGS, "-fPIC", "-shared", "ik_shim.cpp", "-o", "libikshim.so"], cwd=folder,
                   check=True, capture_output=True)
    lib = ctypes.CDLL(str(folder / "libikshim.so"))
    maximum = lib.maximum()

    def solve(poses: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        found = []
        for pose in poses:
            flat = np.ascontiguousarray(pose, dtype=float).ravel()
            out = np.full(maximum * n, np.nan)
            branches = np.full(maximum, -1, dtype=np.intc)
            count = lib.solve(flat.ctypes.data_as(ctypes.c_void_p), out.ctypes.data_as(ctypes.c_void_p),
                              branches.ctypes.data_as(ctypes.c_void_p))
            found.append((out.reshape(maximum, n)[:count].copy(), branches[:count].astype(int)))
        return found

    return solve


def ik_solvers(folder: Path, robot, targets: tuple[str, ...]) -> dict[str, Solver]:
    """Each target's generated ``inverse_kinematics`` as a function of a batch of poses, by target."""
    solvers: dict[str, Solver] = {}
    for target in targets:
        where = folder / target
        where.mkdir(exist_ok=True)
        if target == "c99":
            solvers[target] = Solver(_c99(where, robot))
        elif target == "cpp":
            solvers[target] = Solver(_cpp(where, robot))
        else:
            solvers[target] = Solver(_python(where, robot, target))
    return solvers

"""Generated dynamics and identification modules in the tests: the arms, the reference, and how a module is made.

``test_codegen_dynamics`` and ``test_codegen_identification`` check different functions of the same kind of module:
a Python-family one called with keyword parameters (CasADi: the parameter vector), or a c99 pair or cpp header
compiled with warnings as errors and called through ctypes (the cpp one behind a C-ABI shim whose functions each
test file writes).
"""

from __future__ import annotations

import ctypes
import dataclasses
import importlib.util
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from reference_dynamics import NumericDynamics

from symjac import robot_from_mapping
from symjac.codegen import ModuleRequest, describe, render_files
from symjac.model.inertial_parameters import with_symbolic_inertials
from symjac.model.robot import Parameter

PYTHON_FAMILY = ("python", "numpy", "lambdify", "c", "jax", "casadi")
COMPILED = ("c99", "cpp")
GRAVITY = 9.81
C_FLAGS = ["-Wall", "-Wextra", "-Werror", "-O1", "-fPIC", "-shared"]
EIGEN = Path("/usr/include/eigen3")

CPP_SHIM = """#include "{robot}.hpp"
using namespace symjac::{robot};
using V = Eigen::Matrix<double, {n}, 1>;
static V vector(const double *x) {{ return V(Eigen::Map<const V>(x)); }}
static Params<double> parameters(const double *p) {{ Params<double> values; {assignments} return values; }}
template <class M> static void store(const M& m, double *out)
{{
    for (int i = 0; i < m.rows(); i++) {{
        for (int j = 0; j < m.cols(); j++) {{
            out[i * m.cols() + j] = m(i, j);
        }}
    }}
}}
extern "C" {{
{functions}
}}
"""
"""A cpp module behind C functions ``name_(q, p, ...)``: ``functions`` is their C++ text, inserted as it is."""


def elbow():
    """A spatial 3R arm (standard DH) whose gravity torques are not zero, with symbolic inertial parameters."""
    robot = robot_from_mapping({
        "name": "elbow", "convention": "standard", "parameters": {"d1": 0.3, "a2": 0.4, "a3": 0.35},
        "joints": [{"type": "revolute", "alpha": "pi/2", "d": "d1"}, {"type": "revolute", "a": "a2"},
                   {"type": "revolute", "a": "a3"}]})
    return with_symbolic_inertials(robot)


def inertials(n: int) -> dict[str, float]:
    """Physical inertial parameters other than the defaults: mass, centre, inertia about it (positive definite)."""
    values: dict[str, float] = {}
    for k in range(1, n + 1):
        values |= {f"m{k}": 1.5 + 0.7 * k, f"cx{k}": -0.12 + 0.02 * k, f"cy{k}": 0.03 * k, f"cz{k}": 0.01 - 0.02 * k,
                   f"Ixx{k}": 0.05 + 0.01 * k, f"Iyy{k}": 0.06 + 0.01 * k, f"Izz{k}": 0.07 + 0.005 * k,
                   f"Ixy{k}": 0.002, f"Ixz{k}": -0.003, f"Iyz{k}": 0.001 * k}
    return values


def reference(robot, values: dict[str, float], gravity: float = GRAVITY) -> NumericDynamics:
    """The numeric Newton-Euler of ``robot`` with its parameters at ``values`` (the others at their defaults)."""
    parameters = tuple(Parameter(p.name, sp.nsimplify(values[p.name], rational=True)) if p.name in values else p
                       for p in robot.parameters)
    return NumericDynamics(dataclasses.replace(robot, parameters=parameters), gravity)


def close(got, expected, tolerance: float = 1e-9) -> None:
    """``got`` equals ``expected`` to ``tolerance``, relative to the larger of 1 and the largest expected entry."""
    expected = np.asarray(expected, dtype=float).ravel()
    scale = max(1.0, float(np.abs(expected).max()))
    assert np.abs(np.asarray(got, dtype=float).ravel() - expected).max() <= tolerance * scale


def import_module(path: Path):
    """The Python module in ``path``, imported under a name of its own."""
    spec = importlib.util.spec_from_file_location(f"generated_{path.stem}_{id(path)}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class PythonModule:
    """A Python-family module of ``robot`` made with the request's ``options``, written to ``folder`` and imported."""

    def __init__(self, folder: Path, robot, target: str, **options: bool):
        if target == "jax":
            pytest.importorskip("jax").config.update("jax_enable_x64", True)
        if target == "casadi":
            pytest.importorskip("casadi")
        self.target = target
        self.files = render_files(describe(ModuleRequest(robot, target, **options)))
        self.path = folder / f"{robot.name}_{target}.py"
        self.path.write_text(next(iter(self.files.values())))
        self.module = import_module(self.path)

    def call(self, name: str, *inputs, parameters: dict[str, float]) -> np.ndarray:
        """Function ``name`` at ``inputs`` with ``parameters`` (the others at their defaults), as a NumPy array."""
        function = getattr(self.module, name)
        if self.target == "casadi":
            vector = [parameters.get(p, d) for p, d in zip(self.module.PARAMETER_NAMES,
                                                           self.module.PARAMETER_DEFAULTS, strict=True)]
            return np.asarray(function(*inputs, vector), dtype=float)
        return np.asarray(function(*inputs, **parameters), dtype=float)


class CompiledModule:
    """A c99 pair, or a cpp header behind ``CPP_SHIM`` with ``shim_functions``, compiled and loaded with ctypes."""

    def __init__(self, folder: Path, robot, target: str, shim_functions: str, **options: bool):
        compiler = "gcc" if target == "c99" else "g++"
        if shutil.which(compiler) is None or (target == "cpp" and not (EIGEN / "Eigen" / "Dense").is_file()):
            pytest.skip(f"{compiler} (or Eigen's headers) is not installed")
        self.files = render_files(describe(ModuleRequest(robot, target, **options)))
        for name, text in self.files.items():
            (folder / name).write_text(text)
        self.defaults = dict(describe(ModuleRequest(robot, "python", **options)).parameters)
        self.parameter_names = list(self.defaults)  # the robot's parameters, then gravity's magnitude g
        self.n, self.target = robot.n_coordinates, target
        if target == "c99":
            command = [compiler, "-std=c99", "-pedantic", *C_FLAGS, f"{robot.name}.c", "-o", "lib.so", "-lm"]
            self.prefix, self.suffix = f"{robot.name}_", ""
        else:
            assignments = " ".join(f"values.{name} = p[{k}];" for k, name in enumerate(self.parameter_names))
            (folder / "shim.cpp").write_text(CPP_SHIM.format(robot=robot.name, n=self.n, assignments=assignments,
                                                             functions=shim_functions))
            command = [compiler, "-std=c++17", f"-I{EIGEN}", *C_FLAGS, "shim.cpp", "-o", "lib.so"]
            self.prefix, self.suffix = "", "_"
        result = subprocess.run(command, cwd=folder, capture_output=True, text=True, check=False)
        assert result.returncode == 0, result.stderr
        self.library = ctypes.CDLL(str(folder / "lib.so"))

    def run(self, name: str, inputs, parameters: dict[str, float], size: int) -> np.ndarray:
        """C function ``name`` at ``inputs`` (q, the parameter vector, the rest) written into ``size`` doubles."""
        values = np.array([parameters.get(p, self.defaults[p]) for p in self.parameter_names])
        out = np.zeros(size)
        pointer = ctypes.POINTER(ctypes.c_double)
        first, *rest = (np.ascontiguousarray(a, dtype=float) for a in inputs)
        function = getattr(self.library, f"{self.prefix}{name}{self.suffix}")
        function(first.ctypes.data_as(pointer), values.ctypes.data_as(pointer),
                 *(a.ctypes.data_as(pointer) for a in rest), out.ctypes.data_as(pointer))
        return out

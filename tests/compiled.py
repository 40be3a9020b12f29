"""Comparing a compiled target (c99, cpp) with the python target: what their tests share."""

from __future__ import annotations

import importlib.util
import types
from pathlib import Path
from typing import Protocol

import numpy as np
import sympy as sp

from symjac import JacobianRequest, generate, robot_from_mapping


class CompiledModule(Protocol):
    """What a compiled module offers its test: an array function by name, a scalar function by name."""

    def call(self, name: str, size: int, *inputs: np.ndarray | None) -> np.ndarray: ...

    def scalar(self, name: str, q: np.ndarray, params: np.ndarray | None) -> float: ...


def load_module(folder: Path, robot, target: str, **options) -> types.ModuleType:
    """Generate ``robot``'s module for a Python-family ``target`` into ``folder`` and import it."""
    path = folder / f"{robot.name}_{target}.py"
    path.write_text(generate(robot, target, **options))
    spec = importlib.util.spec_from_file_location(f"generated_{robot.name}_{target}_{id(path)}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def two_joint_robot(name: str = "arm", parameter: str = "L"):
    """A two-joint standard-DH robot named ``name`` with one parameter named ``parameter`` (for name checks)."""
    return robot_from_mapping({"name": name, "convention": "standard", "parameters": {parameter: 1.0},
                               "joints": [{"type": "revolute", "a": parameter}, {"type": "revolute", "a": 1}]})


def python_module(robot, **options) -> dict:
    """The python target's module for ``robot`` (with the acceleration level unless told), executed."""
    namespace: dict = {}
    exec(compile(generate(robot, "python", **{"acceleration": True, **options}), f"{robot.name}.py", "exec"),
         namespace)
    return namespace


SEVERAL = {"jacobians": [JacobianRequest(0, "wrist"), JacobianRequest(2, "wrist"),
                         JacobianRequest(0, (0.1, 0, 0), (0, 1, 5))],
           "scalars": {"reach": sp.Symbol("theta2", real=True) * 2}}
"""Options that exercise several Jacobians (their name suffixes), a subset of rows, a point and a scalar function."""


def numbers_only_robot():
    """A three-joint arm whose every entry is a number: a module without parameters."""
    return robot_from_mapping({"name": "fixed", "convention": "modified", "joints": [
        {"type": "revolute"}, {"type": "revolute", "alpha": "pi/2", "a": 0.3}, {"type": "prismatic", "a": 0.2}]})


def agrees_with_python_target(compiled: CompiledModule, robot, samples: int = 20) -> None:
    """Every function of ``compiled`` equals the python target's to 1e-12, with default and with other parameters."""
    reference = python_module(robot)
    n = robot.n_coordinates
    names = [p.name for p in robot.geometric_parameters]
    defaults = np.array([float(p.default) for p in robot.geometric_parameters])
    rng = np.random.default_rng(7)
    for sample in range(samples):
        q = rng.uniform(-np.pi, np.pi, n)
        qdot, wrench = rng.uniform(-1, 1, n), rng.uniform(-1, 1, 6)
        params = None if sample % 2 == 0 else defaults * rng.uniform(0.8, 1.2, defaults.shape) + 0.01
        keywords = {} if params is None else dict(zip(names, params, strict=True))

        def close(value, expected):
            np.testing.assert_allclose(value, np.ravel(np.asarray(expected, dtype=float)), rtol=1e-12, atol=1e-12)

        close(compiled.call("forward_kinematics", 16, q, params), reference["forward_kinematics"](q, **keywords))
        close(compiled.call("jacobian", 6 * n, q, params), reference["jacobian"](q, **keywords))
        close(compiled.call("joint_torques", n, q, params, wrench),
              reference["joint_torques"](q, wrench, **keywords))
        close(compiled.call("hessian", 6 * n * n, q, params), reference["hessian"](q, **keywords))
        close(compiled.call("bias_acceleration", 6, q, params, qdot),
              reference["bias_acceleration"](q, qdot, **keywords))
        close(compiled.call("manipulability_gradient", n, q, params),
              reference["manipulability_gradient"](q, **keywords))
        close(compiled.scalar("manipulability", q, params), reference["manipulability"](q, **keywords))
        if "jacobian_determinant" in reference:
            close(compiled.scalar("jacobian_determinant", q, params),
                  reference["jacobian_determinant"](q, **keywords))



"""The jax target: pure jax.numpy functions that jit, vmap and grad compose with.

With x64 on, every catalog robot and URDF arm agrees with the python target to 1e-12 (20 random configurations,
default and other parameters); ``jax.jacfwd`` of the generated forward kinematics gives the Jacobian (linear rows
from the position, angular rows from R-dot R^T); ``jit(vmap(jacobian))`` over 1e5 configurations equals the numpy
target; ``grad`` of the manipulability is the generated gradient; float32 is what runs without x64.
"""

from __future__ import annotations

import os
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest
from compiled import SEVERAL, agrees_with_python_target, load_module, numbers_only_robot, python_module
from marks import marked

from symjac import JacobianRequest, generate, load_robot
from symjac.codegen import ModuleRequest, describe, render_files
from symjac.model.io import catalog

jax = pytest.importorskip("jax")
jax.config.update("jax_enable_x64", True)
jnp = jax.numpy

GOLDEN = Path(__file__).resolve().parent / "golden"
ROBOTS = [*sorted(catalog()), "gripper.urdf", "panda.urdf", "ur5.urdf"]


class Functions:
    """The jax module seen as the compiled targets' tests see theirs: by name, with a parameter vector."""

    def __init__(self, module: types.ModuleType, names: list[str]):
        self.module, self.names = module, names

    def _keywords(self, params):
        return {} if params is None else dict(zip(self.names, map(float, params), strict=True))

    def call(self, name: str, size: int, q, params, *more) -> np.ndarray:
        value = np.ravel(np.asarray(getattr(self.module, name)(jnp.asarray(q), *map(jnp.asarray, more),
                                                               **self._keywords(params))))
        assert value.size == size and value.dtype == np.float64
        return value

    def scalar(self, name: str, q, params) -> float:
        return float(getattr(self.module, name)(jnp.asarray(q), **self._keywords(params)))


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_every_function_agrees_with_the_python_target(tmp_path, name):
    robot = load_robot(name)
    module = load_module(tmp_path, robot, "jax", acceleration=True)
    agrees_with_python_target(Functions(module, [p.name for p in robot.geometric_parameters]), robot)
    assert module.selftest() < 1e-6


@pytest.mark.parametrize("name", marked(["planar3r", "stanford", "palletizer", "ur5"]))
def test_jacfwd_of_the_forward_kinematics_is_the_jacobian(tmp_path, name):
    robot = load_robot(name)
    point = "tool" if robot.tool is not None else "wrist"  # where forward_kinematics ends
    module = load_module(tmp_path, robot, "jax", jacobians=[JacobianRequest(0, point)])
    q = jnp.linspace(-1.1, 0.9, robot.n_coordinates)
    T = module.forward_kinematics(q)
    dT = jax.jacfwd(module.forward_kinematics)(q)  # (4, 4, n)
    J = module.jacobian(q)
    np.testing.assert_allclose(dT[:3, 3, :], J[:3], atol=1e-12)
    for m in range(robot.n_coordinates):
        W = dT[:3, :3, m] @ T[:3, :3].T
        np.testing.assert_allclose(jnp.stack([W[2, 1], W[0, 2], W[1, 0]]), J[3:, m], atol=1e-12)


def test_jit_vmap_over_a_hundred_thousand_configurations_equals_the_numpy_target(tmp_path):
    robot = load_robot("puma560")
    module = load_module(tmp_path, robot, "jax")
    reference = load_module(tmp_path, robot, "numpy")
    Q = np.random.default_rng(3).uniform(-np.pi, np.pi, (100_000, robot.n_coordinates))
    batched = jax.jit(jax.vmap(module.jacobian))(jnp.asarray(Q))
    assert batched.shape == (100_000, 6, 6)
    np.testing.assert_allclose(np.asarray(batched), reference.jacobian(Q), rtol=1e-12, atol=1e-12)


def test_grad_of_the_manipulability_is_the_generated_gradient(tmp_path):
    robot = load_robot("puma560")
    module = load_module(tmp_path, robot, "jax", acceleration=True)
    q = jnp.linspace(0.3, 1.4, robot.n_coordinates)  # away from a singular configuration (w is 0.1 here)
    assert module.manipulability(q) > 1e-3
    np.testing.assert_allclose(jax.grad(module.manipulability)(q), module.manipulability_gradient(q), rtol=1e-9,
                               atol=1e-12)
    np.testing.assert_allclose(jax.jit(module.manipulability)(q), module.manipulability(q), rtol=1e-14)


def test_without_x64_it_computes_in_float32(tmp_path):
    path = tmp_path / "puma560_jax.py"
    path.write_text(generate(load_robot("puma560"), "jax"))
    script = ("import importlib.util, jax.numpy as jnp\n"
              f"spec = importlib.util.spec_from_file_location('m', {str(path)!r})\n"
              "m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)\n"
              "print(m.jacobian(jnp.zeros(6)).dtype, m.selftest() < 2e-2)\n")
    environment = {**os.environ, "JAX_ENABLE_X64": "0"}
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=environment, check=True)
    assert result.stdout.split() == ["float32", "True"]


def test_golden_file_determinism_and_lint(tmp_path):
    text = generate(load_robot("planar2r"), "jax", acceleration=True)
    assert text == generate(load_robot("planar2r"), "jax", acceleration=True)
    path = GOLDEN / "planar2r_jax.py.golden"
    if os.environ.get("SYMJAC_UPDATE_GOLDEN") == "1":
        path.write_text(text)
    assert path.read_text() == text, "review and regenerate with SYMJAC_UPDATE_GOLDEN=1"
    files = render_files(describe(ModuleRequest(load_robot("puma560"), "jax", acceleration=True)))
    (tmp_path / "puma560.py").write_text(files["puma560.py"])
    result = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--isolated", "--select",
                             "E,F,W,I,UP,B,SIM,PIE,RUF", "--line-length", "120", str(tmp_path / "puma560.py")],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout


def test_several_jacobians_rows_a_point_a_scalar_and_no_parameters(tmp_path):
    robot = numbers_only_robot()
    module = load_module(tmp_path, robot, "jax", **SEVERAL)
    reference = python_module(robot, **SEVERAL)
    q = [0.3, -0.7, 0.2]
    for name in ("jacobian_2_wrist", "jacobian_0_p1_r015"):
        np.testing.assert_allclose(np.asarray(getattr(module, name)(q)), reference[name](q), atol=1e-12)
    assert abs(float(module.reach(q)) - reference["reach"](q)) < 1e-12
    determinant = module.jacobian_determinant_0_p1_r015
    assert abs(float(determinant(q)) - reference["jacobian_determinant_0_p1_r015"](q)) < 1e-12
    assert module.selftest() < 1e-6

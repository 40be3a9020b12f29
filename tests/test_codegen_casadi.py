"""The casadi target: casadi.Function objects (SX) built from the lowered expressions.

Every catalog robot and URDF arm agrees with the python target to 1e-12 (20 random configurations, default and
other parameters, ``p`` in the order of ``PARAMETER_NAMES``); ``casadi.jacobian`` of the generated forward
kinematics equals the generated Jacobian (linear rows from the position, angular rows from R-dot R^T);
``Function.generate()`` writes C that compiles; ``casadi.Opti`` solves an
inverse-kinematics problem with the functions; the module's self-test passes.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest
from compiled import SEVERAL, agrees_with_python_target, load_module, numbers_only_robot, python_module
from marks import marked

from symjac import JacobianRequest, generate, load_robot
from symjac.codegen import CodegenError
from symjac.model.io import catalog

ca = pytest.importorskip("casadi")

GOLDEN = Path(__file__).resolve().parent / "golden"
ROBOTS = [*sorted(catalog()), "gripper.urdf", "panda.urdf", "ur5.urdf"]


class Functions:
    """The casadi module seen as the compiled targets' tests see theirs (Hessians back in [i, j, m] order)."""

    def __init__(self, module: types.ModuleType, n: int):
        self.module, self.n = module, n

    def _p(self, params):
        return ca.DM(self.module.PARAMETER_DEFAULTS if params is None else list(params))

    def call(self, name: str, size: int, q, params, *more) -> np.ndarray:
        value = np.asarray(getattr(self.module, name)(ca.DM(q), *map(ca.DM, more), self._p(params)))
        if name == "hessian":  # [dJ/dq_1 | ... | dJ/dq_n] -> H[i, j, m]
            value = value.reshape(value.shape[0], self.n, self.n).transpose(0, 2, 1)
        value = np.ravel(value)
        assert value.size == size
        return value

    def scalar(self, name: str, q, params) -> float:
        return float(getattr(self.module, name)(ca.DM(q), self._p(params)))


@pytest.mark.parametrize("name", marked(ROBOTS))
def test_every_function_agrees_with_the_python_target(tmp_path, name):
    robot = load_robot(name)
    module = load_module(tmp_path, robot, "casadi", acceleration=True)
    assert tuple(p.name for p in robot.geometric_parameters) == module.PARAMETER_NAMES
    agrees_with_python_target(Functions(module, robot.n_coordinates), robot)
    assert module.selftest() < 1e-6


@pytest.mark.parametrize("name", marked(["planar3r", "stanford", "palletizer", "ur5"]))
def test_casadi_jacobian_of_the_forward_kinematics_is_the_jacobian(tmp_path, name):
    robot = load_robot(name)
    point = "tool" if robot.tool is not None else "wrist"  # where forward_kinematics ends
    module = load_module(tmp_path, robot, "casadi", jacobians=[JacobianRequest(0, point)])
    q, p = ca.SX.sym("q", robot.n_coordinates), ca.DM(module.PARAMETER_DEFAULTS)
    T = module.forward_kinematics(q, p)
    R = T[:3, :3]
    # linear rows: d p / d q; angular rows: column k of omega is vee(dR/dq_k R^T)
    rows = [ca.jacobian(T[:3, 3], q)]
    dR = [ca.jacobian(R[:, c], q) for c in range(3)]  # dR[c][r, k] = d R[r, c] / d q_k

    def W(r: int, s: int) -> ca.SX:  # (dR/dq R^T)[r, s] for every q_k, as a row
        return sum(dR[c][r, :] * R[s, c] for c in range(3))

    rows.append(ca.vertcat(W(2, 1), W(0, 2), W(1, 0)))
    derivative = ca.Function("d", [q], [ca.vertcat(*rows)])
    at = ca.DM(np.linspace(-1.0, 0.8, robot.n_coordinates))
    np.testing.assert_allclose(np.asarray(derivative(at)), np.asarray(module.jacobian(at, p)), atol=1e-12)


@pytest.mark.external  # a C compiler
@pytest.mark.skipif(shutil.which("gcc") is None, reason="gcc is not installed")
def test_function_generate_writes_c_that_compiles(tmp_path):
    module = load_module(tmp_path, load_robot("puma560"), "casadi", acceleration=True)
    generator = ca.CodeGenerator("puma560_casadi.c")
    for function in (module.jacobian, module.forward_kinematics, module.hessian, module.bias_acceleration):
        generator.add(function)
    generator.generate(str(tmp_path) + os.sep)
    subprocess.run(["gcc", "-std=c99", "-O2", "-c", "puma560_casadi.c"], cwd=tmp_path, check=True)


def test_opti_solves_an_inverse_kinematics_problem(tmp_path):
    module = load_module(tmp_path, load_robot("planar2r"), "casadi")
    opti = ca.Opti()
    q = opti.variable(2)
    target = np.array([0.6, 0.3])
    tip = module.forward_kinematics(q, ca.DM(module.PARAMETER_DEFAULTS))[:2, 3]
    opti.minimize(ca.sumsqr(tip - target))
    opti.set_initial(q, [0.3, 0.8])
    opti.solver("ipopt", {"print_time": False}, {"print_level": 0, "sb": "yes"})
    solution = opti.solve()
    reached = np.asarray(module.forward_kinematics(solution.value(q), module.PARAMETER_DEFAULTS))[:2, 3]
    np.testing.assert_allclose(reached, target, atol=1e-8)


def test_golden_file_determinism_names_and_lint(tmp_path):
    text = generate(load_robot("planar2r"), "casadi", acceleration=True)
    assert text == generate(load_robot("planar2r"), "casadi", acceleration=True)
    path = GOLDEN / "planar2r_casadi.py.golden"
    if os.environ.get("SYMJAC_UPDATE_GOLDEN") == "1":
        path.write_text(text)
    assert path.read_text() == text, "review and regenerate with SYMJAC_UPDATE_GOLDEN=1"
    (tmp_path / "planar2r.py").write_text(text)
    result = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--isolated", "--select",
                             "E,F,W,I,UP,B,SIM,PIE,RUF", "--line-length", "120", str(tmp_path / "planar2r.py")],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout
    with pytest.raises(CodegenError, match="scalar function name 'jac' is a CasADi keyword"):
        generate(load_robot("planar2r"), "casadi", scalars={"jac": 1})


def test_several_jacobians_rows_a_point_a_scalar_and_no_parameters(tmp_path):
    robot = numbers_only_robot()
    module = load_module(tmp_path, robot, "casadi", **SEVERAL)
    reference = python_module(robot, **SEVERAL)
    q = [0.3, -0.7, 0.2]
    for name in ("jacobian_2_wrist", "jacobian_0_p1_r015"):
        np.testing.assert_allclose(np.asarray(getattr(module, name)(q, [])), reference[name](q), atol=1e-12)
    assert abs(float(module.reach(q, [])) - reference["reach"](q)) < 1e-12
    determinant = module.jacobian_determinant_0_p1_r015
    assert abs(float(determinant(q, [])) - reference["jacobian_determinant_0_p1_r015"](q)) < 1e-12
    assert module.selftest() < 1e-6

"""A quantity's codegen part lives in its spec: the kinds table, the functions' order and the generic lowering."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from marks import marked
from reference import evaluate

from symjac import load_robot
from symjac.codegen.coupled import coordinate_derivation, coordinate_jacobian
from symjac.codegen.kinds import KINDS, generated_kinds, quantity_of
from symjac.codegen.module import ModuleRequest, describe
from symjac.errors import ArgumentError
from symjac.kinematics.chain import chain_of, forward_kinematics
from symjac.kinematics.jacobian import point_vector
from symjac.quantities import QUANTITIES, Generated
from symjac.quantities.spec import lazily_memoized

ROOT = Path(__file__).resolve().parent.parent
BUILT_IN = ("forward_kinematics", "jacobian", "hessian", "bias_acceleration", "joint_torques", "manipulability")
"""The quantities of today (a test of the order filters others out: quantities may come and go)."""


def test_the_kinds_table_is_the_quantities_kinds_then_codegens_own():
    own = [q.codegen.name for q in QUANTITIES.values() if q.codegen is not None]
    assert list(KINDS)[:len(own)] == own
    assert list(KINDS)[len(own):] == ["kinematics", "bias_forces", "forward_dynamics", "potential_energy",
                                      "standard_values", "base_values", "scalar", "jacobian_determinant",
                                      "manipulability_gradient"]
    for name in own:
        assert quantity_of(name).kind == name and KINDS[name] is quantity_of(name).codegen
    assert quantity_of("kinematics") is None


def _among(kinds, names):
    """The names of ``kinds`` that are in ``names`` (the built-in ones: other quantities may come and go)."""
    return [kind.name for kind in kinds if kind.name in names]


def test_module_order_velocity_level_then_the_selftests_kinematics_then_acceleration():
    module = generated_kinds("module", True)
    assert module[0].name == "forward_kinematics" and all(kind.scope == "module" for kind in module)
    assert [kind.name for kind in module] == [name for name in KINDS if KINDS[name] in module]  # registry order
    built_in = {"jacobian", "joint_torques", "kinematics", "hessian", "bias_acceleration", "manipulability",
                "jacobian_determinant", "manipulability_gradient"}
    assert _among(generated_kinds("request", False), built_in) == [
        "jacobian", "joint_torques", "kinematics", "manipulability", "jacobian_determinant"]
    assert _among(generated_kinds("request", True), built_in) == [
        "jacobian", "joint_torques", "kinematics", "hessian", "bias_acceleration", "manipulability",
        "jacobian_determinant", "manipulability_gradient"]
    levels = [(kind.derived, kind.acceleration and not kind.derived) for kind in generated_kinds("request", True)]
    assert levels == sorted(levels)  # lowered before derived; among the lowered, the acceleration level last


def test_every_request_records_its_functions_by_kind():
    description = describe(ModuleRequest(load_robot("scara"), "python", frames=(0, 2), acceleration=True))
    info = description.jacobians[1]
    kinds = [kind for kind, _, _ in info.functions if quantity_of(kind) is None or quantity_of(kind).name in BUILT_IN]
    assert kinds == ["jacobian", "joint_torques", "kinematics", "hessian", "bias_acceleration", "manipulability",
                     "manipulability_gradient"]  # 6 x 4: not square, no determinant
    names = dict((kind, name) for kind, name, _ in info.functions)
    assert names["jacobian"] == info.jacobian == "jacobian_2_flange" and names["kinematics"] == info.kinematics
    shapes = {kind: shape for kind, _, shape in info.functions}
    assert shapes["hessian"] == (6, 4, 4) and shapes["manipulability_gradient"] == (4,)


def test_a_generated_kind_says_what_is_wrong_with_it():
    with pytest.raises(ArgumentError, match="generated kind 'x': scope 'arm'"):
        Generated("x", "r", scope="arm")  # type: ignore[arg-type]
    with pytest.raises(ArgumentError, match=r"inputs \['force'\] are not among wrench, qdot"):
        Generated("x", "r", inputs=("force",))  # type: ignore[arg-type]
    with pytest.raises(ArgumentError, match="a derived kind has sources, no lowering"):
        Generated("x", "r", routine="manipulability")
    with pytest.raises(ArgumentError, match="an entry point is 'module:name'"):
        Generated("x", "r", lowering="symjac.codegen.coupled")


def _values(function, q: np.ndarray, robot) -> np.ndarray:
    """A lowered function's outputs at ``q`` (coordinates) and the default parameters."""
    at = {**{s: float(v) for s, v in robot.defaults.items()}, **dict(zip(robot.q, map(float, q), strict=True))}
    trig = {}
    for sine, cosine, angle in function.angles:
        value = float(angle.xreplace(at))
        trig |= {sine: np.sin(value), cosine: np.cos(value)}
    values = {**at, **trig}
    for symbol, expr in function.temporaries:
        values[symbol] = float(expr.xreplace(values))
    return np.array([float(sp.sympify(e).xreplace(values)) for e in function.outputs])


@pytest.mark.parametrize("name", marked(["planar3r", "palletizer"]))  # palletizer: coupled (columns and rates laws)
def test_the_generic_lowering_of_a_derivation_agrees_with_the_quantitys_own(name):
    robot = load_robot(name)
    chain = chain_of(robot)
    point = point_vector(robot, "wrist")
    own = coordinate_jacobian(chain, 0, point, (0, 1, 5), "fastest")
    generic = coordinate_derivation(chain, "symjac.kinematics.jacobian:jacobian", "columns", (0, point), (0, 1, 5))
    assert generic.shape == own.shape == (3, robot.n_coordinates)
    pose = coordinate_derivation(chain, "symjac.kinematics.chain:forward_kinematics", "rates")
    assert pose.shape == (4, 4)
    rng = np.random.default_rng(3)
    for _ in range(3):
        q = rng.uniform(-np.pi, np.pi, robot.n_coordinates)
        np.testing.assert_allclose(_values(generic, q, robot), _values(own, q, robot), atol=1e-12)
        np.testing.assert_allclose(_values(pose, q, robot), evaluate(forward_kinematics(robot), robot, q).ravel(),
                                   atol=1e-12)


def test_lazily_memoized_keeps_one_value_per_chain_and_states_its_law():
    calls = []

    @lazily_memoized(coupling="rates")
    def reach(chain):
        calls.append(chain)
        return chain.transform(0, chain.n_joints)[:3, 3]

    robot = load_robot("planar2r")
    assert reach(robot) is reach(chain_of(robot)) and len(calls) == 1
    assert reach.coupling_law.name == "rates" and reach.__name__ == "reach"


def test_a_quantity_module_with_a_lazily_memoized_derivation_loads_no_sympy():
    code = ("import sys\nfrom symjac.quantities.spec import lazily_memoized\n"
            "f = lazily_memoized(coupling='rates')(lambda chain: chain)\nprint('sympy' in sys.modules)")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120,
                            env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}, cwd=ROOT)
    assert result.stdout.split() == ["False"]

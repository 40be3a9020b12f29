"""Which robots are derived nested (issue 41): textbook robots keep their textbook forms, generic ones do not.

The catalog's robots (multiples of pi/2 and symbolic lengths) must not be nested; a generic arm must be. Asked for
explicitly, the nested route on a textbook robot must give the same numbers as the textbook route. A result that
keeps intermediates must be handed out as a :class:`~symjac.symbolic.nested.NestedMatrix`, which carries its
definitions (a plain Matrix holding intermediates cannot be printed, lambdified or read).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from generic_arms import _poe_arm
from marks import marked

from symjac import (
    Chain,
    NoClosedFormError,
    body_jacobian,
    catalog,
    determinant,
    forward_kinematics,
    jacobian,
    jacobian_derivative,
    load_robot,
    robot_from_toml,
    robot_to_toml,
    space_jacobian,
    urdf_catalog,
)
from symjac.cli.main import main
from symjac.kinematics.points import point_position
from symjac.symbolic.nested import NestedMatrix, has_intermediates, substitute


@pytest.mark.parametrize("name", marked(sorted(catalog()) + sorted(urdf_catalog())))
def test_catalog_robots_are_not_nested(name):
    assert Chain(load_robot(name)).nested is False


def generic_arm():
    """A generic 6R body-form PoE arm (body form: clear of SymPy 1.14's factorint bug, test_generic_properties)."""
    return robot_from_toml(_poe_arm(np.random.default_rng(5), [(False, "generic")] * 6, body=True).text)


def test_a_generic_arm_is_nested():
    assert Chain(generic_arm()).nested is True


def numbers(matrix: sp.MatrixBase, values: dict) -> np.ndarray:
    return np.array([float(e) for e in substitute(list(matrix), values)]).reshape(matrix.shape)


@pytest.mark.parametrize("name", marked(["stanford", "puma560", "ur5_poe"]))
@pytest.mark.parametrize("frame", [0, 3, "tool"])
def test_nested_route_on_a_textbook_robot_gives_the_textbook_jacobian(name, frame):
    robot = load_robot(name)
    point = "tool" if robot.tool is not None else "wrist"
    textbook, nested = Chain(robot), Chain(robot, nested=True)
    assert not textbook.nested and nested.nested
    rng = np.random.default_rng(0)
    values = {**{s: float(v) for s, v in robot.defaults.items()},
              **{q: float(v) for q, v in zip(robot.joint_variables, rng.uniform(-2, 2, robot.n_joints), strict=True)}}
    expected = numbers(jacobian(textbook, frame=frame, point=point), values)
    for method in ("differentiation", "velocity_propagation"):
        np.testing.assert_allclose(numbers(jacobian(nested, frame=frame, point=point, method=method), values),
                                   expected, rtol=0, atol=1e-12, err_msg=method)


PUBLIC = {
    "forward_kinematics": lambda robot: forward_kinematics(robot, target="tool"),
    "jacobian": lambda robot: jacobian(robot),
    "space_jacobian": space_jacobian,
    "jacobian_derivative": lambda robot: jacobian_derivative(robot),
    "body_jacobian": body_jacobian,
    "point_position": lambda robot: point_position(robot, "tool"),
}
@pytest.mark.parametrize("name", list(PUBLIC))
def test_results_that_keep_intermediates_carry_their_definitions(name):
    result = PUBLIC[name](generic_arm())
    assert not has_intermediates(result) or isinstance(result, NestedMatrix), type(result).__name__


def test_closed_form_analyses_of_a_generic_arm_are_refused_in_one_line(tmp_path, capsys):
    robot = generic_arm()
    with pytest.raises(NoClosedFormError, match="not available for this robot: its geometry is generic"):
        determinant(robot)
    path = tmp_path / "generic.toml"
    path.write_text(robot_to_toml(robot), encoding="utf-8")
    assert main(["singularities", str(path)]) == 2
    error = capsys.readouterr().err.strip().splitlines()
    assert len(error) == 1 and "symjac codegen" in error[0]

"""Reading robot descriptions (symjac.model.robot_file): valid mappings, joints, angle units, base and tool."""

from __future__ import annotations

import copy
import dataclasses

import pytest
import sympy as sp
from robot_mappings import (
    L1,
    L2,
    ROTATE_Z,
    SOURCE,
    d3,
    minimal,
    theta1,
    theta2,
    with_joint,
)

from symjac.model.conventions.dh import DHPlacement
from symjac.model.robot import (
    Convention,
    FixedTransform,
    Joint,
    JointType,
    Parameter,
    Robot,
)
from symjac.model.robot_file import robot_from_mapping

# --------------------------------------------------------------------------------------------- valid mappings


def test_minimal_mapping():
    robot = robot_from_mapping(minimal(), source=SOURCE)
    assert isinstance(robot, Robot)
    assert robot.name == "arm"
    assert robot.convention is Convention.STANDARD
    assert robot.description == ""
    assert robot.source == SOURCE
    assert robot.n_joints == 2
    assert robot.q == (theta1, theta2)
    assert robot.parameters == (Parameter("L1", sp.Integer(1)), Parameter("L2", sp.Rational(1, 2)))
    assert robot.parameter_symbols == (L1, L2)
    assert robot.defaults == {L1: 1, L2: sp.Rational(1, 2)}
    assert robot.base is None
    assert robot.tool is None
    first, second = robot.joints
    assert first == Joint(index=1, type=JointType.REVOLUTE, placement=DHPlacement(alpha=0, a=L1), d=0, theta=0)
    assert second.placement.a == L2
    assert first.limits is None


def test_smallest_possible_mapping():
    robot = robot_from_mapping({"name": "r", "convention": "modified", "joints": [{"type": "prismatic"}]})
    assert robot.source == "<mapping>"
    assert robot.parameters == ()
    assert robot.q == (sp.Symbol("d1", real=True),)
    joint = robot.joints[0]
    assert joint.placement.alpha == joint.placement.a == joint.d == joint.theta == 0


def test_fields_are_exact_sympy_expressions():
    data = with_joint(1, alpha="-pi/2", a=0.4318, d="L1 + L2", theta=0.1)
    joint = robot_from_mapping(data).joints[0]
    assert joint.placement.alpha == -sp.pi / 2
    assert joint.placement.a == sp.Rational(2159, 5000)
    assert joint.d == L1 + L2
    assert joint.theta == sp.Rational(1, 10)
    for value in (joint.placement.alpha, joint.placement.a, joint.d, joint.theta):
        assert isinstance(value, sp.Basic)
        assert not value.atoms(sp.Float)


def test_parameter_symbols_are_real_and_match_field_symbols():
    robot = robot_from_mapping(minimal())
    assert all(symbol.is_real for symbol in robot.parameter_symbols)
    assert robot.joints[0].placement.a.free_symbols == {robot.parameters[0].symbol}
    assert robot.parameters[0].symbol == L1


def test_parameter_defaults_are_exact():
    robot = robot_from_mapping(minimal(parameters={"L1": 0.4318, "L2": -3}))
    assert robot.defaults == {L1: sp.Rational(2159, 5000), L2: sp.Integer(-3)}


def test_description_and_modified_convention():
    robot = robot_from_mapping(minimal(description="A test arm", convention="modified"))
    assert robot.description == "A test arm"
    assert robot.convention is Convention.MODIFIED
    assert robot.convention == "modified"


def test_limits_are_kept_as_exact_expressions():
    robot = robot_from_mapping(with_joint(1, limits=["-pi/2", 1.5]))
    assert robot.joints[0].limits == (-sp.pi / 2, sp.Rational(3, 2))


def test_limits_may_use_parameters():
    robot = robot_from_mapping(with_joint(1, limits=["-L1", "L1"]))
    assert robot.joints[0].limits == (-L1, L1)


def test_parameter_named_like_a_revolute_joints_d_is_allowed():
    data = minimal(parameters={"L1": 1, "L2": 0.5, "d1": 0.3, "theta9": 1})
    data["joints"][0]["d"] = "d1"
    robot = robot_from_mapping(data)
    assert robot.joints[0].d == sp.Symbol("d1", real=True)
    assert robot.q == (theta1, theta2)


def test_joints_may_be_a_tuple():
    data = minimal()
    data["joints"] = tuple(data["joints"])
    assert robot_from_mapping(data).n_joints == 2


def test_robot_is_immutable():
    robot = robot_from_mapping(minimal())
    with pytest.raises(dataclasses.FrozenInstanceError):
        robot.name = "other"  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        robot.joints[0].placement.a = 0  # type: ignore[misc]


def test_robot_equality_ignores_source():
    assert robot_from_mapping(minimal(), source="a.toml") == robot_from_mapping(minimal(), source="b.toml")
    assert robot_from_mapping(minimal()) != robot_from_mapping(minimal(name="other"))
    assert robot_from_mapping(minimal()) != robot_from_mapping(minimal(parameters={"L1": 1, "L2": 0.6}))


def test_robot_from_mapping_does_not_change_its_input():
    data = minimal(tool={"xyz": ["L1", 0, 0]})
    before = copy.deepcopy(data)
    robot_from_mapping(data)
    assert data == before


# --------------------------------------------------------------------------------------------- joints


def test_revolute_joint_semantics():
    robot = robot_from_mapping(with_joint(1, theta="pi/2", d=0.2))
    joint = robot.joints[0]
    assert joint.is_revolute
    assert joint.type is JointType.REVOLUTE
    assert joint.variable == theta1
    assert joint.variable.is_real
    assert joint.angle == theta1 + sp.pi / 2
    assert joint.offset == sp.Rational(1, 5)


def test_prismatic_joint_semantics():
    data = minimal()
    data["joints"].append({"type": "prismatic", "theta": "pi/2", "d": 0.1})
    joint = robot_from_mapping(data).joints[2]
    assert not joint.is_revolute
    assert joint.type is JointType.PRISMATIC
    assert joint.index == 3
    assert joint.variable == d3
    assert joint.variable.is_real
    assert joint.angle == sp.pi / 2
    assert joint.offset == d3 + sp.Rational(1, 10)


def test_joint_variables_follow_the_joint_number():
    joints = [{"type": kind} for kind in ("revolute", "prismatic", "revolute", "prismatic")]
    robot = robot_from_mapping({"name": "r", "convention": "modified", "joints": joints})
    assert [str(v) for v in robot.q] == ["theta1", "d2", "theta3", "d4"]
    assert [joint.index for joint in robot.joints] == [1, 2, 3, 4]
    assert [joint.variable for joint in robot.joints] == list(robot.q)


def test_joint_zero_offsets_give_bare_variables():
    joint = robot_from_mapping(minimal()).joints[0]
    assert joint.angle == theta1
    assert joint.offset == 0


# --------------------------------------------------------------------------------------------- angle units


def test_angle_unit_deg_converts_angles_but_not_lengths():
    data = minimal(angle_unit="deg")
    data["joints"][0].update(alpha=90, theta=45, a=90, d=30, limits=[-90, 180])
    data["joints"].append({"type": "prismatic", "alpha": -90, "theta": 90, "d": 30, "limits": [0, 90]})
    robot = robot_from_mapping(data)
    revolute, _, prismatic = robot.joints
    assert revolute.placement.alpha == sp.pi / 2
    assert revolute.theta == sp.pi / 4
    assert revolute.placement.a == 90
    assert revolute.d == 30
    assert revolute.limits == (-sp.pi / 2, sp.pi)
    assert prismatic.placement.alpha == -sp.pi / 2
    assert prismatic.theta == sp.pi / 2  # a prismatic joint's theta is still an angle
    assert prismatic.d == 30
    assert prismatic.limits == (0, 90)  # prismatic limits are lengths


def test_angle_unit_deg_keeps_parameters_and_scales_parameter_angles():
    data = minimal(angle_unit="deg", parameters={"L1": 1, "L2": 0.5, "q0": 90})
    data["joints"][0]["alpha"] = "q0"
    robot = robot_from_mapping(data)
    assert robot.defaults[sp.Symbol("q0", real=True)] == 90
    assert robot.joints[0].placement.alpha.subs(robot.defaults) == sp.pi / 2
    assert robot.joints[1].placement.a == L2


def test_angle_unit_deg_converts_rpy_but_not_xyz():
    robot = robot_from_mapping(minimal(angle_unit="deg", tool={"xyz": [90, 0, 0], "rpy": [0, 0, 90]}))
    assert robot.tool.xyz == (90, 0, 0)
    assert robot.tool.rpy == (0, 0, sp.pi / 2)


def test_angle_unit_rad_is_the_default():
    explicit = robot_from_mapping(minimal(angle_unit="rad"))
    assert explicit == robot_from_mapping(minimal())
    data = with_joint(1, alpha=1)
    assert robot_from_mapping(data).joints[0].placement.alpha == 1


def test_deg_and_rad_descriptions_of_the_same_robot_are_equal():
    deg = with_joint(1, alpha=-90, limits=[-160, 160])
    deg["angle_unit"] = "deg"
    rad = with_joint(1, alpha="-pi/2", limits=["-8*pi/9", "8*pi/9"])
    assert robot_from_mapping(deg) == robot_from_mapping(rad)


# --------------------------------------------------------------------------------------------- base and tool


def test_tool_and_base_from_xyz_and_rpy():
    robot = robot_from_mapping(minimal(base={"xyz": [0, 0, "L1"]}, tool={"rpy": ["pi/2", 0, 0]}))
    assert robot.base == FixedTransform(xyz=(0, 0, L1), rpy=(0, 0, 0))
    assert robot.tool == FixedTransform(xyz=(0, 0, 0), rpy=(sp.pi / 2, 0, 0))
    assert robot.base.matrix == sp.ImmutableMatrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, L1], [0, 0, 0, 1]])
    assert robot.tool.matrix == sp.ImmutableMatrix([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]])


def test_empty_tool_table_is_the_identity():
    robot = robot_from_mapping(minimal(tool={}))
    assert robot.tool.matrix == sp.eye(4)


def test_tool_from_matrix():
    robot = robot_from_mapping(minimal(tool={"matrix": ROTATE_Z}))
    expected = sp.ImmutableMatrix([[0, -1, 0, sp.Rational(1, 10)], [1, 0, 0, 0], [0, 0, 1, L1], [0, 0, 0, 1]])
    assert robot.tool.given_matrix == expected
    assert robot.tool.matrix == expected


def test_matrix_rotation_may_use_exact_decimals():
    half = 0.6
    rows = [[0.8, -half, 0, 0], [half, 0.8, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    robot = robot_from_mapping(minimal(base={"matrix": rows}))
    assert robot.base.matrix[0, 0] == sp.Rational(4, 5)

"""Robot descriptions: validation of mappings, the catalog, reading TOML files and writing them back."""

from __future__ import annotations

import copy
import dataclasses
import math
import re
import tomllib

import pytest
import sympy as sp

from symjac.analysis.inverse_rates import RATE_SYMBOLS
from symjac.errors import RobotFileError, SymjacError, UnknownRobotError
from symjac.kinematics.acceleration_propagation import joint_accelerations
from symjac.kinematics.jacobian import ROW_NAMES
from symjac.kinematics.propagation import joint_rate_symbols, wrench_symbols
from symjac.model.io import catalog, load_robot, robot_from_toml, robot_to_toml
from symjac.model.robot import (
    WRENCH_NAMES,
    Convention,
    FixedTransform,
    Joint,
    JointType,
    Parameter,
    Robot,
    reserved_names,
)
from symjac.model.robot_file import robot_from_mapping, robot_to_mapping

SOURCE = "arm.toml"
L1, L2 = sp.symbols("L1 L2", real=True)
theta1, theta2, theta3, d3 = sp.symbols("theta1 theta2 theta3 d3", real=True)

CATALOG = sorted(catalog())

# name -> (dof, convention, indices of prismatic joints, has base, has tool)
EXPECTED = {
    "planar2r": (2, "standard", (), False, False),
    "planar3r": (3, "modified", (), False, True),
    "articulated3r": (3, "modified", (), False, True),
    "stanford": (6, "modified", (3,), False, False),
    "puma560": (6, "modified", (), False, False),
    "scara": (4, "modified", (3,), False, False),
    "ur5": (6, "standard", (), False, False),
    "panda": (7, "modified", (), False, True),
}


def minimal(**overrides):
    """A valid two-joint planar arm; ``overrides`` replace top-level keys (value None removes the key)."""
    data = {
        "name": "arm",
        "convention": "standard",
        "parameters": {"L1": 1, "L2": 0.5},
        "joints": [{"type": "revolute", "a": "L1"}, {"type": "revolute", "a": "L2"}],
    }
    for key, value in overrides.items():
        if value is None:
            data.pop(key)
        else:
            data[key] = value
    return data


def with_joint(number, **fields):
    """``minimal()`` with joint ``number`` (1-based) updated by ``fields`` (value None removes the field)."""
    data = minimal()
    while len(data["joints"]) < number:
        data["joints"].append({"type": "revolute"})
    joint = data["joints"][number - 1]
    for key, value in fields.items():
        if value is None:
            joint.pop(key, None)
        else:
            joint[key] = value
    return data


def where(joint=None, field=None):
    """The regular expression of the location prefix of a RobotFileError message."""
    parts = [SOURCE]
    if joint is not None:
        parts.append(f"joint {joint}")
    if field is not None:
        parts.append(f"field '{field}'")
    return "^" + re.escape(", ".join(parts) + ": ")


def load_error(data, *, joint=None, field=None, message=""):
    """Check that ``data`` is rejected with the given location, and return the error."""
    with pytest.raises(RobotFileError, match=where(joint, field) + ".*" + message) as info:
        robot_from_mapping(data, source=SOURCE)
    error = info.value
    assert (error.source, error.joint, error.field) == (SOURCE, joint, field)
    return error


# --------------------------------------------------------------------------------------------- valid mappings


def test_minimal_mapping():
    robot = robot_from_mapping(minimal(), source=SOURCE)
    assert isinstance(robot, Robot)
    assert robot.name == "arm"
    assert robot.convention is Convention.STANDARD
    assert robot.description == ""
    assert robot.source == SOURCE
    assert robot.dof == 2
    assert robot.q == (theta1, theta2)
    assert robot.parameters == (Parameter("L1", sp.Integer(1)), Parameter("L2", sp.Rational(1, 2)))
    assert robot.parameter_symbols == (L1, L2)
    assert robot.defaults == {L1: 1, L2: sp.Rational(1, 2)}
    assert robot.base is None
    assert robot.tool is None
    first, second = robot.joints
    assert first == Joint(index=1, type=JointType.REVOLUTE, alpha=0, a=L1, d=0, theta=0)
    assert second.a == L2
    assert first.limits is None


def test_smallest_possible_mapping():
    robot = robot_from_mapping({"name": "r", "convention": "modified", "joints": [{"type": "prismatic"}]})
    assert robot.source == "<mapping>"
    assert robot.parameters == ()
    assert robot.q == (sp.Symbol("d1", real=True),)
    assert robot.joints[0].alpha == robot.joints[0].a == robot.joints[0].d == robot.joints[0].theta == 0


def test_fields_are_exact_sympy_expressions():
    data = with_joint(1, alpha="-pi/2", a=0.4318, d="L1 + L2", theta=0.1)
    joint = robot_from_mapping(data).joints[0]
    assert joint.alpha == -sp.pi / 2
    assert joint.a == sp.Rational(2159, 5000)
    assert joint.d == L1 + L2
    assert joint.theta == sp.Rational(1, 10)
    for value in (joint.alpha, joint.a, joint.d, joint.theta):
        assert isinstance(value, sp.Basic)
        assert not value.atoms(sp.Float)


def test_parameter_symbols_are_real_and_match_field_symbols():
    robot = robot_from_mapping(minimal())
    assert all(symbol.is_real for symbol in robot.parameter_symbols)
    assert robot.joints[0].a.free_symbols == {robot.parameters[0].symbol}
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
    assert robot_from_mapping(data).dof == 2


def test_robot_is_immutable():
    robot = robot_from_mapping(minimal())
    with pytest.raises(dataclasses.FrozenInstanceError):
        robot.name = "other"  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        robot.joints[0].a = 0  # type: ignore[misc]


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
    assert revolute.alpha == sp.pi / 2
    assert revolute.theta == sp.pi / 4
    assert revolute.a == 90
    assert revolute.d == 30
    assert revolute.limits == (-sp.pi / 2, sp.pi)
    assert prismatic.alpha == -sp.pi / 2
    assert prismatic.theta == sp.pi / 2  # a prismatic joint's theta is still an angle
    assert prismatic.d == 30
    assert prismatic.limits == (0, 90)  # prismatic limits are lengths


def test_angle_unit_deg_keeps_parameters_and_scales_parameter_angles():
    data = minimal(angle_unit="deg", parameters={"L1": 1, "L2": 0.5, "q0": 90})
    data["joints"][0]["alpha"] = "q0"
    robot = robot_from_mapping(data)
    assert robot.defaults[sp.Symbol("q0", real=True)] == 90
    assert robot.joints[0].alpha.subs(robot.defaults) == sp.pi / 2
    assert robot.joints[1].a == L2


def test_angle_unit_deg_converts_rpy_but_not_xyz():
    robot = robot_from_mapping(minimal(angle_unit="deg", tool={"xyz": [90, 0, 0], "rpy": [0, 0, 90]}))
    assert robot.tool.xyz == (90, 0, 0)
    assert robot.tool.rpy == (0, 0, sp.pi / 2)


def test_angle_unit_rad_is_the_default():
    explicit = robot_from_mapping(minimal(angle_unit="rad"))
    assert explicit == robot_from_mapping(minimal())
    data = with_joint(1, alpha=1)
    assert robot_from_mapping(data).joints[0].alpha == 1


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


ROTATE_Z = [[0, -1, 0, 0.1], [1, 0, 0, 0], [0, 0, 1, "L1"], [0, 0, 0, 1]]


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


# --------------------------------------------------------------------------------------------- error paths


def test_robot_file_error_is_a_symjac_value_error():
    error = load_error(minimal(convention=None), field="convention")
    assert isinstance(error, SymjacError)
    assert isinstance(error, ValueError)


def test_missing_convention_has_no_default():
    load_error(minimal(convention=None), field="convention", message="'convention' is required")


@pytest.mark.parametrize("convention", ["Standard", "dh", "craig", "", 1, None, ["standard"], {"standard": 1}])
def test_invalid_convention(convention):
    data = minimal()
    data["convention"] = convention
    load_error(data, field="convention", message=re.escape(repr(convention)))


@pytest.mark.parametrize("key", ["convetion", "joint", "Name", "units"])
def test_unknown_top_level_key(key):
    data = minimal()
    data[key] = 1
    load_error(data, message=f"unknown key.*'{key}'")


def test_unknown_joint_key():
    data = with_joint(2, alhpa="pi/2")
    error = load_error(data, joint=2, message="unknown key.*'alhpa'")
    assert "alpha" in str(error)  # the allowed keys are listed


@pytest.mark.parametrize("kind", ["rotary", "Revolute", "", 1, None, ["revolute"], {"revolute": 1}])
def test_bad_joint_type(kind):
    data = with_joint(2, type=kind)  # None removes the key: a missing type
    load_error(data, joint=2, field="type", message="'revolute' or 'prismatic'")


def test_joint_must_be_a_table():
    data = minimal()
    data["joints"].append("revolute")
    load_error(data, joint=3, message="expected a table")


@pytest.mark.parametrize("joints", [[], None, "revolute", {"type": "revolute"}, 3])
def test_joints_must_be_a_non_empty_list(joints):
    data = minimal()
    data["joints"] = joints
    if joints is None:
        del data["joints"]
    load_error(data, field="joints", message="non-empty list")


@pytest.mark.parametrize("name", ["my arm", "2arm", "arm-1", "", "class", "pi", "_arm", 5, None, "ärm"])
def test_robot_name_must_be_an_identifier(name):
    data = minimal()
    data["name"] = name
    if name is None:
        del data["name"]
    load_error(data, field="name", message="identifier")


def test_description_must_be_a_string():
    load_error(minimal(description=3), field="description")


@pytest.mark.parametrize("unit", ["degrees", "DEG", "grad", 1, ["deg"], {"deg": 1}])
def test_angle_unit_must_be_rad_or_deg(unit):
    load_error(minimal(angle_unit=unit), field="angle_unit")


@pytest.mark.parametrize(
    ("name", "reason"),
    [
        ("2x", "must start with a letter"),
        ("a-b", "only ASCII letters, digits and underscores"),
        ("class", "'class' is a Python keyword"),
        ("pi", "'pi' is the constant pi"),
        ("lambda", "is a Python keyword"),
        ("_x", r"names starting with an underscore are not allowed"),
        ("__import__", r"names starting with an underscore are not allowed"),
        ("a b", "only ASCII letters, digits and underscores"),
        ("Lé", "only ASCII letters, digits and underscores"),
        ("éL", "must start with a letter"),
        ("", "the name is empty"),
    ],
)
def test_parameter_name_refused_with_the_true_reason(name, reason):
    error = load_error(minimal(parameters={"L1": 1, "L2": 1, name: 1}), field=f"parameters.{name}", message=reason)
    assert "not an identifier" not in str(error)  # '__import__' is one, in Python's sense: say what is wrong


def test_parameter_names_must_be_strings():
    load_error(minimal(parameters={"L1": 1, "L2": 1, 3: 1}), field="parameters.3")


@pytest.mark.parametrize("name", ["theta1", "theta2", "theta3", "d3"])
def test_parameter_name_clashing_with_a_joint_variable(name):
    data = minimal(parameters={"L1": 1, "L2": 1, name: 0.5})
    data["joints"].append({"type": "prismatic"})
    load_error(data, field=f"parameters.{name}", message="is reserved: taken by a joint variable")


@pytest.mark.parametrize(
    ("name", "reason"),
    [
        ("f_x", "symjac names the wrench components f_x .. n_z"),
        ("n_z", "symjac names the wrench components f_x .. n_z"),
        ("thetadot1", "symjac names the joint rates thetadot<i> and ddot<i>"),
        ("ddot2", "symjac names the joint rates thetadot<i> and ddot<i>"),
        ("thetaddot2", "symjac names the joint accelerations thetaddot<i> and dddot<i>"),
        ("dddot1", "symjac names the joint accelerations thetaddot<i> and dddot<i>"),
        ("omega_z", "symjac names the velocity components v_x .. omega_z"),
    ],
)
def test_parameter_named_like_a_generated_symbol_is_refused(name, reason):
    data = minimal(parameters={"L1": 1, "L2": 1, name: 0.5})
    load_error(data, field=f"parameters.{name}", message=re.escape(f"parameter name {name!r} is reserved: {reason}"))
    with pytest.raises(RobotFileError, match=re.escape(f"'{name}' is reserved: {reason}")):
        robot_from_toml(robot_to_toml(robot_from_mapping(minimal())).replace("L2 = ", f"{name} = 1\nL2 = "))


@pytest.mark.parametrize("name", ["thetadot3", "ddot3", "d1", "fx", "f_x1", "theta_dot1", "omega"])
def test_names_beside_the_generated_symbols_stay_free(name):
    robot = robot_from_mapping(minimal(parameters={"L1": 1, "L2": 1, name: 0.5}))
    assert name in {parameter.name for parameter in robot.parameters}


def test_robot_built_directly_refuses_a_reserved_parameter_name():
    robot = robot_from_mapping(minimal())
    with pytest.raises(RobotFileError, match=r"built\.py, field 'parameters\.f_y': 'f_y' is reserved: .*wrench"):
        dataclasses.replace(robot, parameters=(Parameter("f_y", sp.Integer(1)),), source="built.py")


def test_reserved_names_are_the_symbols_symjac_generates():
    robot = load_robot("stanford")
    generated = {*joint_rate_symbols(robot), *joint_accelerations(robot), *wrench_symbols(), *robot.q, *RATE_SYMBOLS}
    reserved = reserved_names([joint.type for joint in robot.joints])
    assert {symbol.name for symbol in generated} <= set(reserved)
    assert set(ROW_NAMES) | set(WRENCH_NAMES) <= set(reserved)


@pytest.mark.parametrize("default", [math.nan, math.inf, -math.inf, "0.5", True, None, [1], {"value": 1}])
def test_parameter_default_must_be_a_finite_number(default):
    load_error(minimal(parameters={"L1": default, "L2": 1}), field="parameters.L1", message="finite number")


def test_parameters_must_be_a_table():
    load_error(minimal(parameters=[["L1", 1]]), field="parameters")


@pytest.mark.parametrize("field", ["alpha", "a", "d", "theta"])
@pytest.mark.parametrize("value", [math.nan, math.inf, True, None, [0], {"x": 1}])
def test_field_must_be_a_finite_number_or_expression(field, value):
    data = minimal()
    data["joints"][1][field] = value
    load_error(data, joint=2, field=field)


def test_nan_field_message():
    load_error(with_joint(2, alpha=float("nan")), joint=2, field="alpha", message="finite")


def test_field_using_an_unknown_name():
    error = load_error(with_joint(2, d="L3"), joint=2, field="d", message="unknown name 'L3'")
    assert "L1, L2" in str(error)


def test_field_cannot_use_a_joint_variable():
    load_error(with_joint(2, d="theta1"), joint=2, field="d", message="unknown name 'theta1'")


@pytest.mark.parametrize("text", ["-pi/", "sin(L1)", "L1**9", "1/0", "L1.real", "x" * 300])
def test_field_outside_the_grammar(text):
    load_error(with_joint(1, alpha=text), joint=1, field="alpha")


def test_hostile_field_is_rejected_without_running(tmp_path):
    target = tmp_path / "pwned_symjac"
    data = with_joint(2, a=f"__import__('os').system('touch {target}')")
    load_error(data, joint=2, field="a", message="not allowed")
    assert not target.exists()


def test_field_infinite_once_defaults_are_substituted():
    data = minimal(parameters={"L1": 0, "L2": 1})
    data["joints"][1]["a"] = "1/L1"
    load_error(data, joint=2, field="a", message="not a finite number")


@pytest.mark.parametrize(
    "limits",
    [[1, 1], [1, 0], ["pi", "-pi"], ["L1", "L1"], [0], [0, 1, 2], [], "0, 1", 1, {"lower": 0, "upper": 1}],
)
def test_bad_limits(limits):
    load_error(with_joint(2, limits=limits), joint=2, field="limits")


def test_limits_with_lower_not_below_upper_message():
    load_error(with_joint(1, limits=[0.5, -0.5]), joint=1, field="limits", message="lower < upper")


@pytest.mark.parametrize("limits", [[math.nan, 1], [0, math.inf], ["-1/L1", 1], [0, "L3"], [True, 1]])
def test_limits_must_be_finite_numbers(limits):
    data = minimal(parameters={"L1": 0, "L2": 1})
    data["joints"][0]["limits"] = limits
    load_error(data, joint=1, field="limits")


@pytest.mark.parametrize("key", ["base", "tool"])
class TestFixedTransformErrors:
    def test_matrix_not_4_by_4(self, key):
        three = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
        load_error(minimal(**{key: {"matrix": three}}), field=f"{key}.matrix", message="4 rows of 4")
        rows_of_three = [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 0]]
        load_error(minimal(**{key: {"matrix": rows_of_three}}), field=f"{key}.matrix", message="4 rows of 4")
        load_error(minimal(**{key: {"matrix": "abcd"}}), field=f"{key}.matrix")
        load_error(minimal(**{key: {"matrix": ["abcd"] * 4}}), field=f"{key}.matrix")

    @pytest.mark.parametrize("last", [[0, 0, 1, 1], [0, 0, 0, 2], [0, 0, 0, 0], [0, 0, 0, "L1 - 1"]])
    def test_matrix_last_row(self, key, last):
        rows = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], last]
        load_error(minimal(**{key: {"matrix": rows}}), field=f"{key}.matrix", message="last row")

    @pytest.mark.parametrize(
        "block",
        [
            [[2, 0, 0], [0, 2, 0], [0, 0, 2]],  # a scaling
            [[1, 0, 0], [0, 1, 0], [0, 0, -1]],  # a reflection: orthogonal, determinant -1
            [[1, 1, 0], [0, 1, 0], [0, 0, 1]],  # a shear
            [[0, 0, 0], [0, 0, 0], [0, 0, 0]],
            [[0.7071, -0.7071, 0], [0.7071, 0.7071, 0], [0, 0, 1]],  # too coarse an approximation
            [["L1", 0, 0], [0, 1, 0], [0, 0, 1]],  # L1 = 1 would pass: L1 defaults to 2 here
        ],
    )
    def test_matrix_block_not_a_rotation(self, key, block):
        rows = [[*block[0], 0], [*block[1], 0], [*block[2], 0], [0, 0, 0, 1]]
        data = minimal(**{key: {"matrix": rows}}, parameters={"L1": 2, "L2": 1})
        load_error(data, field=f"{key}.matrix", message="not a rotation")

    def test_matrix_entries_must_be_finite_numbers_or_expressions(self, key):
        rows = [[1, 0, 0, math.nan], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
        load_error(minimal(**{key: {"matrix": rows}}), field=f"{key}.matrix", message="finite")
        rows = [[1, 0, 0, "L9"], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
        load_error(minimal(**{key: {"matrix": rows}}), field=f"{key}.matrix", message="unknown name 'L9'")

    @pytest.mark.parametrize("other", [{"xyz": [0, 0, 0]}, {"rpy": [0, 0, 0]}])
    def test_matrix_and_xyz_or_rpy_together(self, key, other):
        rows = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
        load_error(minimal(**{key: {"matrix": rows, **other}}), field=key, message="not both")

    @pytest.mark.parametrize("vector", ["xyz", "rpy"])
    @pytest.mark.parametrize("entries", [[0, 0], [0, 0, 0, 0], [], "abc", 0])
    def test_vector_of_wrong_length(self, key, vector, entries):
        load_error(minimal(**{key: {vector: entries}}), field=f"{key}.{vector}", message="list of 3")

    @pytest.mark.parametrize("vector", ["xyz", "rpy"])
    def test_vector_entries_must_be_finite(self, key, vector):
        load_error(minimal(**{key: {vector: [0, math.inf, 0]}}), field=f"{key}.{vector}", message="finite")
        load_error(minimal(**{key: {vector: [0, "q", 0]}}), field=f"{key}.{vector}", message="unknown name 'q'")

    def test_unknown_transform_key(self, key):
        load_error(minimal(**{key: {"xyz": [0, 0, 0], "pos": [0, 0, 0]}}), field=key, message="'pos'")

    @pytest.mark.parametrize("value", [[0, 0, 0], "identity", 1])
    def test_transform_must_be_a_table(self, key, value):
        load_error(minimal(**{key: value}), field=key)


@pytest.mark.parametrize("data", [[], "name = 'arm'", None, 3])
def test_mapping_must_be_a_mapping(data):
    with pytest.raises(RobotFileError, match="^" + re.escape(f"{SOURCE}: expected a table")):
        robot_from_mapping(data, source=SOURCE)


def test_default_source_in_messages():
    with pytest.raises(RobotFileError, match=r"^<mapping>, field 'convention'"):
        robot_from_mapping(minimal(convention=None))


def test_first_problem_is_reported_with_its_joint():
    data = minimal()
    data["joints"][1]["alpha"] = "nope"
    data["joints"].append({"type": "revolute", "alpha": "nope"})
    load_error(data, joint=2, field="alpha")


# --------------------------------------------------------------------------------------------- catalog and load_robot


def test_catalog_lists_the_built_in_robots():
    robots = catalog()
    assert set(EXPECTED) <= set(robots)
    assert list(robots) == sorted(robots)
    for name, description in robots.items():
        assert isinstance(description, str)
        assert description, f"{name} has no description"


@pytest.mark.parametrize("name", CATALOG)
def test_every_catalog_robot_loads(name):
    robot = load_robot(name)
    assert isinstance(robot, Robot)
    assert robot.name == name
    assert robot.source == f"{name}.toml"
    assert robot.description == catalog()[name]
    assert robot.dof == len(robot.q) >= 1
    for parameter in robot.parameters:
        assert isinstance(parameter.default, sp.Rational)
    for joint in robot.joints:
        for value in (joint.alpha, joint.a, joint.d, joint.theta):
            assert value.free_symbols <= set(robot.parameter_symbols)
            assert math.isfinite(float(value.subs(robot.defaults)))


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_catalog_robot_shapes(name):
    dof, convention, prismatic, has_base, has_tool = EXPECTED[name]
    robot = load_robot(name)
    assert robot.dof == dof
    assert robot.convention == convention
    assert tuple(j.index for j in robot.joints if not j.is_revolute) == prismatic
    assert (robot.base is not None) == has_base
    assert (robot.tool is not None) == has_tool


def test_stanford_arm():
    robot = load_robot("stanford")
    assert [str(v) for v in robot.q] == ["theta1", "theta2", "d3", "theta4", "theta5", "theta6"]
    assert robot.joints[2].type is JointType.PRISMATIC
    assert robot.joints[2].limits == (sp.Rational(3, 10), sp.Rational(13, 10))
    assert robot.joints[2].offset == d3


def test_puma560_parameters_and_limits():
    robot = load_robot("puma560")
    a2, d4 = sp.symbols("a2 d4", real=True)
    assert robot.defaults[a2] == sp.Rational(2159, 5000)
    assert robot.defaults[d4] == sp.Rational(2159, 5000)
    assert robot.joints[1].alpha == -sp.pi / 2
    assert robot.joints[0].limits == (-8 * sp.pi / 9, 8 * sp.pi / 9)
    assert robot.joints[2].a == a2


def test_ur5_is_standard_dh():
    robot = load_robot("ur5")
    assert robot.convention is Convention.STANDARD
    assert robot.joints[0].alpha == sp.pi / 2
    assert robot.defaults[sp.Symbol("a3", real=True)] == sp.Rational(-1569, 4000)


def test_panda_has_a_tool():
    robot = load_robot("panda")
    assert robot.dof == 7
    assert robot.tool is not None
    assert robot.tool.xyz == (0, 0, sp.Symbol("dF", real=True))
    assert robot.tool.rpy == (0, 0, 0)
    assert all(joint.limits is not None for joint in robot.joints)


def test_scara_prismatic_joint():
    robot = load_robot("scara")
    assert robot.joints[2].variable == d3
    assert robot.joints[2].limits == (sp.Rational(-3, 20), 0)


PLANAR = """\
name = "myarm"
description = "two links"
convention = "standard"

[parameters]
L1 = 0.5
L2 = 0.4

[[joints]]
type = "revolute"
a = "L1"

[[joints]]
type = "revolute"
a = "L2"
limits = [-3, 3]
"""


def test_load_robot_from_a_path(tmp_path):
    path = tmp_path / "myarm.toml"
    path.write_text(PLANAR, encoding="utf-8")
    for argument in (path, str(path)):
        robot = load_robot(argument)
        assert robot.name == "myarm"
        assert robot.source == str(path)
        assert robot.dof == 2
        assert robot.joints[1].limits == (-3, 3)
        assert robot.defaults == {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5)}


def test_load_robot_from_a_path_with_another_suffix(tmp_path):
    path = tmp_path / "myarm.robot"
    path.write_text(PLANAR, encoding="utf-8")
    assert load_robot(str(path)).name == "myarm"


def test_load_robot_from_a_relative_toml_path(tmp_path, monkeypatch):
    (tmp_path / "myarm.toml").write_text(PLANAR, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert load_robot("myarm.toml").name == "myarm"


def test_catalog_name_wins_over_a_file_of_the_same_name(tmp_path, monkeypatch):
    (tmp_path / "puma560").write_text(PLANAR, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    assert load_robot("puma560").name == "puma560"


def test_invalid_toml_names_the_file(tmp_path):
    path = tmp_path / "broken.toml"
    path.write_text('name = "arm"\nconvention = \n', encoding="utf-8")
    with pytest.raises(RobotFileError, match="^" + re.escape(f"{path}: invalid TOML")) as info:
        load_robot(path)
    assert info.value.source == str(path)


def test_invalid_robot_in_a_file_names_file_joint_and_field(tmp_path):
    path = tmp_path / "typo.toml"
    path.write_text(PLANAR.replace('a = "L2"', 'a = "L3"'), encoding="utf-8")
    with pytest.raises(RobotFileError, match="^" + re.escape(f"{path}, joint 2, field 'a': unknown name 'L3'")):
        load_robot(path)


def test_file_that_is_not_utf8(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes(PLANAR.replace("two links", "zwei Glieder \xe4").encode("latin-1"))
    with pytest.raises(RobotFileError, match="^" + re.escape(f"{path}: cannot read file")):
        load_robot(path)


def test_hostile_file_is_rejected_without_running(tmp_path):
    target = tmp_path / "pwned_symjac"
    path = tmp_path / "evil.toml"
    path.write_text(PLANAR.replace('a = "L1"', f"a = \"__import__('os').system('touch {target}')\""), "utf-8")
    with pytest.raises(RobotFileError, match="joint 1, field 'a'"):
        load_robot(path)
    assert not target.exists()


CLIMBING_NAME = "../puma560"  # outside-the-repository: allowed (a catalog name that must be refused)


@pytest.mark.parametrize("name", ["no_such_robot", "PUMA560", "puma", "", CLIMBING_NAME, "robots/puma560"])
def test_unknown_robot_name(name):
    with pytest.raises(UnknownRobotError, match="neither a built-in robot") as info:
        load_robot(name)
    assert isinstance(info.value, SymjacError)
    assert isinstance(info.value, LookupError)
    assert "puma560" in str(info.value)  # the catalog is listed


def test_missing_file_and_directory_are_unknown_robots(tmp_path):
    with pytest.raises(UnknownRobotError):
        load_robot(tmp_path / "missing.toml")
    with pytest.raises(UnknownRobotError):
        load_robot(str(tmp_path / "missing.toml"))
    with pytest.raises(UnknownRobotError):
        load_robot(tmp_path)


def test_robot_from_toml_default_source():
    with pytest.raises(RobotFileError, match=r"^<string>: invalid TOML"):
        robot_from_toml("name = ")
    with pytest.raises(RobotFileError, match=r"^<string>, field 'convention'"):
        robot_from_toml('name = "arm"\n[[joints]]\ntype = "revolute"\n')


def test_robot_from_toml_with_source():
    robot = robot_from_toml(PLANAR, source="inline")
    assert robot.source == "inline"
    assert robot == load_robot_from_text(PLANAR)


def load_robot_from_text(text):
    return robot_from_mapping(tomllib.loads(text))


# --------------------------------------------------------------------------------------------- writing back


def matrix_tool_robot():
    return robot_from_mapping(
        minimal(
            description='matrix tool, "quoted"',
            base={"xyz": [0, 0, "L1 + 0.1"], "rpy": [0, "-pi/2", 0]},
            tool={"matrix": ROTATE_Z},
        )
    )


def degree_robot():
    data = {
        "name": "degarm",
        "convention": "modified",
        "angle_unit": "deg",
        "parameters": {"a2": 0.4318, "d3": 0.15005, "q0": 10},
        "joints": [
            {"type": "revolute", "alpha": 0, "a": 0, "d": 0, "theta": 0, "limits": [-160, 160]},
            {"type": "revolute", "alpha": -90, "a": 0, "d": 0, "theta": "q0", "limits": [-225, 45]},
            {"type": "revolute", "alpha": 0, "a": "a2", "d": "d3", "theta": 0},
            {"type": "prismatic", "alpha": 90, "a": 0, "d": 0.1, "theta": 30, "limits": [0, 0.5]},
        ],
        "tool": {"xyz": [0, 0, 0.05], "rpy": [180, 0, 45]},
    }
    return robot_from_mapping(data)


def odd_robot():
    """Things that stress the writer: thirds, tiny and huge numbers, powers, text that needs escaping."""
    data = {
        "name": "odd",
        "description": 'line one\nline two\ttab "quotes" \\ backslash, unicode θ₁ ✓, DEL \x7f, bell \x07',
        "convention": "standard",
        "parameters": {"L1": 1e-7, "L2": 1e22, "L3": -0.0, "big": 10**30, "third": 0.3333333333333333},
        "joints": [
            {"type": "revolute", "alpha": "1/3", "a": "L1**2/7", "d": "(L1 + L2)**-2", "theta": "-pi/7"},
            {"type": "prismatic", "alpha": "pi/2", "a": "big/3", "d": "-third", "limits": ["1/3", "2/3"]},
            {"type": "revolute", "a": "0.5/(L1 + L2)", "d": "L3*(L1 + L2)*2", "theta": "-1/(pi + 1)"},
        ],
    }
    return robot_from_mapping(data)


EXTRA = {"matrix_tool": matrix_tool_robot, "degrees": degree_robot, "odd": odd_robot}


def all_robots():
    return [pytest.param(lambda name=name: load_robot(name), id=name) for name in CATALOG] + [
        pytest.param(make, id=label) for label, make in EXTRA.items()
    ]


@pytest.mark.parametrize("make", all_robots())
def test_toml_round_trip(make):
    robot = make()
    text = robot_to_toml(robot)
    again = robot_from_toml(text, source="written.toml")
    assert again == robot
    assert again.source == "written.toml"
    assert robot_to_toml(again) == text  # writing is stable


@pytest.mark.parametrize("make", all_robots())
def test_toml_is_the_mapping(make):
    robot = make()
    assert tomllib.loads(robot_to_toml(robot)) == robot_to_mapping(robot)


@pytest.mark.parametrize("make", all_robots())
def test_mapping_round_trip(make):
    robot = make()
    data = robot_to_mapping(robot)
    assert robot_from_mapping(data) == robot
    assert robot_to_mapping(robot_from_mapping(data)) == data


@pytest.mark.parametrize("name", CATALOG)
def test_catalog_file_round_trips_through_a_real_file(name, tmp_path):
    robot = load_robot(name)
    path = tmp_path / f"copy_of_{name}.toml"
    path.write_text(robot_to_toml(robot), encoding="utf-8")
    again = load_robot(path)
    assert again == robot
    assert again.source == str(path)


def test_mapping_is_plain_data_in_radians():
    data = robot_to_mapping(degree_robot())
    assert "angle_unit" not in data
    assert data["joints"][1]["alpha"] == "-pi/2"
    assert data["joints"][0]["limits"] == ["-8*pi/9", "8*pi/9"]
    assert data["joints"][3]["theta"] == "pi/6"
    assert data["joints"][3]["d"] == 0.1
    assert data["joints"][3]["limits"] == [0, 0.5]
    assert data["joints"][1]["theta"] == "pi*q0/180"
    assert data["parameters"] == {"a2": 0.4318, "d3": 0.15005, "q0": 10}
    assert data["tool"] == {"xyz": [0, 0, 0.05], "rpy": ["pi", 0, "pi/4"]}


def test_mapping_layout():
    data = robot_to_mapping(robot_from_mapping(minimal()))
    assert data == {
        "name": "arm",
        "convention": "standard",
        "parameters": {"L1": 1, "L2": 0.5},
        "joints": [
            {"type": "revolute", "alpha": 0, "a": "L1", "d": 0, "theta": 0},
            {"type": "revolute", "alpha": 0, "a": "L2", "d": 0, "theta": 0},
        ],
    }


def test_mapping_of_a_matrix_tool():
    data = robot_to_mapping(matrix_tool_robot())
    assert data["tool"] == {"matrix": [[0, -1, 0, 0.1], [1, 0, 0, 0], [0, 0, 1, "L1"], [0, 0, 0, 1]]}
    assert data["base"] == {"xyz": [0, 0, "L1 + 1/10"], "rpy": [0, "-pi/2", 0]}


def test_toml_layout():
    text = robot_to_toml(load_robot("planar2r"))
    lines = text.splitlines()
    assert lines[0] == 'name = "planar2r"'
    assert lines[1].startswith("description = ")
    assert lines[2] == 'convention = "standard"'
    assert "[parameters]" in lines
    assert lines.count("[[joints]]") == 2
    assert text.endswith("\n")


def test_toml_keeps_exact_decimals():
    text = robot_to_toml(load_robot("puma560"))
    assert "a2 = 0.4318" in text
    assert "d3 = 0.15005" in text


def test_readme_robot_file_example_loads_and_matches_the_catalog_puma():
    from pathlib import Path

    readme = (Path(__file__).resolve().parent.parent / "README.md").read_text(encoding="utf-8")
    (example,) = re.findall(r"```toml\n(.*?)```", readme, flags=re.S)
    robot = robot_from_toml(example, source="README.md")
    puma = load_robot("puma560")
    assert [(j.alpha, j.a, j.d, j.theta) for j in robot.joints] == [(j.alpha, j.a, j.d, j.theta) for j in puma.joints]
    assert robot.tool is not None and robot.tool.xyz == (0, 0, sp.Rational(1, 10))


# --------------------------------------------------------------------------------------------- messages in plain words

@pytest.mark.parametrize("text", ["", "\n  \n", "# only a comment\n"])
def test_empty_robot_file_says_so(text, tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(RobotFileError, match=rf"^{re.escape(str(path))}: the file is empty: a robot file") as info:
        load_robot(path)
    assert "None" not in str(info.value)


@pytest.mark.parametrize(
    ("alpha", "words"),
    [
        ("sin(L1)", "function calls are not allowed in 'sin(L1)'"),
        ("L1 if L2 else 0", "conditional expressions (x if c else y) are not allowed"),
        ("f'{L1}'", "string formatting (f-strings) is not allowed"),
        ("L1 % 2", "the operator % is not allowed"),
        ("__import__('os')", "function calls are not allowed"),
    ],
)
def test_expression_errors_in_a_robot_file_use_plain_words(alpha, words):
    data = minimal()
    data["joints"][1]["alpha"] = alpha
    error = load_error(data, joint=2, field="alpha", message=re.escape(words))
    assert str(error).startswith(f"arm.toml, joint 2, field 'alpha': {words}")
    assert not re.search(r"\b(Call|IfExp|JoinedStr|BinOp)\b", str(error))


@pytest.mark.parametrize(
    ("data", "field", "message"),
    [
        ({"convention": "standard", "joints": [{"type": "revolute"}]}, "name", "'name' is required"),
        ({"name": "arm", "joints": [{"type": "revolute"}]}, "convention", "'convention' is required"),
        ({"name": "arm", "convention": "standard"}, "joints", "'joints' is required"),
        ({"name": "arm", "convention": "standard", "joints": [{"a": 1}]}, "type", "'type' is required"),
    ],
)
def test_missing_field_is_called_missing_not_none(data, field, message):
    with pytest.raises(RobotFileError, match=re.escape(f"field '{field}': {message}")) as info:
        robot_from_mapping(data, source=SOURCE)
    assert "None" not in str(info.value)


@pytest.mark.parametrize("text", ["a = " + "[" * 10_000, "a = [" + "{x = [" * 3000])
def test_toml_nested_beyond_the_parser_limits_is_a_robot_file_error(text):
    with pytest.raises(RobotFileError, match=r"^arm\.toml: invalid TOML"):
        robot_from_toml(text, source="arm.toml")

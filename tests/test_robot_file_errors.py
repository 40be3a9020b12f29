"""Robot descriptions that are refused (symjac.model.robot_file, symjac.model.robot): one message that says
what is wrong and where, in plain words."""

from __future__ import annotations

import dataclasses
import math
import re

import pytest
import sympy as sp
from robot_mappings import (
    SOURCE,
    load_error,
    minimal,
    with_joint,
)

from symjac.analysis.inverse_rates import RATE_SYMBOLS
from symjac.errors import RobotFileError, SymjacError
from symjac.kinematics.acceleration_propagation import joint_accelerations
from symjac.kinematics.jacobian import ROW_NAMES
from symjac.kinematics.propagation import joint_rate_symbols, wrench_symbols
from symjac.model.io import load_robot, robot_from_toml, robot_to_toml
from symjac.model.robot import (
    WRENCH_NAMES,
    Parameter,
    reserved_names,
)
from symjac.model.robot_file import robot_from_mapping

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


@pytest.mark.parametrize("text", ["-pi/", "exp(L1)", "L1**9", "1/0", "L1.real", "x" * 300])
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
        ("exp(L1)", "function calls are not allowed in 'exp(L1)'"),
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
